"""Side-by-side benchmark: vsrlab-evolution vs pycma (CMA-ES) and pymoo (NSGA-II).

Measurements (identical settings on both sides, one run per seed, medians over seeds):
- CMA-ES, evaluations until the best f < 1e-8 on sphere and Rosenbrock, n = 10 and 40;
  default population size, sigma0 = 0.5, initial mean uniform in [-1, 1]^n, budgets
  1e5 (n = 10) and 4e5 (n = 40) evaluations. pycma runs with its defaults (active CMA,
  no restarts) plus ftarget and maxfevals. A run that misses the target counts as a failure;
  medians are over successful runs.
- NSGA-II on ZDT1, ZDT2 and ZDT3 (n = 30), population 100, 100 offspring per generation, SBX (p 0.9, eta 15)
  and polynomial mutation (eta 20, p 1/n), 25 000 evaluations; hypervolume of the final
  non-dominated set w.r.t. (1.1, 1.1), computed with pymoo's HV indicator for both sides
  (the vsrlab value is also checked against vsrlab's own hypervolume); two-sided Mann-Whitney
  U p-value of the per-seed hypervolumes (scipy). vsrlab runs twice: with its default (no
  duplicate elimination, as Deb et al.) and with `with_duplicate_elimination(true)` ("dedup"),
  which is pymoo's default.
- CMA-ES termination: default termination criteria, no target, budget 1e6 evaluations, on
  the ellipsoid (n = 20, sigma0 = 0.5, mean uniform in [-1, 1]^n) and Rastrigin (n = 10,
  sigma0 = 2, mean uniform in [-5.12, 5.12]^n): evaluations until the run stops by itself and
  which criterion stopped it (pycma: the keys of `es.stop()`; vsrlab: `stop_reason()`).
Time per run: CPU seconds (Python, process_time) vs wall seconds (Rust, single thread).
"""

import argparse
import collections
import json
import math
import statistics
import subprocess
import sys
import time

import cma
import numpy as np
import pymoo
from pymoo.algorithms.moo.nsga2 import NSGA2
from pymoo.indicators.hv import HV
from pymoo.optimize import minimize
from pymoo.problems import get_problem
from scipy.stats import mannwhitneyu

TARGET = 1e-8
CMA_CASES = [("sphere", 10, 100_000), ("sphere", 40, 400_000),
             ("rosenbrock", 10, 100_000), ("rosenbrock", 40, 400_000)]
ZDT_BUDGET = 25_000
REFERENCE = np.array([1.1, 1.1])
# Hypervolume of the true fronts w.r.t. REFERENCE (ZDT3: its five segments sampled densely).
TRUE_HV = {"zdt1": 0.1 + 2.0 / 3.0 + 0.11, "zdt2": 0.1 + 1.0 / 3.0 + 0.11, "zdt3": 1.33176}


def sphere(x):
    return float(np.dot(x, x))


def rosenbrock(x):
    return float(np.sum(100.0 * (x[1:] - x[:-1] ** 2) ** 2 + (1.0 - x[:-1]) ** 2))


def ellipsoid(x):
    n = len(x)
    return float(np.sum(10.0 ** (6.0 * np.arange(n) / (n - 1)) * x * x))


def rastrigin(x):
    return float(10.0 * len(x) + np.sum(x * x - 10.0 * np.cos(2.0 * math.pi * x)))


FUNCTIONS = {"sphere": sphere, "rosenbrock": rosenbrock, "ellipsoid": ellipsoid, "rastrigin": rastrigin}


def median_or_nan(values):
    return statistics.median(values) if values else math.nan


def pycma_run(name, n, budget, seed):
    f = FUNCTIONS[name]
    x0 = np.random.default_rng(seed).uniform(-1.0, 1.0, n)
    opts = {"seed": seed + 1, "ftarget": TARGET, "maxfevals": budget, "verbose": -9}
    start = time.process_time()
    es = cma.CMAEvolutionStrategy(x0, 0.5, opts)
    while not es.stop():
        xs = es.ask()
        es.tell(xs, [f(x) for x in xs])
    seconds = time.process_time() - start
    reached = es.result.fbest < TARGET
    return (es.result.evaluations if reached else None), seconds


