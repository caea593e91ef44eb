//! # vsrlab-experiment
//!
//! Runs evolutionary experiments on voxel-based soft robots as described in one TOML file
//! (`docs/experiments.md`): representation (body, sensors, brain, preset), locomotion task,
//! optimizer, stop criterion, runs and outputs.
//!
//! - [`config`]: the experiment file, parsed with errors that name the field and the line.
//! - [`optimizers`]: the registry of optimizer kinds and their `[optimizer]` parameters, and
//!   [`optimizers::SearchOptimizer`], what the runner needs of an optimizer over any genotype.
//! - [`genotype`]: what the runner needs of a genotype type (serde and a key).
//! - [`genotypes`]: the registry of genotype kinds (`[genotype] kind`: flat vectors, the graph
//!   of the self-organizing controller) and [`run_configured`], which runs any experiment file.
//! - [`evaluator`]: genotype → fitness values, descriptor, speciation features, snapshot record.
//! - [`codesign`]: body–brain co-design (thesis ch. 5.2): material-grid bodies whose fitness is
//!   what PPO learns for them on an EvoGym task ([`learning_env`]: those tasks as environments).
//! - [`features`]: simple morphology descriptors, dynamic pose and behaviour spectrum.
//! - [`runner`]: the ask → parallel evaluate → tell loop, with CSV logs, snapshots, the best
//!   robot, checkpoints and resume; [`checkpoint`]: checkpoint files and the content hashes
//!   that resume verifies; [`output_lock`]: one process per output folder; [`memory`]: the
//!   per-run memory estimate checked before a run starts.
//! - [`validate`](mod@validate): what a file will do before it runs (resolved configuration,
//!   sizes, a time estimate).
//! - [`campaign`]: many experiment files × their runs side by side, on one pool or cluster.
//! - [`remote`]: a run's batches evaluated elsewhere (Ray workers), and the workers' side,
//!   for every genotype kind.
//! - [`batch`]: many flat genotypes evaluated in one call, for optimisers outside vsrlab
//!   (`vsrlab evaluate`, the Python package).
//! - [`bench`](mod@bench): the simulation speed benchmark on the standard robots (`vsrlab bench`),
//!   timed in CPU seconds ([`cpu_time`]).
//!
//! ## Guarantees
//! - **Thread count never changes results**: batches are evaluated with rayon and collected in
//!   candidate order; all randomness derives from the run seed.
//! - **Resume**: a run killed at any point and resumed from its last checkpoint ends with the
//!   same deterministic files (`generations.csv`, snapshots, best robot) as an uninterrupted one.
//! - **Atomic files**: everything is written to a temporary file and renamed.
//! - **Failed evaluations never abort a run**: they get the worst fitness (NaN) and are counted.
//!
//! ## Example
//! ```no_run
//! use vsrlab_experiment::{config, run_configured, runner};
//! let experiment = config::load("experiments/quickstart.toml".as_ref()).unwrap();
//! let options = runner::RunOptions::default();
//! run_configured(&experiment, "out/quickstart".as_ref(), &options, &mut runner::Silent).unwrap();
//! ```
#![warn(missing_docs)]

pub mod batch;
mod batches;
pub mod bench;
pub mod bench_learning;
pub mod bench_population;
pub mod campaign;
pub mod checkpoint;
pub mod codesign;
pub mod config;
pub mod cpu_time;
pub mod evaluator;
pub mod features;
pub mod genotype;
pub mod genotypes;
pub mod learning_env;
pub mod memory;
pub mod optimizers;
pub mod output_lock;
pub mod remote;
pub mod runner;
pub mod unfinished_generation;
pub mod validate;

pub use batch::{BatchError, BatchEvaluator};
pub use bench::{run_bench, BenchError, BenchOptions, BenchReport};
pub use config::{ConfigError, Experiment};
pub use evaluator::{Evaluated, Evaluator, Record, RobotEvaluator};
pub use genotype::Genotype;
pub use genotypes::run_configured;
pub use runner::{run_search, Flow, Observer, Plan, Progress, RunError, RunOptions, RunSummary, Silent};
