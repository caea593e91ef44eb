//! Benchmarks of vsrlab-evolution's CMA-ES and NSGA-II, the same measurements that
//! `bench/optimizers/run.sh` makes with pycma and pymoo:
//! - CMA-ES: evaluations to reach f < 1e-8 on sphere and Rosenbrock in 10 and 40 dimensions
//!   (default λ, σ0 = 0.5, initial mean uniform in [−1, 1]^n), one run per seed;
//! - NSGA-II: hypervolume (reference point (1.1, 1.1)) of the first front after 25 000
//!   evaluations on ZDT1, ZDT2 and ZDT3 (n = 30, N = 100, SBX + polynomial mutation), one run
//!   per seed, with the default configuration and again with duplicate elimination (as pymoo);
//! - CMA-ES termination: with the default termination criteria and no target, the evaluations
//!   until the run stops by itself and the criterion named, on the 20-D ellipsoid (σ0 = 0.5,
//!   mean in [−1, 1]^n) and the 10-D Rastrigin (σ0 = 2, mean in [−5.12, 5.12]^n), budget 10⁶.
//!
//! ```text
//! cargo run --release -p vsrlab-evolution --example optimizer_bench -- [--seeds 15] \
//!     [--termination-seeds 10] [--nsga2-only] [--json]
//! ```
//! Prints medians (and per-seed values with `--json`, including the ZDT fronts so the Python
//! side can recompute the hypervolume with pymoo's indicator). `--nsga2-only` skips the CMA-ES
//! measurements.

use serde_json::json;
use std::time::Instant;
use vsrlab_evolution::pareto::hypervolume_2d;
use vsrlab_evolution::test_functions::{rastrigin, rosenbrock, sphere, zdt1, zdt2, zdt3};
use vsrlab_evolution::{
    run_to_budget, CmaEs, CmaEsConfig, CmaSettings, Evaluation, Nsga2, Nsga2Config, Optimizer, SbxPolynomial, Sense,
    Stop, StopReason,
};