def pycma_termination_run(name, n, sigma0, half_width, budget, seed):
    """One run with pycma's default termination criteria and no target: (evaluations, the keys
    of es.stop() in the order pycma tested them, best f)."""
    f = FUNCTIONS[name]
    x0 = np.random.default_rng(seed).uniform(-half_width, half_width, n)
    es = cma.CMAEvolutionStrategy(x0, sigma0, {"seed": seed + 1, "maxfevals": budget, "verbose": -9})
    while not es.stop():
        xs = es.ask()
        es.tell(xs, [f(x) for x in xs])
    return es.result.evaluations, list(es.stop().keys()), float(es.result.fbest)


def termination_rows(ours):
    rows = []
    for mine in ours:
        name, n = mine["function"], mine["dimension"]
        runs = [pycma_termination_run(name, n, mine["sigma0"], mine["init_half_width"], mine["budget"], seed)
                for seed in range(len(mine["evaluations"]))]
        for seed, (e, keys, best) in enumerate(runs):
            print(f"[compare] pycma {name} n={n} seed {seed}: stopped after {e} evals by {keys}, best {best:.3e}",
                  file=sys.stderr)
        rows.append({
            "benchmark": f"CMA-ES {name} n={n} sigma0={mine['sigma0']:g}",
            "seeds": len(runs),
            "peer": f"pycma {cma.__version__}",
            "peer_median_evaluations": statistics.median(e for e, _, _ in runs),
            "vsrlab_median_evaluations": mine["median_evaluations"],
            "peer_median_best": statistics.median(b for _, _, b in runs),
            "vsrlab_median_best": mine["median_best"],
            # pycma may report several criteria at once; count the first (its test order) and all.
            "peer_first_reason": dict(collections.Counter(keys[0] for _, keys, _ in runs)),
            "peer_all_reasons": dict(collections.Counter("+".join(keys) for _, keys, _ in runs)),
            "vsrlab_reason": dict(collections.Counter(mine["reasons"])),
        })
    return rows


def print_termination(rows):
    print("\nCMA-ES stopping by itself (default criteria, no target, budget 1e6); medians over seeds\n")
    header = f"{'benchmark':<34} {'side':<12} {'evals to stop':>13} {'best f':>10}  stop reasons"
    print(header)
    print("-" * len(header))
    for r in rows:
        print(f"{r['benchmark']:<34} {r['peer']:<12} {r['peer_median_evaluations']:>13.0f} "
              f"{r['peer_median_best']:>10.3g}  {r['peer_all_reasons']}")
        print(f"{'':<34} {'vsrlab':<12} {r['vsrlab_median_evaluations']:>13.0f} "
              f"{r['vsrlab_median_best']:>10.3g}  {r['vsrlab_reason']}")


def pymoo_run(name, seed):
    problem = get_problem(name, n_var=30)
    start = time.process_time()
    res = minimize(problem, NSGA2(pop_size=100), ("n_eval", ZDT_BUDGET), seed=seed + 1, verbose=False)
    seconds = time.process_time() - start
    return float(HV(ref_point=REFERENCE)(res.F)), seconds


