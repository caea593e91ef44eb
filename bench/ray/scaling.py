"""Ray scaling on one machine: a loopback cluster of 1 then 2 worker nodes (1 CPU each).

    .venv/bin/python bench/ray/scaling.py batches [EVALUATIONS]   # quickstart genotypes in batches of 40
    .venv/bin/python bench/ray/scaling.py codesign [ITERATIONS]   # a small co-design run (PPO per body)
    .venv/bin/python bench/ray/scaling.py campaign [FILES] [SECONDS]  # a campaign of many small runs

ITERATIONS (default 2) is each body's PPO iterations, SECONDS (default 10) each campaign
episode's duration: larger values make each evaluation heavier (closer to the thesis's, where a
body trains for 1,000 iterations and episodes last 30-60 s), so that the fixed costs (start-up,
the driver's share of this machine's cores) weigh less.

`batches` also times local evaluate_batch on 1 and 2 threads. Needs ray in the environment
(python/requirements-test.txt). Prints seconds per setting and the ratio to Ray on 1 node.
"""

import json
import os
import resource
import subprocess
import sys
import tempfile
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

# A small co-design run in the thesis's shape (ch. 5.2: 25 bodies, then generations of 20
# offspring of the best 5): 5x5 Walker bodies, each trained by a short PPO on the worker.
CODESIGN = """
name = "scaling-codesign"
runs = 1
seed = 1
[genotype]
kind = "material-grid"
width = 5
height = 5
mutation_rate = 0.1
[genotype.ppo]
iterations = {iterations}
environments = 2
steps_per_environment = 64
[task]
kind = "evogym"
env = "Walker-v0"
[optimizer]
kind = "ga"
population_size = 5
offspring_size = 20
tournament_size = 1
mutation_probability = 1.0
initial_population_size = 25
[stop]
evaluations = 65
"""

# One file of a campaign of many small runs: a biped GA with batches of 8.
SMALL_RUN = """
name = "{name}"
runs = 2
seed = {seed}
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = {{ kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }}
[task]
terrain = "flat"
duration = {duration}
fitness = "velocity"
[optimizer]
kind = "ga"
population_size = 8
offspring_size = 8
[stop]
evaluations = 96
"""


def ray(*args: str) -> None:
    subprocess.run([RAY, *args], env=ENV, check=True, capture_output=True, timeout=180)


def on_cluster(nodes: int, work) -> float:
    """Seconds `work(address)` takes on a loopback cluster of `nodes` worker nodes of 1 CPU."""
    ray("start", "--head", f"--port={PORT}", "--node-ip-address=127.0.0.1", "--num-cpus=1",
        "--include-dashboard=false", "--disable-usage-stats")
    try:
        if nodes == 2:
            ray("start", f"--address=127.0.0.1:{PORT}", "--node-ip-address=127.0.0.1", "--num-cpus=1")
        start = time.perf_counter()
        cpu = resource.getrusage(resource.RUSAGE_SELF)
        work(f"127.0.0.1:{PORT}")
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_SELF)
        driver = after.ru_utime + after.ru_stime - cpu.ru_utime - cpu.ru_stime
        print(f"  ({nodes} node(s): the driver process used {driver:.1f} CPU-s of {wall:.1f} s)", file=sys.stderr)
        return wall
    finally:
        subprocess.run([RAY, "stop", "--force"], env=ENV, capture_output=True, timeout=180)


def batches(n: int) -> list:
    genotypes = np.random.default_rng(0).uniform(-1, 1, (n, vsrlab.genotype_length(CONFIG)))
    texts = [json.dumps(list(map(float, row))) for row in genotypes]
    text = vsrlab._native.experiment_text(str(CONFIG))

    def timed(evaluate, rows) -> float:
        start = time.perf_counter()
        for i in range(0, n, 40):
            evaluate(rows[i:i + 40], np.arange(i, i + 40, dtype=np.uint64))
        return time.perf_counter() - start

    rows = []
    for threads in (1, 2):
        local = vsrlab.BatchEvaluator(text, str(CONFIG), threads)
        rows.append((f"local evaluate_batch, {threads} thread(s)", timed(local.fitness, genotypes)))
    for nodes in (1, 2):
        seconds = {}

        def work(address: str) -> None:
            pool = RayEvaluator(text, address=address, origin=str(CONFIG))
            assert len(pool.actors) == nodes
            pool(texts[:40], np.arange(40, dtype=np.uint64))  # warm-up
            seconds["batches"] = timed(pool, texts)
            pool.close()

        on_cluster(nodes, work)
        rows.append((f"Ray, {nodes} worker node(s) x 1 CPU", seconds["batches"]))
    return rows


def evaluation_seconds(out: Path) -> float:
    """The run's wall-clock seconds in evaluations (timings.csv), without start-up and saving."""
    total = 0.0
    for timings in out.glob("run-*/timings.csv"):
        lines = timings.read_text().splitlines()
        column = lines[0].split(",").index("evaluation_seconds")
        total += sum(float(line.split(",")[column]) for line in lines[1:])
    return total


def codesign(iterations: int) -> list:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        config = Path(tmp) / "codesign.toml"
        config.write_text(CODESIGN.format(iterations=iterations))
        for nodes in (1, 2):
            out = Path(tmp) / f"out-{nodes}"
            wall = on_cluster(nodes, lambda address: vsrlab.run(config, out, ray=address))
            rows.append((f"co-design run, Ray {nodes} node(s) x 1 CPU", wall))
            rows.append((f"  its batches only ({nodes} node(s))", evaluation_seconds(out)))
    return rows


def campaign(files: int, duration: float) -> list:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for i in range(files):
            path = Path(tmp) / f"small-{i}.toml"
            path.write_text(SMALL_RUN.format(name=f"small-{i}", seed=i + 1, duration=duration))
            paths.append(path)
        for nodes in (1, 2):
            out = Path(tmp) / f"out-{nodes}"
            rows.append((f"campaign {files} files x 2 runs, Ray {nodes} node(s)",
                         on_cluster(nodes, lambda address: vsrlab.campaign(paths, out, ray=address))))
    return rows


def main() -> None:
    os.environ.update(RAY_AUTH_MODE="disabled", RAY_USAGE_STATS_ENABLED="0")
    mode = sys.argv[1] if len(sys.argv) > 1 else "batches"
    if mode == "batches":
        n = int(sys.argv[2]) if len(sys.argv) > 2 else 2000
        rows, base = batches(n), 2
    elif mode == "codesign":
        rows = codesign(int(sys.argv[2]) if len(sys.argv) > 2 else 2)
        for name, seconds in rows:
            reference = rows[0][1] if "batches only" not in name else rows[1][1]
            print(f"{name:44s} {seconds:8.2f} s  ({reference / seconds:.2f}x Ray on 1 node)")
        return
    elif mode == "campaign":
        files = int(sys.argv[2]) if len(sys.argv) > 2 else 8
        rows, base = campaign(files, float(sys.argv[3]) if len(sys.argv) > 3 else 10.0), 0
    else:
        sys.exit(f"unknown mode {mode}: batches, codesign or campaign")
    reference = rows[base][1]
    for name, seconds in rows:
        print(f"{name:44s} {seconds:8.2f} s  ({reference / seconds:.2f}x Ray on 1 node)")


if __name__ == "__main__":
    main()