/// (name, function, dimension, evaluation budget)
type CmaCase = (&'static str, fn(&[f64]) -> f64, usize, u64);

const CMA_CASES: [CmaCase; 4] = [
    ("sphere", sphere, 10, 100_000),
    ("sphere", sphere, 40, 400_000),
    ("rosenbrock", rosenbrock, 10, 100_000),
    ("rosenbrock", rosenbrock, 40, 400_000),
];
const TARGET: f64 = 1e-8;
const ZDT_BUDGET: u64 = 25_000;

/// (name, function, hypervolume of the true front w.r.t. (1.1, 1.1))
type ZdtCase = (&'static str, fn(&[f64]) -> [f64; 2], f64);

const ZDT_CASES: [ZdtCase; 3] = [
    ("zdt1", zdt1, 0.87667),
    ("zdt2", zdt2, 0.54333),
    ("zdt3", zdt3, 1.33176),
];

/// (name, function, dimension, σ0, half-width of the initial mean's box)
type TerminationCase = (&'static str, fn(&[f64]) -> f64, usize, f64, f64);

const TERMINATION_CASES: [TerminationCase; 2] = [
    ("ellipsoid", ellipsoid, 20, 0.5, 1.0),
    ("rastrigin", rastrigin, 10, 2.0, 5.12),
];
const TERMINATION_BUDGET: u64 = 1_000_000;

/// f = Σ 10^{6(i−1)/(n−1)} x_i² (condition 1e6).
fn ellipsoid(x: &[f64]) -> f64 {
    let n = x.len() as f64;
    x.iter()
        .enumerate()
        .map(|(i, v)| 10f64.powf(6.0 * i as f64 / (n - 1.0)) * v * v)
        .sum()
}

/// One row per termination case: per seed the evaluations at the stop, the reason and the
/// best value.
fn termination_rows(seeds: u64, as_json: bool) -> Vec<serde_json::Value> {
    let mut rows = Vec::new();
    for (name, f, n, sigma0, half_width) in TERMINATION_CASES {
        let (mut evaluations, mut reasons, mut best, mut seconds) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for seed in 0..seeds {
            let config = CmaEsConfig {
                settings: CmaSettings {
                    sigma0,
                    ..CmaSettings::default()
                },
                init_min: -half_width,
                init_max: half_width,
                sense: Sense::Minimize,
                ..CmaEsConfig::default()
            };
            let mut cma = CmaEs::new(config, n, seed).expect("valid configuration");
            let start = Instant::now();
            let summary = run_to_budget(
                &mut cma,
                |c| Evaluation::single(f(&c.genotype)),
                &Stop::evaluations(TERMINATION_BUDGET),
            )
            .expect("run");
            seconds.push(start.elapsed().as_secs_f64());
            evaluations.push(summary.evaluations as f64);
            reasons.push(match summary.reason {
                StopReason::Optimizer(reason) => reason.trim_start_matches("cma-es:").to_string(),
                other => format!("{other:?}"),
            });
            best.push(cma.best().map_or(f64::NAN, |b| b.fitness()));
        }
        let row = json!({
            "function": name,
            "dimension": n,
            "sigma0": sigma0,
            "init_half_width": half_width,
            "budget": TERMINATION_BUDGET,
            "evaluations": evaluations,
            "reasons": reasons,
            "best": best,
            "median_evaluations": median(&mut evaluations.clone()),
            "median_best": median(&mut best.clone()),
            "median_seconds": median(&mut seconds.clone()),
        });
        if !as_json {
            println!(
                "CMA-ES {name:>10} n={n:<3} until it stops by itself: median {:>9.0} evals, median best {:.3e}, reasons {reasons:?}",
                row["median_evaluations"].as_f64().unwrap_or(f64::NAN),
                row["median_best"].as_f64().unwrap_or(f64::NAN),
            );
        }
        rows.push(row);
    }
    rows
}

fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let as_json = args.iter().any(|a| a == "--json");
    let seeds: u64 = args
        .iter()
        .position(|a| a == "--seeds")
        .and_then(|i| args.get(i + 1))
        .map(|s| s.parse().expect("--seeds takes an integer"))
        .unwrap_or(15);
    let nsga2_only = args.iter().any(|a| a == "--nsga2-only");
    let termination_seeds: u64 = args
        .iter()
        .position(|a| a == "--termination-seeds")
        .and_then(|i| args.get(i + 1))
        .map(|s| s.parse().expect("--termination-seeds takes an integer"))
        .unwrap_or(10);

    let mut cma_rows = Vec::new();
    for (name, f, n, budget) in CMA_CASES.into_iter().filter(|_| !nsga2_only) {
        let mut evaluations = Vec::new();
        let mut seconds = Vec::new();
        for seed in 0..seeds {
            let config = CmaEsConfig {
                sense: Sense::Minimize,
                ..CmaEsConfig::default()
            };
            let mut cma = CmaEs::new(config, n, seed).expect("valid configuration");
            let start = Instant::now();
            let summary = run_to_budget(
                &mut cma,
                |c| Evaluation::single(f(&c.genotype)),
                &Stop::evaluations(budget).or_target(TARGET),
            )
            .expect("run");
            seconds.push(start.elapsed().as_secs_f64());
            evaluations.push((summary.reason == StopReason::Target).then_some(summary.evaluations));
        }
        let mut successes: Vec<f64> = evaluations.iter().flatten().map(|&e| e as f64).collect();
        let row = json!({
            "function": name,
            "dimension": n,
            "target": TARGET,
            "budget": budget,
            "evaluations": evaluations,
            "successes": successes.len(),
            "median_evaluations": median(&mut successes),
            "median_seconds": median(&mut seconds.clone()),
            "seconds": seconds,
        });
        if !as_json {
            println!(
                "CMA-ES {name:>10} n={n:<3} evals to {TARGET:e}: median {:>9.0} ({}/{seeds} reached), {:.4} s/run",
                row["median_evaluations"].as_f64().unwrap_or(f64::NAN),
                row["successes"],
                row["median_seconds"].as_f64().unwrap_or(f64::NAN),
            );
        }
        cma_rows.push(row);
    }

    let nsga_rows: Vec<serde_json::Value> = ZDT_CASES
        .into_iter()
        .flat_map(|case| [(case, false), (case, true)])
        .map(|((problem, f, true_hv), dedup)| {
            let row = nsga2_row(problem, f, seeds, dedup);
            if !as_json {
                let variant = if dedup { " (duplicates eliminated)" } else { "" };
                println!(
                    "NSGA-II {problem}{variant} n=30 N=100 {ZDT_BUDGET} evals: median hypervolume {:.5} (true front {true_hv:.5}), {:.4} s/run",
                    row["median_hypervolume"].as_f64().unwrap_or(f64::NAN),
                    row["median_seconds"].as_f64().unwrap_or(f64::NAN),
                );
            }
            row
        })
        .collect();
    let termination = if nsga2_only {
        Vec::new()
    } else {
        termination_rows(termination_seeds, as_json)
    };
    if as_json {
        println!(
            "{}",
            json!({ "cma_es": cma_rows, "nsga2": nsga_rows, "cma_termination": termination })
        );
    }
}

/// NSGA-II on one ZDT problem (n = 30, default configuration), one run per seed: the
/// hypervolumes and first fronts.
fn nsga2_row(problem: &str, f: fn(&[f64]) -> [f64; 2], seeds: u64, eliminate_duplicates: bool) -> serde_json::Value {
    let mut hvs = Vec::new();
    let mut fronts = Vec::new();
    let mut seconds = Vec::new();
    for seed in 0..seeds {
        let config = Nsga2Config::new(vec![Sense::Minimize; 2]);
        let mut nsga = Nsga2::new(config, SbxPolynomial::new(30, 0.0, 1.0), seed)
            .expect("valid")
            .with_duplicate_elimination(eliminate_duplicates);
        let start = Instant::now();
        run_to_budget(
            &mut nsga,
            |c| Evaluation::multi(f(&c.genotype).to_vec()),
            &Stop::evaluations(ZDT_BUDGET),
        )
        .expect("run");
        seconds.push(start.elapsed().as_secs_f64());
        let front: Vec<[f64; 2]> = nsga
            .first_front()
            .iter()
            .map(|i| [i.objectives[0], i.objectives[1]])
            .collect();
        hvs.push(hypervolume_2d(&front, [1.1, 1.1], [Sense::Minimize; 2]));
        fronts.push(front);
    }
    json!({
        "problem": problem,
        "eliminate_duplicates": eliminate_duplicates,
        "n_var": 30,
        "population": 100,
        "budget": ZDT_BUDGET,
        "reference": [1.1, 1.1],
        "hypervolume": hvs,
        "median_hypervolume": median(&mut hvs.clone()),
        "median_seconds": median(&mut seconds.clone()),
        "seconds": seconds,
        "fronts": fronts,
    })
}
