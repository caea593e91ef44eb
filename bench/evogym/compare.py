#!/usr/bin/env python3
"""Side-by-side speed comparison: EvoGym (evogym==2.0.0) vs vsrlab.

Run through run.sh, which prepares the CPython 3.10 venv that EvoGym needs.

EvoGym half: builds robots of about the same voxel count as vsrlab's bench robots
with EvoGym's low-level API (EvoWorld + EvoSim, no viewer, no rendering), drives
every actuator with a sine wave each step, and measures single-thread CPU time
with time.process_time().  The common unit is

    voxel-seconds simulated per CPU-second = n_voxels * simulated_seconds / cpu_seconds

vsrlab half: runs `cargo run --release -p vsrlab-cli -- bench --json` (or the
binary given with --vsrlab) and reads its JSON rows from stdout.

Output: a table on stdout (or JSON with --json); progress goes to stderr.
Exit status: 0 ok, 1 an EvoGym measurement failed, 3 the vsrlab numbers are
missing (its bench failed or could not be run; not with --skip-vsrlab).
"""

import os

# Single thread for any numeric library before numpy is imported.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import argparse
import json
import math
import platform
import subprocess
import sys
import time
from importlib import metadata

HERE = os.path.dirname(os.path.abspath(__file__))
REPO_ROOT = os.path.dirname(os.path.dirname(HERE))

# ---------------------------------------------------------------------------
# EvoGym's notion of time, read from the C++ sources that ship inside the
# evogym 2.0.0 wheel (evogym/simulator_cpp/SimulatorCPP/):
#   Environment.cpp, Environment::step(): physics_handler.step_rk4(0.0001)
#       -> one physics update is one RK4 step of dt = 1e-4 s
#   Sim.cpp, Sim::Sim(): physics_updates_per_step = 30, and Sim::step() runs
#       Environment::step() that many times
#       -> one EvoSim.step() = 30 * 1e-4 s = 3e-3 s of simulated time
#   evogym/envs/base.py, EvoGymBase.step(): clips the action to [0.6, 1.6],
#       calls EvoSim.set_action() and then EvoSim.step() exactly once
#       -> one gym env.step() (e.g. Walker-v0) is also 3e-3 s
#   PhysicsEngine.h: gravity = 110 (length unit: EvoSim.VOXEL_SIZE = 0.1 per voxel)
# measure_dt_check() re-derives the step length from a free fall at run time.
# ---------------------------------------------------------------------------
SUBSTEP_DT = 1e-4
SUBSTEPS_PER_STEP = 30
STEP_SECONDS = SUBSTEP_DT * SUBSTEPS_PER_STEP
GRAVITY = 110.0
VOXEL_SIZE = 0.1

# EvoGym voxel codes (same values as evogym.VOXEL_TYPES).
E, R, S, H, V, F = 0, 1, 2, 3, 4, 5

VSRLAB_DEFAULT_CMD = ["cargo", "run", "--release", "-p", "vsrlab-cli", "--", "bench", "--json"]


def log(msg):
    print(msg, file=sys.stderr, flush=True)


# ---------------------------------------------------------------------------
# Robots (arrays are top row first, as EvoGym's body arrays are)
# ---------------------------------------------------------------------------

def body_biped_4x3():
    # rigid/soft back, actuated hips, two vertical-actuator legs; bottom-middle empty
    return [
        [R, S, S, R],
        [V, H, H, V],
        [V, E, E, V],
    ]


def body_worm_10x4():
    # soft skin top and bottom, two rows of alternating H/V actuators
    mid = [H if x % 2 == 0 else V for x in range(10)]
    return [[S] * 10, list(mid), list(mid), [S] * 10]


def body_box(n):
    # soft border, checkerboard of H/V actuators inside
    rows = []
    for y in range(n):
        row = []
        for x in range(n):
            if x in (0, n - 1) or y in (0, n - 1):
                row.append(S)
            else:
                row.append(H if (x + y) % 2 == 0 else V)
        rows.append(row)
    return rows


