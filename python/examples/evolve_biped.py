"""Evolve a walking biped from Python, no notebook: a plain (μ, λ) evolution strategy in NumPy
that calls vsrlab only to evaluate (one call per generation, every core, GIL released).

    python python/examples/evolve_biped.py --generations 60 --out biped.robot.json
    vsrlab simulate --robot biped.robot.json --video biped.gif

The experiment file fixes the robot (a 4x3 biped with the thesis's distributed MLP) and the task
(10 s on flat ground, fitness = velocity); the optimiser is yours.
"""

import argparse
import time
from pathlib import Path

import numpy as np

import vsrlab

CONFIG = Path(__file__).resolve().parents[2] / "experiments" / "quickstart.toml"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--generations", type=int, default=60)
    p.add_argument("--population", type=int, default=40)
    p.add_argument("--sigma", type=float, default=0.35)
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--out", default="biped.robot.json", help="where the best robot is saved")
    a = p.parse_args()

    rng = np.random.default_rng(a.seed)
    genes = vsrlab.genotype_length(CONFIG)
    parents = a.population // 4
    mean = rng.uniform(-1, 1, genes)
    best, best_fitness = mean, -np.inf
    start = time.perf_counter()
    for generation in range(a.generations):
        population = mean + a.sigma * rng.standard_normal((a.population, genes))
        fitness = vsrlab.evaluate_batch(CONFIG, population)
        fitness = np.nan_to_num(fitness, nan=-np.inf)  # a failed evaluation is the worst
        order = np.argsort(-fitness)
        mean = population[order[:parents]].mean(axis=0)
        if fitness[order[0]] > best_fitness:
            best, best_fitness = population[order[0]], fitness[order[0]]
        print(f"generation {generation + 1:3d}  best {best_fitness:.3f}  mean {np.mean(fitness[np.isfinite(fitness)]):.3f}")
    seconds = time.perf_counter() - start
    robot = vsrlab.robot_of(CONFIG, best)
    robot.save(a.out, note=f"evolved by python/examples/evolve_biped.py, velocity {best_fitness:.3f}")
    check = vsrlab.simulate(robot, task=str(CONFIG))
    print(f"{a.generations * a.population} evaluations in {seconds:.1f} s; best velocity {best_fitness:.3f} "
          f"(replayed: {check['velocity']:.3f}); saved {a.out}")


if __name__ == "__main__":
    main()
