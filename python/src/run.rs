//! Experiment runs from Python (`vsrlab.run`): the runner of `vsrlab run`, whose batches of
//! evaluations may go to a Python callable instead of local threads (the Ray route: see
//! `vsrlab/cluster.py`). Checkpoints, resume and the output files are the runner's own.

use crate::value_error;
use numpy::PyArray1;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vsrlab_experiment::evaluator::{Evaluated, EvaluatorError, Record};
use vsrlab_experiment::remote::{Evaluations, Transport};
use vsrlab_experiment::runner::{self, Flow, Observer, Progress, RunOptions, RunSummary};
use vsrlab_experiment::{config, Experiment};

/// Sends every batch to a Python callable `evaluate(genotypes: list[str], seeds: ndarray (n,)) ->
/// str`: the genotypes as their JSON texts (any genotype kind), the answer as the JSON of the
/// batch's evaluations (`Worker.evaluations`). When the callable has a `robot_file(genotype: str,
/// record: str | None, note: str) -> bytes` method, a run's best robot file is made there too.
pub(crate) struct PyTransport {
    pub(crate) evaluate: Py<PyAny>,
}

impl Transport for PyTransport {
    fn evaluate(&self, genotypes: &[String], seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError> {
        let text: String = Python::attach(|py| -> PyResult<String> {
            let seeds = PyArray1::from_slice(py, seeds);
            self.evaluate.call1(py, (genotypes.to_vec(), seeds))?.extract(py)
        })
        .map_err(|e| EvaluatorError::Remote(format!("the batch callable failed: {e}")))?;
        serde_json::from_str(&text)
            .map_err(|e| EvaluatorError::Remote(format!("the batch callable returned bad evaluations: {e}")))
    }

    fn robot_file(
        &self,
        genotype: &str,
        record: Option<&Record>,
        note: &str,
    ) -> Result<Option<Vec<u8>>, EvaluatorError> {
        let record = record
            .map(serde_json::to_string)
            .transpose()
            .map_err(|e| EvaluatorError::Remote(format!("a record does not serialise: {e}")))?;
        Python::attach(|py| -> PyResult<Option<Vec<u8>>> {
            let callable = self.evaluate.bind(py);
            if !callable.hasattr("robot_file")? {
                return Ok(None);
            }
            callable.call_method1("robot_file", (genotype, record, note))?.extract()
        })
        .map_err(|e| EvaluatorError::Remote(format!("the robot file callable failed: {e}")))
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
/// text. With `evaluate`, every batch goes to that callable (see [`PyTransport`]), whatever the genotype kind; the results are
/// the same bit for bit, since each evaluation is a pure function of (genotype, seed).
#[pyfunction]
#[pyo3(signature = (config, out, resume = false, threads = 0, evaluate = None, verbose = false, solver = None))]
#[allow(clippy::too_many_arguments)]
pub fn run(
    py: Python<'_>,
    config: PathBuf,
    out: PathBuf,
    resume: bool,
    threads: usize,
    evaluate: Option<Py<PyAny>>,
    verbose: bool,
    solver: Option<&str>,
) -> PyResult<String> {
    let experiments = load(&config, solver)?;
    let [experiment]: [Experiment; 1] = experiments.try_into().map_err(|e: Vec<Experiment>| {
        value_error(format!(
            "config: {} is a sweep of {} settings; run each setting's file, or the CLI's `vsrlab run`",
            config.display(),
            e.len()
        ))
    })?;
    let evaluations = match evaluate {
        None => Evaluations::Local,
        Some(callable) => Evaluations::Remote(Arc::new(PyTransport { evaluate: callable })),
    };
    let options = RunOptions {
        threads,
        resume,
        evaluations,
        ..RunOptions::default()
    };
    let mut reporter = Reporter {
        name: experiment.name.clone().unwrap_or_else(|| "experiment".into()),
        interrupted: false,
        verbose,
    };
    let summaries = py.detach(|| {
        vsrlab_experiment::run_configured(&experiment, &out, &options, &mut reporter).map_err(|e| e.to_string())
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

/// An experiment file as it runs: every default written out and every file it names read in
/// (the text a cluster's workers build their evaluator from, with nothing to find on their disk).
/// A sweep of several settings is refused: each setting is its own run.
#[pyfunction]
#[pyo3(signature = (config, solver = None))]
pub fn experiment_text(config: PathBuf, solver: Option<&str>) -> PyResult<String> {
    let experiments = load(&config, solver)?;
    match experiments.as_slice() {
        [experiment] => Ok(experiment.to_toml()),
        many => Err(value_error(format!(
            "config: {} is a sweep of {} settings; run each setting's file",
            config.display(),
            many.len()
        ))),
    }
}

/// Every setting of an experiment file, under `solver` if given (the CLI's `--solver`: the
/// task's 2D physics solver replaced); the error names the argument.
pub(crate) fn load(config: &Path, solver: Option<&str>) -> PyResult<Vec<Experiment>> {
    let mut experiments = config::load_all(config).map_err(value_error)?;
    if let Some(solver) = solver {
        for experiment in &mut experiments {
            experiment
                .task
                .set_solver(solver)
                .map_err(|e| value_error(e.at("solver")))?;
        }
    }
    Ok(experiments)
}
