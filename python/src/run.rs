//! Experiment runs from Python (`vsrlab.run`): the runner of `vsrlab run`, whose batches of
//! evaluations may go to a Python callable instead of local threads (the Ray route: see
//! `vsrlab/cluster.py`). Checkpoints, resume and the output files are the runner's own.

use crate::value_error;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use vsrlab_experiment::evaluator::{Evaluated, Evaluator, EvaluatorError, Record, RobotEvaluator};
use vsrlab_experiment::genotypes::vector::run_vectors;
use vsrlab_experiment::runner::{self, Flow, Observer, Progress, RunOptions, RunSummary};
use vsrlab_experiment::{config, Experiment};

/// Evaluates with the runner's evaluator, but sends every batch to a Python callable
/// `evaluate(genotypes: ndarray (n, genes), seeds: ndarray (n,)) -> str` that returns the
/// batch's evaluations as the JSON of `BatchEvaluator.evaluations`.
struct Remote {
    local: RobotEvaluator,
    evaluate: Py<PyAny>,
}

impl Evaluator<Vec<f64>> for Remote {
    fn evaluate(&self, genotype: &Vec<f64>, candidate_seed: u64) -> Evaluated {
        self.local.evaluate(genotype, candidate_seed)
    }

    fn objectives(&self) -> usize {
        Evaluator::<Vec<f64>>::objectives(&self.local)
    }

    fn failure(&self, seed: u64, error: String) -> Evaluated {
        Evaluator::<Vec<f64>>::failure(&self.local, seed, error)
    }

    fn evaluate_batch_reporting(
        &self,
        genotypes: &[&Vec<f64>],
        seeds: &[u64],
        done: &(dyn Fn(usize, &Evaluated) + Sync),
    ) -> Result<Vec<Evaluated>, EvaluatorError> {
        let width = genotypes.first().map_or(0, |g| g.len());
        let genes: Vec<f64> = genotypes.iter().flat_map(|g| g.iter().copied()).collect();
        let text: String = Python::attach(|py| -> PyResult<String> {
            let matrix = PyArray1::from_vec(py, genes).reshape([genotypes.len(), width])?;
            let seeds = PyArray1::from_slice(py, seeds);
            self.evaluate.call1(py, (matrix, seeds))?.extract(py)
        })
        .map_err(|e| EvaluatorError::Remote(format!("the batch callable failed: {e}")))?;
        let evaluated: Vec<Evaluated> = serde_json::from_str(&text)
            .map_err(|e| EvaluatorError::Remote(format!("the batch callable returned bad evaluations: {e}")))?;
        if evaluated.len() != genotypes.len() {
            return Err(EvaluatorError::Remote(format!(
                "the batch callable returned {} evaluations for {} genotypes",
                evaluated.len(),
                genotypes.len()
            )));
        }
        // the callable returns the batch whole: every evaluation ends at once
        for (index, e) in evaluated.iter().enumerate() {
            done(index, e);
        }
        Ok(evaluated)
    }

    fn save_robot(
        &self,
        genotype: &Vec<f64>,
        record: Option<&Record>,
        path: &Path,
        note: &str,
    ) -> Result<(), EvaluatorError> {
        self.local.save_robot(genotype, record, path, note)
    }

    fn save_replay(&self, genotype: &Vec<f64>, path: &Path, title: &str) -> Result<(), EvaluatorError> {
        self.local.save_replay(genotype, path, title)
    }

    fn genotype_columns(&self) -> &'static [&'static str] {
        Evaluator::<Vec<f64>>::genotype_columns(&self.local)
    }

    fn genotype_stats(&self, genotype: &Vec<f64>) -> Vec<f64> {
        self.local.genotype_stats(genotype)
    }

    fn check(&self, genotype: &Vec<f64>) -> Result<(), EvaluatorError> {
        self.local.check(genotype)
    }
}

/// Prints a line per finished run (and per `progress_every` generations when asked), and stops
/// the run cleanly on Ctrl-C (the checkpoint is kept: `resume=True` continues it).
struct Reporter {
    name: String,
    interrupted: bool,
    verbose: bool,
}

impl Observer for Reporter {
    fn generation(&mut self, p: &Progress) -> Flow {
        if Python::attach(|py| py.check_signals()).is_err() {
            self.interrupted = true;
            return Flow::Interrupt;
        }
        if self.verbose {
            eprintln!(
                "{}: run {}/{} generation {} evaluations {} best {:.6}",
                self.name,
                p.run + 1,
                p.runs,
                p.generation,
                p.evaluations,
                p.best_fitness
            );
        }
        Flow::Continue
    }

    fn notice(&mut self, message: &str) {
        eprintln!("{}: {message}", self.name);
    }

    fn run_finished(&mut self, s: &RunSummary) {
        if self.verbose {
            eprintln!(
                "{}: run {} done: {} evaluations, best fitness {:?}",
                self.name, s.run, s.evaluations, s.best_fitness
            );
        }
    }
}

/// Runs an experiment file into `out` like `vsrlab run` and returns the runs' summaries as JSON
/// text. With `evaluate`, every batch goes to that callable (see [`Remote`]); the results are
/// the same bit for bit, since each evaluation is a pure function of (genotype, seed).
#[pyfunction]
#[pyo3(signature = (config, out, resume = false, threads = 0, evaluate = None, verbose = false))]
pub fn run(
    py: Python<'_>,
    config: PathBuf,
    out: PathBuf,
    resume: bool,
    threads: usize,
    evaluate: Option<Py<PyAny>>,
    verbose: bool,
) -> PyResult<String> {
    let experiments = config::load_all(&config).map_err(value_error)?;
    let [experiment]: [Experiment; 1] = experiments.try_into().map_err(|e: Vec<Experiment>| {
        value_error(format!(
            "config: {} is a sweep of {} settings; run each setting's file, or the CLI's `vsrlab run`",
            config.display(),
            e.len()
        ))
    })?;
    let options = RunOptions {
        threads,
        resume,
        memory_limit: None,
    };
    let mut reporter = Reporter {
        name: experiment.name.clone().unwrap_or_else(|| "experiment".into()),
        interrupted: false,
        verbose,
    };
    let summaries = py.detach(|| -> Result<Vec<RunSummary>, String> {
        match evaluate {
            None => vsrlab_experiment::run_configured(&experiment, &out, &options, &mut reporter).map_err(|e| e.to_string()),
            Some(callable) => {
                let kind = experiment.genotype_kind();
                if !kind.rows() {
                    return Err(format!(
                        "evaluate: {} genotypes are not rows of numbers and are evaluated locally only; leave evaluate out",
                        kind.name()
                    ));
                }
                let local = RobotEvaluator::new(&experiment).map_err(|e| e.to_string())?;
                let remote = Remote {
                    local,
                    evaluate: callable,
                };
                run_vectors(&experiment, &remote, &out, &options, &mut reporter).map_err(|e| e.to_string())
            }
        }
    });
    if reporter.interrupted {
        return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
            "interrupted: the last checkpoint is kept; run again with resume=True to continue",
        ));
    }
    let summaries = summaries.map_err(value_error)?;
    serde_json::to_string(&summaries).map_err(value_error)
}

/// The files of an output folder that must be identical between two runs of the same
/// experiment (logs without timings, snapshots, best robots), as (name, bytes) pairs.
#[pyfunction]
pub fn deterministic_files(out: PathBuf) -> PyResult<Vec<(String, Vec<u8>)>> {
    runner::deterministic_files(&out).map_err(|e| value_error(format!("out: {e}")))
}