# name -> (body builder, terrain); names match vsrlab's bench robot names
ROBOTS = {
    "biped-4x3": (body_biped_4x3, "flat"),
    "worm-10x4": (body_worm_10x4, "flat"),
    "box-5x5": (lambda: body_box(5), "hilly"),
    "box-10x10": (lambda: body_box(10), "flat"),
}
DEFAULT_ROBOTS = "biped-4x3,worm-10x4,box-5x5,box-10x10"


def make_ground(np, terrain, width):
    """Ground as an EvoGym object of FIXED voxels; returns (array, column heights)."""
    if terrain == "flat":
        heights = [1] * width
    elif terrain == "hilly":
        # bumps 1..3 voxels (0.1..0.3) high, period 8 voxels
        heights = [1 + int(round(1.0 + math.sin(2.0 * math.pi * x / 8.0))) for x in range(width)]
    else:
        raise ValueError("unknown terrain %r" % terrain)
    top = max(heights)
    grid = np.zeros((top, width), dtype=int)
    for x, h in enumerate(heights):
        grid[top - h:, x] = F
    return grid, heights


# ---------------------------------------------------------------------------
# EvoGym measurement
# ---------------------------------------------------------------------------

def import_evogym():
    import numpy as np
    import evogym
    from evogym import EvoSim, EvoWorld

    # EvoSim prints a version banner through C++ std::cout on first use; skip it.
    EvoSim._has_displayed_version = True
    assert evogym.VOXEL_TYPES == {"EMPTY": E, "RIGID": R, "SOFT": S, "H_ACT": H, "V_ACT": V, "FIXED": F}
    return np, EvoWorld, EvoSim


def measure_dt_check(np, EvoWorld, EvoSim, n_steps=20):
    """Drop one rigid voxel in empty space and infer the simulated time per step."""
    world = EvoWorld()
    world.add_from_array("probe", np.array([[R]]), 5, 50)
    sim = EvoSim(world)
    y0 = sim.object_pos_at_time(0, "probe")[1].mean()
    for _ in range(n_steps):
        sim.step()
    y1 = sim.object_pos_at_time(sim.get_time(), "probe")[1].mean()
    drop = (y0 - y1) * VOXEL_SIZE  # EvoSim reports positions in voxels
    implied = math.sqrt(2.0 * drop / GRAVITY) / n_steps
    return {
        "steps": n_steps,
        "drop": drop,
        "predicted_drop_no_drag": 0.5 * GRAVITY * (n_steps * STEP_SECONDS) ** 2,
        "implied_step_seconds": implied,
        "ok": abs(implied / STEP_SECONDS - 1.0) < 0.02,
    }


