"""Ray scaling on one machine: a loopback cluster of 1 then 2 worker nodes (1 CPU each) evaluates
the quickstart's genotypes in batches of 40 through vsrlab.cluster.RayEvaluator, next to local
evaluate_batch on 1 and 2 threads. Needs ray in the environment (python/requirements-test.txt):

    .venv/bin/python bench/ray/scaling.py [EVALUATIONS]
"""

import os
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import vsrlab
from vsrlab.cluster import RayEvaluator

ROOT = Path(__file__).resolve().parents[2]
CONFIG = ROOT / "experiments" / "quickstart.toml"
RAY = str(Path(sys.executable).parent / "ray")
ENV = dict(os.environ, RAY_AUTH_MODE="disabled", RAY_USAGE_STATS_ENABLED="0")
PORT = 6391


def ray(*args: str) -> None:
    subprocess.run([RAY, *args], env=ENV, check=True, capture_output=True, timeout=180)


def timed(evaluate, genotypes: np.ndarray) -> float:
    start = time.perf_counter()
    for i in range(0, len(genotypes), 40):
        evaluate(genotypes[i:i + 40], np.arange(i, i + 40, dtype=np.uint64))
    return time.perf_counter() - start


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 2000
    os.environ.update(RAY_AUTH_MODE="disabled", RAY_USAGE_STATS_ENABLED="0")
    genotypes = np.random.default_rng(0).uniform(-1, 1, (n, vsrlab.genotype_length(CONFIG)))
    text = CONFIG.read_text()
    rows = []
    for threads in (1, 2):
        local = vsrlab.BatchEvaluator(text, str(CONFIG), threads)
        rows.append((f"local evaluate_batch, {threads} thread(s)", timed(local.fitness, genotypes)))
    for nodes in (1, 2):
        ray("start", "--head", f"--port={PORT}", "--node-ip-address=127.0.0.1", "--num-cpus=1",
            "--include-dashboard=false", "--disable-usage-stats")
        try:
            if nodes == 2:
                ray("start", f"--address=127.0.0.1:{PORT}", "--node-ip-address=127.0.0.1", "--num-cpus=1")
            pool = RayEvaluator(text, address=f"127.0.0.1:{PORT}", origin=str(CONFIG))
            assert len(pool.actors) == nodes
            pool(genotypes[:40], np.arange(40, dtype=np.uint64))  # warm-up
            rows.append((f"Ray, {nodes} worker node(s) x 1 CPU", timed(pool, genotypes)))
            pool.close()
        finally:
            subprocess.run([RAY, "stop", "--force"], env=ENV, capture_output=True, timeout=180)
    base = rows[2][1]
    for name, seconds in rows:
        print(f"{name:38s} {seconds:7.2f} s  {n / seconds:6.0f} evaluations/s  ({base / seconds:.2f}x Ray on 1 node)")


if __name__ == "__main__":
    main()
