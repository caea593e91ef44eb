"""Drive vsrlab from pycma (``pip install cma``): CMA-ES asks, vsrlab evaluates the whole
population in one call, CMA-ES is told.

    python python/examples/pycma_biped.py --evaluations 2000 --out pycma-biped.robot.json

pycma minimises, so it is told the negative velocity.
"""

import argparse
from pathlib import Path

import cma
import numpy as np

import vsrlab

CONFIG = Path(__file__).resolve().parents[2] / "experiments" / "quickstart.toml"


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--evaluations", type=int, default=2000)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--out", default="pycma-biped.robot.json", help="where the best robot is saved")
    a = p.parse_args()
    genes = vsrlab.genotype_length(CONFIG)
    es = cma.CMAEvolutionStrategy(np.zeros(genes), 0.5, {"seed": a.seed, "maxfevals": a.evaluations, "verbose": -9})
    while not es.stop():
        population = es.ask()
        fitness = vsrlab.evaluate_batch(CONFIG, np.array(population))
        es.tell(population, list(-np.nan_to_num(fitness, nan=-1e9)))
        print(f"evaluations {es.countevals:5d}  best velocity {-es.result.fbest:.3f}")
    vsrlab.robot_of(CONFIG, es.result.xbest).save(a.out)
    print(f"saved {a.out}")


if __name__ == "__main__":
    main()