def measure_robot(np, EvoWorld, EvoSim, name, args):
    build, terrain = ROBOTS[name]
    body = np.array(build(), dtype=int)
    height, width = body.shape
    n_voxels = int(np.count_nonzero(body))

    ground_w = width + 2 * args.ground_margin
    ground, heights = make_ground(np, terrain, ground_w)
    x0 = args.ground_margin
    y0 = max(heights[x0:x0 + width])

    world = EvoWorld()
    world.add_from_array("ground", ground, 0, 0)
    world.add_from_array("robot", body, x0, y0)
    sim = EvoSim(world)

    act_idx = sim.get_actuator_indices("robot")
    n_act = len(act_idx)
    # actuator index = position in body.flatten(); travelling wave along x,
    # vertical actuators half a period behind horizontal ones
    flat = body.flatten()
    phases = np.array(
        [-2.0 * math.pi * (i % width) / width + (math.pi if flat[i] == V else 0.0) for i in act_idx]
    )
    omega = 2.0 * math.pi * args.freq
    n_points = int(sim.pos_at_time(0).shape[1])
    n_ground = int(np.count_nonzero(ground))
    com_x0 = float(sim.object_pos_at_time(0, "robot")[0].mean())

    def action(k):
        return 1.0 + args.amp * np.sin(omega * k * STEP_SECONDS + phases)

    # warm-up (not timed)
    for k in range(args.warmup_steps):
        sim.set_action("robot", action(k))
        if sim.step():
            break
    sim.reset()

    steps = ok_steps = unstable = episodes = ep_step = 0
    max_drift = 0.0
    fell_off = False
    target = args.evogym_seconds
    wall0 = time.perf_counter()
    cpu0 = time.process_time()
    while True:
        sim.set_action("robot", action(ep_step))
        bad = sim.step()
        steps += 1
        ep_step += 1
        if bad:
            unstable += 1  # EvoSim aborted this step (robot self-collision)
        else:
            ok_steps += 1
        if bad or ep_step >= args.episode_steps:
            pos = sim.object_pos_at_time(sim.get_time(), "robot")
            max_drift = max(max_drift, abs(float(pos[0].mean()) - com_x0))
            if float(pos[1].min()) < 0.0:
                fell_off = True
            sim.reset()
            episodes += 1
            ep_step = 0
        if steps % 25 == 0 and time.process_time() - cpu0 >= target:
            break
    cpu = time.process_time() - cpu0
    wall = time.perf_counter() - wall0
    if ep_step:
        episodes += 1

    sim_seconds = ok_steps * STEP_SECONDS
    return {
        "robot": name,
        "terrain": terrain,
        "voxels": n_voxels,
        "mode": "single",
        "threads": 1,
        "episodes": episodes,
        "steps": steps,
        "cpu_seconds": cpu,
        "wall_seconds": wall,
        "steps_per_s": steps / cpu,
        "voxel_steps_per_s": n_voxels * steps / cpu,
        "voxel_seconds_per_cpu_s": n_voxels * sim_seconds / cpu,
        # extra context
        "grid": "%dx%d" % (width, height),
        "actuators": n_act,
        "ground_voxels": n_ground,
        "point_masses": n_points,
        "sim_seconds": sim_seconds,
        "sim_seconds_per_cpu_s": sim_seconds / cpu,
        "unstable_steps": unstable,
        "max_com_drift_voxels": max_drift,
        "left_ground": fell_off,
    }


def run_evogym(args, names):
    np, EvoWorld, EvoSim = import_evogym()
    info = {
        "package_version": metadata.version("evogym"),
        "python": platform.python_version(),
        "api": "evogym.EvoWorld + evogym.EvoSim (no viewer, no rendering)",
        "substep_dt_seconds": SUBSTEP_DT,
        "substeps_per_step": SUBSTEPS_PER_STEP,
        "step_seconds": STEP_SECONDS,
        "gravity": GRAVITY,
        "voxel_size": VOXEL_SIZE,
        "controller": "a_i = 1 + %g*sin(2*pi*%g*t + phase_i), every step" % (args.amp, args.freq),
        "episode_steps": args.episode_steps,
        "warmup_steps": args.warmup_steps,
        "target_cpu_seconds_per_robot": args.evogym_seconds,
        "ground_margin_voxels": args.ground_margin,
    }
    dt = measure_dt_check(np, EvoWorld, EvoSim)
    info["dt_check"] = dt
    log("[evogym] step = %d x %g s = %g s simulated; free-fall check implies %.5f s/step (%s)"
        % (SUBSTEPS_PER_STEP, SUBSTEP_DT, STEP_SECONDS, dt["implied_step_seconds"],
           "ok" if dt["ok"] else "MISMATCH"))
    rows, failed = [], False
    for name in names:
        log("[evogym] %s: measuring ~%.1f CPU-s ..." % (name, args.evogym_seconds))
        try:
            row = measure_robot(np, EvoWorld, EvoSim, name, args)
        except Exception as exc:  # keep going with the other robots
            failed = True
            log("[evogym] %s: FAILED: %r" % (name, exc))
            rows.append({"robot": name, "error": repr(exc)})
            continue
        rows.append(row)
        log("[evogym] %s: %d voxels, %d steps in %.2f CPU-s (%.2f wall-s), %.1f voxel*s/CPU-s, "
            "sim %.2f s over %d episodes, %d unstable steps, max drift %.1f voxels%s"
            % (name, row["voxels"], row["steps"], row["cpu_seconds"], row["wall_seconds"],
               row["voxel_seconds_per_cpu_s"], row["sim_seconds"], row["episodes"],
               row["unstable_steps"], row["max_com_drift_voxels"],
               ", LEFT THE GROUND" if row["left_ground"] else ""))
    info["rows"] = rows
    return info, failed


