"""Episodes that EvoGym ends as unstable (a robot folded into itself), to check that vsrlab ends
the same episodes at the same step (issue 33).

Draws random 5x5 bodies (empty 45 %, soft 15 %, each actuator 20 %; connected, with an actuator)
and drives each in EvoGym with extreme actions (every actuator 0.6 or 1.6, each with probability
one half from a splitmix64 stream seeded with the run's index, held for `--hold` steps), for up to
`--steps` steps. Writes every run, with the step at which EvoGym reported it unstable (or null), to
a JSON file; `crates/tasks/examples/evogym_instability.rs` replays them.

    bench/evogym/.venv/bin/python bench/evogym/instability.py --out target/evogym-instability.json
    cargo run --release -p vsrlab-tasks --example evogym_instability target/evogym-instability.json
"""
import argparse
import json
import time

import gymnasium as gym
import numpy as np
import evogym.envs  # noqa: F401  (registers the environments)
from evogym import has_actuator, is_connected

from trajectories import SplitMix64


def random_body(rs):
    while True:
        body = rs.choice([0, 2, 3, 4], size=(5, 5), p=[0.45, 0.15, 0.2, 0.2])
        if is_connected(body) and has_actuator(body):
            return body


def run(task, body, seed, hold, steps):
    env = gym.make(task, body=body)
    env.reset(seed=0)
    rng = SplitMix64(seed)
    n = env.action_space.shape[0]
    action = None
    for t in range(steps):
        if t % hold == 0:
            action = np.array([0.6 if rng.uniform() < 0.5 else 1.6 for _ in range(n)])
        _, reward, terminated, truncated, _ = env.step(action)
        if terminated:
            return t + 1, float(reward)
        if truncated:
            break
    return None, None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--task", default="Walker-v0")
    parser.add_argument("--runs", type=int, default=150)
    parser.add_argument("--steps", type=int, default=300)
    parser.add_argument("--hold", type=int, default=15)
    parser.add_argument("--seed", type=int, default=2, help="numpy seed of the bodies")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    rs = np.random.RandomState(args.seed)
    runs, c0 = [], time.process_time()
    for k in range(args.runs):
        body = random_body(rs)
        step, reward = run(args.task, body, k, args.hold, args.steps)
        rows = "/".join("".join(str(int(c)) for c in row) for row in body)
        runs.append({"seed": k, "body": rows, "unstable_step": step, "reward": reward})
    unstable = sum(r["unstable_step"] is not None for r in runs)
    print(f"{args.task}: {unstable} of {args.runs} runs unstable, {time.process_time() - c0:.1f} CPU s")
    with open(args.out, "w") as f:
        json.dump({"evogym": "2.0.0", "task": args.task, "steps": args.steps, "hold": args.hold,
                   "actions": [0.6, 1.6], "runs": runs}, f)


if __name__ == "__main__":
    main()
