"""EvoGym's own task environments, side by side with vsrlab's (issue 33).

Runs each of the four tasks of thesis ch. 5.2 in EvoGym (gymnasium.make, a full 5x5 body of
horizontal actuators) with the square-wave gait of crates/tasks/examples/evogym_speed.rs, and
prints per task: the observation and action sizes, the summed reward and steps of one episode
(fidelity: the same gait in vsrlab's EvoGym model should give the same rewards), and the CPU
time per env.step() over `--steps` steps (speed).

    bench/evogym/run.sh --skip-vsrlab                  # once, to create bench/evogym/.venv
    bench/evogym/.venv/bin/python bench/evogym/tasks.py
    cargo run --release -p vsrlab-tasks --example evogym_speed 1000
"""
import argparse
import time

import gymnasium as gym
import numpy as np
import evogym.envs  # noqa: F401  (registers the environments)

TASKS = ["Walker-v0", "BridgeWalker-v0", "BeamToppler-v0", "CaveCrawler-v0"]


class FixedOffsets:
    """Stands in for Python's global `random` in EvoGym's manipulate module: Catcher-v0 draws
    its package's and pegs' offsets (x, then y) from it at every reset, unseeded. These are the
    offsets vsrlab draws for seed 0 (`--example evogym_speed 1 Catcher` prints its world)."""

    def __init__(self, ox, oy):
        self.values, self.drawn = (ox, oy), 0

    def randint(self, low, high):
        value = self.values[self.drawn % 2]
        self.drawn += 1
        assert low <= value <= high, (low, value, high)
        return value


class FixedGoals:
    """Stands in for Python's global `random` in EvoGym's multi_goal module: BidirectionalWalker-v0
    draws its goals from it at every reset, unseeded. These are the goals vsrlab draws for a seed,
    given in order; every draw of the sequence gives them again."""

    def __init__(self, goals):
        self.goals, self.drawn = goals, 0

    def randrange(self, low, high):
        goal = self.goals[self.drawn % len(self.goals)]
        self.drawn += 1
        assert low <= goal < high, (low, goal, high)
        return goal


def gait(t, n):
    return np.array([1.6 if (t + 5 * (i % 5)) % 20 < 10 else 0.6 for i in range(n)])


def episode(name, steps):
    env = gym.make(name, body=np.full((5, 5), 3))
    env.reset(seed=0)
    total, k = 0.0, 0
    for t in range(steps):
        _, r, term, trunc, _ = env.step(gait(t, env.action_space.shape[0]))
        total, k = total + r, k + 1
        if term or trunc:
            break
    return env, total, k


def speed(name, steps):
    env = gym.make(name, body=np.full((5, 5), 3))
    env.reset(seed=0)
    actions = [gait(t, env.action_space.shape[0]) for t in range(20)]
    c0 = time.process_time()
    for t in range(steps):
        _, _, term, trunc, _ = env.step(actions[t % 20])
        if term or trunc:
            env.reset(seed=0)
    return 1e6 * (time.process_time() - c0) / steps


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--steps", type=int, default=1000, help="env steps timed per task")
    parser.add_argument("--tasks", default=",".join(TASKS), help="comma-separated EvoGym ids (default: ch. 5.2's four)")
    parser.add_argument("--catcher-offsets", default="1,4", help="Catcher-v0's offsets ox,oy (vsrlab's seed 0: 1,4)")
    parser.add_argument(
        "--bidirectional-goals",
        default=None,
        help="BidirectionalWalker-v0's goals in cells, comma-separated (vsrlab's seed 0: `--example evogym_speed 1 Bidirectional` prints them)",
    )
    args = parser.parse_args()
    import evogym.envs.manipulate as manipulate
    import evogym.envs.multi_goal as multi_goal

    manipulate.random = FixedOffsets(*(int(v) for v in args.catcher_offsets.split(",")))
    if args.bidirectional_goals:
        multi_goal.random = FixedGoals([int(float(g)) for g in args.bidirectional_goals.split(",")])
    for name in args.tasks.split(","):
        length = gym.spec(name).max_episode_steps
        env, total, k = episode(name, length)
        us = speed(name, args.steps)
        print(
            f"{name:16s} obs {env.observation_space.shape[0]:3d}  actions {env.action_space.shape[0]:2d}  "
            f"reward {total:+.9f} over {k} steps  {us:7.1f} us/step (CPU)"
        )


if __name__ == "__main__":
    main()