# ---------------------------------------------------------------------------
# vsrlab
# ---------------------------------------------------------------------------

def parse_vsrlab_json(text):
    text = text.strip()
    try:
        return json.loads(text)
    except ValueError:
        pass
    # tolerate chatter before the JSON document: try from each line that opens an object
    lines = text.splitlines()
    for i, line in enumerate(lines):
        if line.lstrip().startswith("{"):
            try:
                return json.loads("\n".join(lines[i:]))
            except ValueError:
                continue
    raise ValueError("no JSON object found on stdout")


def run_vsrlab(args):
    if args.vsrlab:
        cmd = [args.vsrlab, "bench", "--json"]
    else:
        cmd = list(VSRLAB_DEFAULT_CMD)
    if args.duration is not None:
        cmd += ["--duration", args.duration]
    result = {"ok": False, "skipped": False, "command": cmd, "cwd": REPO_ROOT, "rows": [], "error": None}
    log("[vsrlab] running: %s  (in %s)" % (" ".join(cmd), REPO_ROOT))
    t0 = time.perf_counter()
    try:
        proc = subprocess.run(cmd, cwd=REPO_ROOT, stdout=subprocess.PIPE, stdin=subprocess.DEVNULL,
                              timeout=args.vsrlab_timeout)
    except FileNotFoundError as exc:
        result["error"] = "could not start %r: %s" % (cmd[0], exc)
        return result
    except subprocess.TimeoutExpired:
        result["error"] = "timed out after %d s" % args.vsrlab_timeout
        return result
    result["seconds"] = time.perf_counter() - t0
    result["returncode"] = proc.returncode
    out = proc.stdout.decode("utf-8", "replace")
    if proc.returncode != 0:
        result["error"] = "exited with status %d" % proc.returncode
        return result
    try:
        doc = parse_vsrlab_json(out)
    except ValueError as exc:
        result["error"] = "could not parse its stdout as JSON (%s); first 200 chars: %r" % (exc, out[:200])
        return result
    rows = doc.get("rows") if isinstance(doc, dict) else None
    if not isinstance(rows, list) or not rows:
        result["error"] = "JSON has no non-empty 'rows' list"
        return result
    result["rows"] = rows
    result["ok"] = True
    return result


def is_single(row):
    return row.get("mode") == "single" and row.get("threads", 1) in (1, None)


def compare(evo_rows, vsr_rows):
    out = []
    seen = set()
    for er in evo_rows:
        name = er["robot"]
        seen.add(name)
        cands = [r for r in vsr_rows if r.get("robot") == name and is_single(r)]
        same_terrain = [r for r in cands if r.get("terrain") == er.get("terrain")]
        vr = (same_terrain or cands or [None])[0]
        e_val = er.get("voxel_seconds_per_cpu_s")
        v_val = vr.get("voxel_seconds_per_cpu_s") if vr else None
        out.append({
            "robot": name,
            "evogym_voxels": er.get("voxels"),
            "vsrlab_voxels": vr.get("voxels") if vr else None,
            "evogym_terrain": er.get("terrain"),
            "vsrlab_terrain": vr.get("terrain") if vr else None,
            "evogym_voxel_seconds_per_cpu_s": e_val,
            "vsrlab_voxel_seconds_per_cpu_s": v_val,
            "ratio_vsrlab_over_evogym": (v_val / e_val) if (e_val and v_val is not None) else None,
        })
    for vr in vsr_rows:
        name = vr.get("robot")
        if name in seen or not is_single(vr):
            continue
        seen.add(name)
        out.append({
            "robot": name,
            "evogym_voxels": None,
            "vsrlab_voxels": vr.get("voxels"),
            "evogym_terrain": None,
            "vsrlab_terrain": vr.get("terrain"),
            "evogym_voxel_seconds_per_cpu_s": None,
            "vsrlab_voxel_seconds_per_cpu_s": vr.get("voxel_seconds_per_cpu_s"),
            "ratio_vsrlab_over_evogym": None,
        })
    return out


