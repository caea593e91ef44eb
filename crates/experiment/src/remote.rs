//! Evaluations elsewhere: a run whose batches go to other processes or machines (Ray workers,
//! [`Transport`]), and the workers' side, which evaluates them ([`serve`]).
//!
//! Kind-neutral by construction: every [`Genotype`] is serde, so a batch travels as the JSON
//! text of its genotypes, and the evaluations come back as JSON ([`Evaluated`] keeps non-finite
//! values). A worker builds its evaluator by running the experiment's own genotype kind
//! ([`GenotypeKind::run`](crate::genotypes::GenotypeKind::run)) in serving mode: the kind makes
//! the evaluator exactly as for a local run, and the runner hands it to the worker instead of
//! starting the optimizer. So a new genotype kind works on a cluster without a line for it here,
//! and a worker's evaluation is the driver's, bit for bit.

use crate::config::Experiment;
use crate::evaluator::{Evaluated, Evaluator, EvaluatorError, Record};
use crate::genotype::Genotype;
use crate::runner::{RunError, RunOptions, Silent};
use std::fmt;
use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// The version of vsrlab a worker runs, which must be the driver's: the results of one model
/// version only are joined in a run.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Where a run's batches are evaluated, as [`RunOptions::evaluations`] says.
#[derive(Clone, Default)]
pub enum Evaluations {
    /// On this machine's threads.
    #[default]
    Local,
    /// Sent elsewhere: every batch goes to the transport, as JSON genotypes.
    Remote(Arc<dyn Transport>),
    /// Served: no run; the experiment's evaluator goes to the hook (a worker's side).
    Serve(ServeHook),
}

impl fmt::Debug for Evaluations {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Evaluations::Local => "Local",
            Evaluations::Remote(_) => "Remote",
            Evaluations::Serve(_) => "Serve",
        })
    }
}

/// What sends batches elsewhere and brings their evaluations back (Python's Ray evaluator).
pub trait Transport: Send + Sync {
    /// Evaluates `genotypes` (each one genotype's JSON text) with their candidate `seeds`; the
    /// evaluations in the same order.
    fn evaluate(&self, genotypes: &[String], seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError>;

    /// The robot file of a run's best `genotype` (its JSON text), made where the evaluations
    /// run (a co-design robot's policy is learned again there); `None`: made on this machine.
    fn robot_file(
        &self,
        _genotype: &str,
        _record: Option<&Record>,
        _note: &str,
    ) -> Result<Option<Vec<u8>>, EvaluatorError> {
        Ok(None)
    }
}

/// An experiment's evaluator as a worker serves it: genotypes as JSON text.
pub trait Served: Sync {
    /// Evaluates `genotypes` (each one genotype's JSON text) with their candidate `seeds`, on the
    /// worker's threads; the evaluations in the same order.
    fn evaluate(&self, genotypes: &[String], seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError>;

    /// The bytes of `genotype`'s robot file, as the runner writes a run's best.
    fn robot_file(&self, genotype: &str, record: Option<&Record>, note: &str) -> Result<Vec<u8>, EvaluatorError>;
}

/// A worker's hook: called once with the experiment's evaluator, which lives as long as the
/// call does (a worker loops inside it, answering requests).
#[derive(Clone)]
pub struct ServeHook(Arc<Mutex<Option<Hook>>>);

/// The worker's function, called once.
type Hook = Box<dyn FnOnce(&dyn Served) + Send>;

impl ServeHook {
    /// Wraps the hook.
    pub fn new(hook: impl FnOnce(&dyn Served) + Send + 'static) -> ServeHook {
        ServeHook(Arc::new(Mutex::new(Some(Box::new(hook)))))
    }

