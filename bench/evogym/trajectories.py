"""EvoGym's trajectories under random actions, to compare with vsrlab's (issue 33).

For each of the four tasks of thesis ch. 5.2 and one robot per task, runs `--sequences` episodes
in EvoGym, each driven by its own random action sequence (every action of every step uniform in
[0.6, 1.6], drawn from a splitmix64 stream that
`crates/tasks/examples/evogym_trajectories.rs` reproduces bit for bit), and records per step the
robot's centre of mass (mean of its point masses), the reward and the end flags. Writes one JSON
file; the Rust example replays the same actions in vsrlab and reports the deviations.

    bench/evogym/run.sh --skip-vsrlab        # once, to create bench/evogym/.venv
    bench/evogym/.venv/bin/python bench/evogym/trajectories.py --out target/evogym-trajectories.json
    cargo run --release -p vsrlab-tasks --example evogym_trajectories target/evogym-trajectories.json
"""
import argparse
import json
import time

import gymnasium as gym
import numpy as np
import evogym.envs  # noqa: F401  (registers the environments)

MASK = (1 << 64) - 1

# One robot per task, rows top first (EvoGym's array order). The walker is the full body of
# horizontal actuators; the others mix every robot material.
ROBOTS = {
    "Walker-v0": ["33333", "33333", "33333", "33333", "33333"],
    "BridgeWalker-v0": ["13231", "34443", "32023", "33033", "40004"],
    "BeamToppler-v0": ["22222", "34443", "31013", "30003", "40004"],
    "CaveCrawler-v0": ["11111", "34343", "23432", "30003", "30003"],
}
LENGTHS = {"Walker-v0": 500, "BridgeWalker-v0": 500, "BeamToppler-v0": 1000, "CaveCrawler-v0": 1000}


class SplitMix64:
    """The splitmix64 generator; `uniform` gives the top 53 bits as a float in [0, 1)."""

    def __init__(self, seed):
        self.state = seed & MASK

    def next(self):
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        return z ^ (z >> 31)

    def uniform(self):
        return (self.next() >> 11) / float(1 << 53)


def sequence_seed(task_index, sequence):
    return 1000 * (task_index + 1) + sequence


def run(name, rows, length, seed):
    body = np.array([[int(c) for c in row] for row in rows])
    env = gym.make(name, body=body)
    env.reset(seed=0)
    inner = env.unwrapped
    rng = SplitMix64(seed)
    n = env.action_space.shape[0]
    com, rewards, ends = [], [], None

    def centre():
        pos = inner.object_pos_at_time(inner.get_time(), "robot")
        return [float(pos[0].mean()), float(pos[1].mean())]

    com.append(centre())
    for t in range(length):
        action = np.array([0.6 + rng.uniform() for _ in range(n)])
        _, r, term, trunc, _ = env.step(action)
        rewards.append(float(r))
        com.append(centre())
        if term or trunc:
            ends = {"step": t + 1, "terminated": bool(term), "truncated": bool(trunc)}
            break
    return {"seed": seed, "com": com, "reward": rewards, "end": ends}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sequences", type=int, default=20, help="random action sequences per task")
    parser.add_argument("--out", required=True, help="JSON file to write")
    args = parser.parse_args()
    tasks = []
    for k, (name, rows) in enumerate(ROBOTS.items()):
        c0 = time.process_time()
        runs = [run(name, rows, LENGTHS[name], sequence_seed(k, s)) for s in range(args.sequences)]
        print(f"{name}: {args.sequences} sequences in {time.process_time() - c0:.1f} CPU s")
        tasks.append({"task": name, "body": "/".join(rows), "runs": runs})
    with open(args.out, "w") as f:
        json.dump({"evogym": "2.0.0", "action_range": [0.6, 1.6], "tasks": tasks}, f)


if __name__ == "__main__":
    main()