# ---------------------------------------------------------------------------
# Output
# ---------------------------------------------------------------------------

def fmt(v, spec="%.1f"):
    if v is None:
        return "-"
    if isinstance(v, (int, float)):
        return spec % v
    return str(v)


def print_table(out, evo, vsr, comparison):
    w = out.write
    w("EvoGym %s (Python %s), %s\n" % (evo["package_version"], evo["python"], evo["api"]))
    dt = evo["dt_check"]
    w("EvoGym time step: one EvoSim.step() (= one gym env.step()) = %d RK4 substeps x %g s = %g s simulated\n"
      % (SUBSTEPS_PER_STEP, SUBSTEP_DT, STEP_SECONDS))
    w("  run-time check: free fall of one voxel over %d steps implies %.5f s/step (%s)\n"
      % (dt["steps"], dt["implied_step_seconds"], "ok" if dt["ok"] else "MISMATCH with the source constants"))
    w("unit: voxel*s/CPU-s = voxels x simulated seconds / CPU seconds (single thread, time.process_time())\n\n")

    headers = ["robot", "voxels E/V", "terrain E/V", "EvoGym vox*s/CPU-s", "vsrlab vox*s/CPU-s", "vsrlab/EvoGym"]
    body = []
    for c in comparison:
        body.append([
            c["robot"],
            "%s/%s" % (fmt(c["evogym_voxels"], "%d"), fmt(c["vsrlab_voxels"], "%d")),
            "%s/%s" % (fmt(c["evogym_terrain"]), fmt(c["vsrlab_terrain"])),
            fmt(c["evogym_voxel_seconds_per_cpu_s"]),
            fmt(c["vsrlab_voxel_seconds_per_cpu_s"]),
            fmt(c["ratio_vsrlab_over_evogym"], "%.2fx"),
        ])
    widths = [max(len(headers[i]), *(len(r[i]) for r in body)) if body else len(headers[i])
              for i in range(len(headers))]
    line = "  ".join(h.ljust(widths[i]) if i < 3 else h.rjust(widths[i]) for i, h in enumerate(headers))
    w(line + "\n" + "-" * len(line) + "\n")
    for r in body:
        w("  ".join(c.ljust(widths[i]) if i < 3 else c.rjust(widths[i]) for i, c in enumerate(r)) + "\n")

    errs = [r for r in evo["rows"] if "error" in r]
    for r in errs:
        w("EvoGym %s FAILED: %s\n" % (r["robot"], r["error"]))
    w("\nEvoGym details (per robot): ")
    w("; ".join("%s %s %d act, %d ground voxels, %d steps, %.2f CPU-s, %d unstable"
                % (r["robot"], r["grid"], r["actuators"], r["ground_voxels"], r["steps"], r["cpu_seconds"],
                   r["unstable_steps"])
                for r in evo["rows"] if "error" not in r) + "\n")

    if vsr.get("skipped"):
        w("\nvsrlab: skipped (--skip-vsrlab)\n")
    elif not vsr["ok"]:
        w("\nvsrlab numbers MISSING: `%s` failed: %s\n" % (" ".join(vsr["command"]), vsr["error"]))
    else:
        par = [r for r in vsr["rows"] if not is_single(r)]
        if par:
            w("\nvsrlab multi-thread rows (not compared; EvoGym is measured single-thread only):\n")
            for r in par:
                w("  %s %s %s threads=%s: %s voxel*s/CPU-s, %s steps/s\n"
                  % (r.get("robot"), r.get("terrain"), r.get("mode"), r.get("threads"),
                     fmt(r.get("voxel_seconds_per_cpu_s")), fmt(r.get("steps_per_s"))))
    out.flush()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", action="store_true", help="print machine-readable JSON instead of the table")
    ap.add_argument("--skip-vsrlab", action="store_true", help="measure EvoGym only")
    ap.add_argument("--vsrlab", metavar="BIN", help="prebuilt vsrlab CLI binary (default: cargo run --release -p vsrlab-cli)")
    ap.add_argument("--duration", metavar="SECONDS", help="passed through unchanged to `vsrlab bench --duration`")
    ap.add_argument("--vsrlab-timeout", type=int, default=1800, metavar="S",
                    help="give up on the vsrlab command after S seconds, build included (default 1800)")
    ap.add_argument("--robots", default=DEFAULT_ROBOTS, help="comma list of EvoGym robots (default: %(default)s)")
    ap.add_argument("--evogym-seconds", type=float, default=5.0, metavar="S",
                    help="CPU seconds to measure each EvoGym robot for (default 5)")
    ap.add_argument("--warmup-steps", type=int, default=300, help="untimed steps before measuring (default 300)")
    ap.add_argument("--episode-steps", type=int, default=1000,
                    help="steps per episode before EvoSim.reset() (default 1000 = 3 s simulated)")
    ap.add_argument("--ground-margin", type=int, default=10, metavar="VOXELS",
                    help="ground extends this many voxels beyond each side of the robot (default 10)")
    ap.add_argument("--freq", type=float, default=2.0, help="actuation frequency in Hz of EvoGym time (default 2)")
    ap.add_argument("--amp", type=float, default=0.4, help="actuation amplitude around 1.0 (default 0.4)")
    args = ap.parse_args(argv)

    names = [n.strip() for n in args.robots.split(",") if n.strip()]
    unknown = [n for n in names if n not in ROBOTS]
    if unknown:
        ap.error("unknown robot(s) %s; known: %s" % (", ".join(unknown), ", ".join(ROBOTS)))
    if args.duration is not None:
        try:
            if not float(args.duration) > 0:
                raise ValueError
        except ValueError:
            ap.error("--duration must be a positive number of seconds")
    if not 0.0 < args.amp <= 0.6:
        ap.error("--amp must be in (0, 0.6] so actions stay inside EvoGym's [0.6, 1.6]")

    # EvoGym's C++ code writes to std::cout (fd 1); send fd 1 to stderr and keep
    # the real stdout only for our result, so --json output stays clean.
    sys.stdout.flush()
    real_stdout = os.fdopen(os.dup(1), "w", encoding="utf-8")
    os.dup2(2, 1)

    evo, evo_failed = run_evogym(args, names)
    if args.skip_vsrlab:
        vsr = {"ok": False, "skipped": True, "command": None, "rows": [], "error": "skipped (--skip-vsrlab)"}
    else:
        vsr = run_vsrlab(args)
        if not vsr["ok"]:
            log("[vsrlab] FAILED: %s -- vsrlab numbers are missing" % vsr["error"])
    comparison = compare([r for r in evo["rows"] if "error" not in r], vsr["rows"])

    if args.json:
        doc = {"unit": "voxel_seconds_per_cpu_s = voxels * simulated_seconds / cpu_seconds",
               "evogym": evo, "vsrlab": vsr, "comparison": comparison}
        real_stdout.write(json.dumps(doc, indent=2) + "\n")
        real_stdout.flush()
    else:
        print_table(real_stdout, evo, vsr, comparison)

    if evo_failed:
        return 1
    if not vsr["ok"] and not vsr.get("skipped"):
        return 3
    return 0


if __name__ == "__main__":
    sys.exit(main())
