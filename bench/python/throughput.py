"""evaluate_batch's throughput next to `vsrlab run` doing the same work: the quickstart's 8 000
evaluations (10 s episodes of a 10-voxel biped), in batches of 40 as its GA asks them, and in one
batch; then `vsrlab run experiments/quickstart.toml` itself. Run with a release build of both:

    python3 -m venv /tmp/venv && /tmp/venv/bin/pip install ./python
    cargo build --release -p vsrlab-cli
    /tmp/venv/bin/python bench/python/throughput.py target/release/vsrlab
"""

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import vsrlab

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "experiments" / "quickstart.toml"
EVALUATIONS = 8000


def best_of(times: int, f) -> float:
    return min(f() for _ in range(times))


def batches_of(size: int, genotypes: np.ndarray) -> float:
    start = time.perf_counter()
    for i in range(0, len(genotypes), size):
        vsrlab.evaluate_batch(CONFIG, genotypes[i:i + size], np.arange(i, min(i + size, len(genotypes))))
    return time.perf_counter() - start


def cli_run(binary: str) -> float:
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([binary, "run", str(CONFIG), "--out", out], check=True, capture_output=True)
        return time.perf_counter() - start


def main() -> None:
    binary = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "target/release/vsrlab")
    rng = np.random.default_rng(0)
    genotypes = rng.uniform(-1, 1, (EVALUATIONS, vsrlab.genotype_length(CONFIG)))
    vsrlab.evaluate_batch(CONFIG, genotypes[:40])  # warm-up: parse and cache the evaluator
    run = best_of(3, lambda: cli_run(binary))
    in_40 = best_of(3, lambda: batches_of(40, genotypes))
    in_one = best_of(3, lambda: batches_of(EVALUATIONS, genotypes))
    print(f"vsrlab run (GA, 8000 evaluations):  {run:6.2f} s  {EVALUATIONS / run:7.0f} evaluations/s")
    print(f"evaluate_batch, batches of 40:      {in_40:6.2f} s  {EVALUATIONS / in_40:7.0f} evaluations/s  "
          f"({run / in_40:.2f}x vsrlab run)")
    print(f"evaluate_batch, one batch of 8000:  {in_one:6.2f} s  {EVALUATIONS / in_one:7.0f} evaluations/s  "
          f"({run / in_one:.2f}x vsrlab run)")


if __name__ == "__main__":
    main()
