"""An EvoGym-style script run on vsrlab (issue 54): sample robots, build a world by hand, evolve
the bodies with a small genetic algorithm for a few generations (each body driven by a sine gait
in the hand-built world), then run the best body on a task's gym id and render frames headless.
Only the imports differ from an EvoGym script."""

import random

import gymnasium
import numpy as np

from vsrlab.evogym import EvoSim, EvoViewer, EvoWorld, has_actuator, is_connected, sample_robot


def flat_world(robot):
    world = EvoWorld()
    world.add_from_array("ground", np.full((1, 40), 5), x=0, y=0)
    world.add_from_array("robot", robot, x=2, y=1)
    return world


def distance(robot, steps=60):
    """How far the robot's centre moves right under a sine gait, in cells."""
    sim = EvoSim(flat_world(robot))
    n = sim.get_dim_action_space("robot")
    start = sim.object_pos_at_time(0, "robot")[0].mean()
    for t in range(steps):
        phases = np.arange(n) * 2 * np.pi / max(n, 1)
        sim.set_action("robot", 1.1 + 0.5 * np.sin(2 * np.pi * t / 20 + phases))
        if sim.step():
            return -10.0
    return float(sim.object_pos_at_time(sim.get_time(), "robot")[0].mean() - start)


def mutate(robot):
    while True:
        child = robot.copy()
        i, j = random.randrange(robot.shape[0]), random.randrange(robot.shape[1])
        child[i, j] = random.choice([0, 1, 2, 3, 4])
        if is_connected(child) and has_actuator(child):
            return child


def test_an_evogym_style_script_evolves_runs_and_renders():
    random.seed(7)
    population = [sample_robot((4, 4))[0] for _ in range(6)]
    best_per_generation = []
    for _ in range(3):
        scored = sorted(((distance(r), k) for k, r in enumerate(population)), reverse=True)
        best_per_generation.append(scored[0][0])
        parents = [population[k] for _, k in scored[:3]]
        population = parents + [mutate(p) for p in parents]
    assert all(np.isfinite(best_per_generation))
    # elitism: the best never gets worse
    assert best_per_generation == sorted(best_per_generation), best_per_generation
    best = population[0]

    env = gymnasium.make("vsrlab-evogym/Walker-v0", body=best, render_mode="rgb_array")
    obs, _ = env.reset(seed=0)
    for _ in range(10):
        obs, reward, terminated, truncated, _ = env.step(env.action_space.sample())
        assert np.isfinite(obs).all() and np.isfinite(reward)
    frame = env.render()
    assert frame.ndim == 3 and frame.shape[2] == 3 and frame.std() > 0
    viewer_frame = EvoViewer(EvoSim(flat_world(best))).render("img")
    assert viewer_frame.shape == frame.shape
