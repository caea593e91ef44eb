#!/usr/bin/env python3
"""The PSA ring on Box2D (pybox2d 2.3.10 from PyPI), written from the facts in psa-model.md:
a reference for vsrlab's PSA physics (the inflation protocol) and for its speed.

Not the original code: the ring, the joints, the pressure routine and the loop are written here
from the published description (n 1x1 boxes of density 2500, friction 10, fixed rotation, on a
circle of radius r; distance joints at 8 Hz, damping 0.3; pressure p*L/2 on both ends of each
edge along its outward normal, applied after each world step; Step(1/60, 8, 3); gravity -10).

  inflate SIZE [--actual-length]   φ per step of the inflation protocol, as CSV on stdout
  speed SIZE [--steps N]           steps/s of a random-control episode (physics + pressure +
                                   a random controller in Python, no sensors, no MLP), and the
                                   time inside world.Step alone during that episode (the ceiling
                                   of any Box2D-based PSA)
"""
import math
import random
import sys
import time

from Box2D import b2World, b2PolygonShape, b2EdgeShape, b2FixtureDef

SIZES = {"small": (10, 5.0, 50.0), "medium": (15, 7.5, 75.0), "large": (20, 10.0, 100.0)}
R_GAS, MOLAR, TEMP = 8.314462618, 28.0134, 288.20


def build(size):
    n, r, mass = SIZES[size]
    world = b2World(gravity=(0, -10), doSleep=True)
    ground = world.CreateStaticBody()
    ground.CreateFixture(b2FixtureDef(shape=b2EdgeShape(vertices=[(-500, 0), (500, 0)]), friction=0.2))
    bodies = []
    for i in range(n):
        a = 2 * math.pi * i / n
        b = world.CreateDynamicBody(position=(r + r * math.cos(a), r + 1 + r * math.sin(a)), fixedRotation=True)
        b.CreateFixture(b2FixtureDef(shape=b2PolygonShape(box=(0.5, 0.5)), density=2500, friction=10))
        bodies.append(b)
    rest = 2 * r * math.sin(math.pi / n)
    joints = []
    for i in range(n):
        j = world.CreateDistanceJoint(bodyA=bodies[i], bodyB=bodies[(i + 1) % n],
                                      anchorA=bodies[i].position, anchorB=bodies[(i + 1) % n].position,
                                      frequencyHz=8.0, dampingRatio=0.3, collideConnected=False)
        joints.append(j)
    n_r_t = mass * MOLAR * R_GAS * TEMP  # the original's amount n = m*M
    p_max = 1.25 * n_r_t / (math.pi * r * r)
    return world, bodies, joints, rest, p_max, r


def area(points):
    s = 0.0
    for i in range(len(points)):
        x1, y1 = points[i]
        x2, y2 = points[(i + 1) % len(points)]
        s += x1 * y2 - x2 * y1
    return 0.5 * s


def apply_pressure(bodies, joints, p, actual):
    pts = [(b.position.x, b.position.y) for b in bodies]
    side = 1.0 if area(pts) > 0 else -1.0
    n = len(bodies)
    for i in range(n):
        (x1, y1), (x2, y2) = pts[i], pts[(i + 1) % n]
        ex, ey = x2 - x1, y2 - y1
        length = math.hypot(ex, ey)
        if length < 1e-12:
            continue
        nx, ny = side * ey / length, -side * ex / length
        L = length if actual else joints[i].length
        f = (0.5 * p * L * nx, 0.5 * p * L * ny)
        bodies[i].ApplyForceToCenter(f, True)
        bodies[(i + 1) % n].ApplyForceToCenter(f, True)


def inflate(size, actual, steps=1200):
    world, bodies, joints, rest, p_max, r = build(size)
    p = 0.0
    print("step,pressure_ratio,phi")
    for k in range(steps):
        world.Step(1 / 60, 8, 3)
        for j in joints:
            j.length = rest
        p = min(p + p_max / 100, p_max)
        apply_pressure(bodies, joints, p, actual)
        phi = abs(area([(b.position.x, b.position.y) for b in bodies])) / (math.pi * r * r)
        print(f"{k + 1},{p / p_max:.4f},{phi:.5f}")


def speed(size, steps):
    world, bodies, joints, rest, p_max, r = build(size)
    rng = random.Random(0)
    p = p_max / 1.25
    in_step = 0.0
    t0 = time.perf_counter()
    for _ in range(steps):
        s0 = time.perf_counter()
        world.Step(1 / 60, 8, 3)
        in_step += time.perf_counter() - s0
        for j in joints:
            j.length = rest * (1 + 0.25 * rng.uniform(-1, 1))
        p = min(max(p + rng.uniform(-1, 1) * 100, 0.2 * p_max), p_max)
        apply_pressure(bodies, joints, p, False)
    elapsed = time.perf_counter() - t0
    print(f"box2d+python {size}: {steps} steps in {elapsed:.3f} s = {steps / elapsed:.0f} steps/s")
    print(f"box2d-step-only {size}: {steps} steps in {in_step:.3f} s = {steps / in_step:.0f} steps/s")


if __name__ == "__main__":
    args = sys.argv[1:]
    if len(args) >= 2 and args[0] == "inflate":
        inflate(args[1], "--actual-length" in args)
    elif len(args) >= 2 and args[0] == "speed":
        n = int(args[args.index("--steps") + 1]) if "--steps" in args else 1800
        speed(args[1], n)
    else:
        sys.exit(__doc__)