def vsrlab_results(seeds, termination_seeds, nsga2_only):
    cmd = ["cargo", "run", "--release", "-q", "-p", "vsrlab-evolution", "--example",
           "optimizer_bench", "--", "--json", "--seeds", str(seeds),
           "--termination-seeds", str(termination_seeds)] + (["--nsga2-only"] if nsga2_only else [])
    print("[compare] " + " ".join(cmd), file=sys.stderr)
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def ratio(a, b):
    return a / b if b and not math.isnan(a) and not math.isnan(b) else math.nan


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seeds", type=int, default=15, help="runs per benchmark (default 15)")
    parser.add_argument("--termination-seeds", type=int, default=10,
                        help="runs per CMA-ES termination benchmark (default 10)")
    parser.add_argument("--json", action="store_true", help="print JSON instead of the table")
    parser.add_argument("--nsga2-only", action="store_true", help="only the NSGA-II benchmarks")
    args = parser.parse_args()

    rows = []
    ours = vsrlab_results(args.seeds, args.termination_seeds, args.nsga2_only)
    for (name, n, budget), mine in zip(CMA_CASES, ours["cma_es"]):
        assert (mine["function"], mine["dimension"], mine["budget"]) == (name, n, budget)
        evals, secs = [], []
        for seed in range(args.seeds):
            e, s = pycma_run(name, n, budget, seed)
            evals.append(e)
            secs.append(s)
            print(f"[compare] pycma {name} n={n} seed {seed}: {e} evals, {s:.3f} s", file=sys.stderr)
        ok = [e for e in evals if e is not None]
        mine_ok = [e for e in mine["evaluations"] if e is not None]
        rows.append({
            "benchmark": f"CMA-ES {name} n={n}",
            "metric": f"evals to f<{TARGET:g}",
            "peer": f"pycma {cma.__version__}",
            "peer_value": median_or_nan(ok),
            "vsrlab_value": median_or_nan(mine_ok),
            "peer_success": f"{len(ok)}/{args.seeds}",
            "vsrlab_success": f"{len(mine_ok)}/{args.seeds}",
            "peer_seconds": statistics.median(secs),
            "vsrlab_seconds": mine["median_seconds"],
        })

    indicator = HV(ref_point=REFERENCE)
    peer_runs = {}
    for mine in ours["nsga2"]:
        name = mine["problem"]
        if name not in peer_runs:
            peer_runs[name] = [pymoo_run(name, seed) for seed in range(args.seeds)]
            for seed, (hv, s) in enumerate(peer_runs[name]):
                print(f"[compare] pymoo {name} seed {seed}: hv {hv:.5f}, {s:.3f} s", file=sys.stderr)
        hvs = [hv for hv, _ in peer_runs[name]]
        secs = [s for _, s in peer_runs[name]]
        mine_hvs = [float(indicator(np.array(front))) for front in mine["fronts"]]
        for ours_hv, own in zip(mine_hvs, mine["hypervolume"]):
            assert abs(ours_hv - own) < 1e-9, (ours_hv, own)
        variant = " dedup" if mine["eliminate_duplicates"] else ""
        rows.append({
            "benchmark": f"NSGA-II {name.upper()}{variant} n=30",
            "metric": f"hypervolume @ {ZDT_BUDGET} evals (true {TRUE_HV[name]:.5f})",
            "peer": f"pymoo {pymoo.__version__}",
            "peer_value": statistics.median(hvs),
            "vsrlab_value": statistics.median(mine_hvs),
            "peer_values": hvs,
            "vsrlab_values": mine_hvs,
            "mann_whitney_p": float(mannwhitneyu(mine_hvs, hvs, alternative="two-sided").pvalue),
            "peer_success": "-",
            "vsrlab_success": "-",
            "peer_seconds": statistics.median(secs),
            "vsrlab_seconds": mine["median_seconds"],
        })

    termination = termination_rows(ours["cma_termination"])
    if args.json:
        print(json.dumps({"seeds": args.seeds, "rows": rows, "termination": termination}, indent=2))
        return
    print(f"\nMedians over {args.seeds} seeds; ratio = vsrlab / peer "
          "(evals: < 1 is fewer evaluations; hypervolume: > 1 is better; time: < 1 is faster)\n")
    header = f"{'benchmark':<26} {'metric':<44} {'peer':<13} {'peer':>10} {'vsrlab':>10} {'ratio':>7}" \
             f" {'reached p/v':>12} {'s/run peer':>11} {'s/run vsrlab':>13} {'time ratio':>10}"
    print(header)
    print("-" * len(header))
    for r in rows:
        fmt = "{:>10.5f}" if "hypervolume" in r["metric"] else "{:>10.0f}"
        print(f"{r['benchmark']:<26} {r['metric']:<44} {r['peer']:<13} "
              f"{fmt.format(r['peer_value'])} {fmt.format(r['vsrlab_value'])} "
              f"{ratio(r['vsrlab_value'], r['peer_value']):>7.3f} "
              f"{r['peer_success'] + ' ' + r['vsrlab_success']:>12} "
              f"{r['peer_seconds']:>11.4f} {r['vsrlab_seconds']:>13.4f} "
              f"{ratio(r['vsrlab_seconds'], r['peer_seconds']):>10.3f}"
              + (f"  Mann-Whitney p = {r['mann_whitney_p']:.3g}" if "mann_whitney_p" in r else ""))
    if termination:
        print_termination(termination)


if __name__ == "__main__":
    main()
