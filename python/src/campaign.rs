//! Campaigns from Python (`vsrlab.campaign`): many experiment files × their runs side by side,
//! locally on one pool of threads or with every setting's batches sent to a Python callable (a
//! Ray evaluator bound to the setting's experiment, sharing one pool of actors).

use crate::run::PyTransport;
use crate::value_error;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{channel, RecvTimeoutError};
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;
use vsrlab_experiment::campaign::{self as campaigns, CampaignObserver, SettingResult};
use vsrlab_experiment::remote::Evaluations;
use vsrlab_experiment::runner::{Flow, Progress, RunOptions, RunSummary};

/// Every setting of the files, as `[{"name", "out", "text"}]` JSON: the text is the resolved
/// experiment a cluster's workers build their evaluator from.
#[pyfunction]
#[pyo3(signature = (files, out, solver = None))]
pub fn campaign_settings(files: Vec<PathBuf>, out: PathBuf, solver: Option<&str>) -> PyResult<String> {
    let settings = settings(&files, &out, solver)?;
    let list: Vec<serde_json::Value> = settings
        .iter()
        .map(|s| {
            serde_json::json!({
                "name": s.name,
                "out": s.out.display().to_string(),
                "text": s.experiment.to_toml(),
            })
        })
        .collect();
    serde_json::to_string(&list).map_err(value_error)
}

/// Prints a line per finished run when `verbose`; stops every run at its next generation once
/// `interrupted` is set (Ctrl-C on the calling thread).
struct Reporter {
    names: Vec<String>,
    runs: Vec<usize>,
    verbose: bool,
    interrupted: Arc<AtomicBool>,
}

impl CampaignObserver for Reporter {
    fn generation(&mut self, _setting: usize, _progress: &Progress) -> Flow {
        if self.interrupted.load(Ordering::SeqCst) {
            Flow::Interrupt
        } else {
            Flow::Continue
        }
    }

    fn run_finished(&mut self, setting: usize, s: &RunSummary) {
        if self.verbose {
            let best = s.best_fitness.map_or("-".to_string(), |v| format!("{v:.4}"));
            eprintln!(
                "{} run {}/{}: best {best} after {} evaluations ({}), {:.1} s",
                self.names[setting],
                s.run + 1,
                self.runs[setting],
                s.evaluations,
                s.stop_reason,
                s.wall_seconds
            );
        }
    }

    fn notice(&mut self, setting: usize, message: &str) {
        eprintln!("{}: {message}", self.names[setting]);
    }
}

fn result_json(r: &SettingResult) -> serde_json::Value {
    serde_json::json!({
        "name": r.name,
        "out": r.out.display().to_string(),
        "runs": r.runs,
        "summaries": r.summaries,
    })
}

/// Runs every setting of `files` into `out/<setting>` side by side and returns
/// `{"settings": [{"name", "out", "runs", "summaries"}], "table": text}` as JSON. With
/// `evaluators` (one callable per setting, in `campaign_settings`' order), each setting's batches
/// go to its callable; the results are the same bit for bit.
#[pyfunction]
#[pyo3(signature = (files, out, resume = false, threads = 0, evaluators = None, verbose = false, solver = None))]
#[allow(clippy::too_many_arguments)]
pub fn campaign(
    py: Python<'_>,
    files: Vec<PathBuf>,
    out: PathBuf,
    resume: bool,
    threads: usize,
    evaluators: Option<Vec<Py<PyAny>>>,
    verbose: bool,
    solver: Option<&str>,
) -> PyResult<String> {
    let mut settings = settings(&files, &out, solver)?;
    if let Some(evaluators) = evaluators {
        if evaluators.len() != settings.len() {
            return Err(value_error(format!(
                "evaluators: {} callables for {} settings",
                evaluators.len(),
                settings.len()
            )));
        }
        for (setting, evaluate) in settings.iter_mut().zip(evaluators) {
            setting.evaluations = Evaluations::Remote(Arc::new(PyTransport { evaluate }));
        }
    }
    let interrupted = Arc::new(AtomicBool::new(false));
    let mut reporter = Reporter {
        names: settings.iter().map(|s| s.name.clone()).collect(),
        runs: settings.iter().map(|s| s.experiment.runs).collect(),
        verbose,
        interrupted: interrupted.clone(),
    };
    let options = RunOptions {
        threads,
        resume,
        ..RunOptions::default()
    };
    let (done, finished) = channel();
    // behind a lock: a receiver may not cross into `detach` by reference otherwise
    let finished = Mutex::new(finished);
    let outcome = std::thread::scope(|scope| {
        let settings = &settings;
        let options = &options;
        let reporter = &mut reporter;
        scope.spawn(move || {
            let _ = done.send(campaigns::run_campaign(settings, options, reporter));
        });
        // the runs go on in the background; this thread watches for Ctrl-C
        loop {
            match py.detach(|| lock(&finished).recv_timeout(Duration::from_millis(100))) {
                Ok(outcome) => return Some(outcome),
                Err(RecvTimeoutError::Disconnected) => return None,
                Err(RecvTimeoutError::Timeout) => {
                    if py.check_signals().is_err() {
                        interrupted.store(true, Ordering::SeqCst);
                    }
                }
            }
        }
    });
    if interrupted.load(Ordering::SeqCst) {
        return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
            "interrupted: every run keeps its last checkpoint; run again with resume=True to continue",
        ));
    }
    let results = outcome
        .ok_or_else(|| value_error("campaign: its thread stopped without an answer"))?
        .map_err(value_error)?;
    let table = campaigns::table(&settings, &results);
    let answer = serde_json::json!({
        "settings": results.iter().map(result_json).collect::<Vec<_>>(),
        "table": table,
    });
    serde_json::to_string(&answer).map_err(value_error)
}

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The campaign's settings, under `solver` if given (the task's 2D physics solver replaced in
/// every setting); the error names the argument.
fn settings(files: &[PathBuf], out: &Path, solver: Option<&str>) -> PyResult<Vec<campaigns::Setting>> {
    let mut settings = campaigns::settings(files, out).map_err(value_error)?;
    if let Some(solver) = solver {
        for setting in &mut settings {
            setting
                .experiment
                .task
                .set_solver(solver)
                .map_err(|e| value_error(e.at("solver")))?;
        }
    }
    Ok(settings)
}