    /// Calls the hook with `served` (once: a second call does nothing).
    pub(crate) fn call(&self, served: &dyn Served) {
        let hook = self.0.lock().unwrap_or_else(|e| e.into_inner()).take();
        if let Some(hook) = hook {
            hook(served);
        }
    }
}

/// Builds the evaluator of `experiment`, as its genotype kind builds it for a run, and calls
/// `hook` with it, evaluating on `pool` (a worker's experiments share its pool). An error when
/// the kind does not run through the runner (it has no evaluator to serve) or its settings are
/// refused.
pub fn serve(
    experiment: &Experiment,
    pool: Arc<rayon::ThreadPool>,
    hook: impl FnOnce(&dyn Served) + Send + 'static,
) -> Result<(), RunError> {
    let called = Arc::new(AtomicBool::new(false));
    let flag = called.clone();
    let options = RunOptions {
        threads: pool.current_num_threads(),
        evaluations: Evaluations::Serve(ServeHook::new(move |served| {
            flag.store(true, Ordering::SeqCst);
            hook(served);
        })),
        pool: Some(pool),
        ..RunOptions::default()
    };
    crate::run_configured(experiment, Path::new(""), &options, &mut Silent)?;
    if !called.load(Ordering::SeqCst) {
        return Err(RunError::Other(format!(
            "{} genotypes: this kind's runs do not go through the runner, so it cannot serve evaluations",
            experiment.genotype_kind().name()
        )));
    }
    Ok(())
}

/// An evaluator of `G` serving JSON genotypes on a pool of threads.
pub(crate) struct Serving<'a, G> {
    pub(crate) evaluator: &'a dyn Evaluator<G>,
    pub(crate) pool: &'a rayon::ThreadPool,
}

impl<G: Genotype> Served for Serving<'_, G> {
    fn evaluate(&self, genotypes: &[String], seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError> {
        if genotypes.len() != seeds.len() {
            return Err(EvaluatorError::Remote(format!(
                "{} genotypes with {} seeds",
                genotypes.len(),
                seeds.len()
            )));
        }
        let parsed: Vec<G> = genotypes
            .iter()
            .enumerate()
            .map(|(i, text)| parse(text).map_err(|e| EvaluatorError::Remote(format!("genotypes[{i}]: {e}"))))
            .collect::<Result<_, _>>()?;
        let refs: Vec<&G> = parsed.iter().collect();
        self.pool.install(|| self.evaluator.evaluate_batch(&refs, seeds))
    }

    fn robot_file(&self, genotype: &str, record: Option<&Record>, note: &str) -> Result<Vec<u8>, EvaluatorError> {
        let genotype: G = parse(genotype).map_err(|e| EvaluatorError::Remote(format!("genotype: {e}")))?;
        let dir = tempfile_dir()?;
        let path = dir.join("best.robot.json");
        let saved = self
            .pool
            .install(|| self.evaluator.save_robot(&genotype, record, &path, note))
            .and_then(|()| {
                std::fs::read(&path).map_err(|source| EvaluatorError::File {
                    path: path.clone(),
                    source,
                })
            });
        let _ = std::fs::remove_dir_all(&dir);
        saved
    }
}

fn parse<G: Genotype>(text: &str) -> Result<G, serde_json::Error> {
    serde_json::from_str(text)
}

/// A fresh folder under the system's temporary folder, for one robot file.
fn tempfile_dir() -> Result<std::path::PathBuf, EvaluatorError> {
    static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::SeqCst);
    let dir = std::env::temp_dir().join(format!("vsrlab-worker-{}-{n}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|source| EvaluatorError::File {
        path: dir.clone(),
        source,
    })?;
    Ok(dir)
}

/// The runner's evaluator when batches go to a [`Transport`]: everything else (checks, robot
/// replays, descriptors of the genotype) stays with the local evaluator.
pub(crate) struct Sent<'a, G> {
    pub(crate) local: &'a dyn Evaluator<G>,
    pub(crate) transport: &'a dyn Transport,
}

impl<G: Genotype> Sent<'_, G> {
    fn json(genotype: &G) -> Result<String, EvaluatorError> {
        serde_json::to_string(genotype)
            .map_err(|e| EvaluatorError::Remote(format!("a genotype does not serialise: {e}")))
    }
}

impl<G: Genotype> Evaluator<G> for Sent<'_, G> {
    fn evaluate(&self, genotype: &G, candidate_seed: u64) -> Evaluated {
        self.local.evaluate(genotype, candidate_seed)
    }

    fn objectives(&self) -> usize {
        self.local.objectives()
    }

    fn failure(&self, seed: u64, error: String) -> Evaluated {
        self.local.failure(seed, error)
    }

    fn evaluate_batch_reporting(
        &self,
        genotypes: &[&G],
        seeds: &[u64],
        done: &(dyn Fn(usize, &Evaluated) + Sync),
    ) -> Result<Vec<Evaluated>, EvaluatorError> {
        let texts: Vec<String> = genotypes.iter().map(|g| Self::json(g)).collect::<Result<_, _>>()?;
        let evaluated = self.transport.evaluate(&texts, seeds)?;
        if evaluated.len() != genotypes.len() {
            return Err(EvaluatorError::Remote(format!(
                "{} evaluations came back for {} genotypes",
                evaluated.len(),
                genotypes.len()
            )));
        }
        // a batch comes back whole: every evaluation ends at once
        for (index, e) in evaluated.iter().enumerate() {
            done(index, e);
        }
        Ok(evaluated)
    }

    fn save_robot(&self, genotype: &G, record: Option<&Record>, path: &Path, note: &str) -> Result<(), EvaluatorError> {
        match self.transport.robot_file(&Self::json(genotype)?, record, note)? {
            Some(bytes) => vsrlab_tasks::files::write_atomic(path, &bytes).map_err(|source| EvaluatorError::File {
                path: path.to_path_buf(),
                source,
            }),
            None => self.local.save_robot(genotype, record, path, note),
        }
    }

    fn save_replay(&self, genotype: &G, path: &Path, title: &str) -> Result<(), EvaluatorError> {
        self.local.save_replay(genotype, path, title)
    }

    fn genotype_columns(&self) -> &'static [&'static str] {
        self.local.genotype_columns()
    }

    fn genotype_stats(&self, genotype: &G) -> Vec<f64> {
        self.local.genotype_stats(genotype)
    }

    fn check(&self, genotype: &G) -> Result<(), EvaluatorError> {
        self.local.check(genotype)
    }
}
