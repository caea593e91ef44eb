//! The run loop: ask → evaluate the batch in parallel → tell, with per-generation logs,
//! population snapshots, checkpoints and resume.
//!
//! Output folder of an experiment (every file written atomically, temporary file + rename):
//!
//! ```text
//! OUT/experiment.toml            the resolved experiment (every default written out)
//! OUT/summary.json               per-run results and timings (written when all runs end)
//! OUT/run-00/generations.csv     one row per generation: deterministic columns only
//! OUT/run-00/timings.csv         one row per generation: wall-clock columns
//! OUT/run-00/snapshots/evaluations-0001000.jsonl   the population, every N evaluations
//! OUT/run-00/best.robot.json     the best robot (a robot file)
//! OUT/run-00/best.replay.json    its episode for the browser viewer (`vsrlab view`)
//! OUT/run-00/summary.json        the run's result, timings and overhead (written at its end)
//! OUT/run-00/checkpoint.json     optimizer + run state (while the run is unfinished)
//! OUT/run-00/unfinished-generation.jsonl   evaluations that ended in a long generation (while it runs)
//! OUT/.vsrlab.lock               held by the process writing the folder
//! ```
//!
//! Integrity: checkpoints carry a content hash and the hashes of the files written before them;
//! a finished run's `summary.json` carries the hashes of its deterministic files. `--resume`
//! verifies them, and every genotype and fitness of a checkpoint against the representation,
//! and refuses damaged files with what to do (see [`crate::checkpoint`]).
//!
//! Determinism: evaluations run on a rayon pool but their results are collected in candidate
//! order, and every random number comes from the run seed, so `generations.csv`, the snapshots
//! and the best robot do not depend on the number of threads, nor on whether the run was
//! interrupted and resumed. Only `timings.csv` and the `summary.json` files hold wall-clock
//! figures. (A `stop.wall_seconds` criterion makes the stopping point machine-dependent.)

use crate::checkpoint::{self, content_hash, Checkpoint, RunState, SnapshotEntry};
use crate::config::{Experiment, OutputConfig, StopConfig};
use crate::evaluator::{Evaluated, Evaluator, EvaluatorError, Record};
use crate::genotype::Genotype;
use crate::memory::MemoryLimit;
use crate::optimizers::SearchOptimizer;
use crate::output_lock::{LockError, OutputLock, LOCK_FILE};
use crate::remote::{Evaluations, Sent, Serving};
use crate::unfinished_generation::{Carried, Recorder};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;
use vsrlab_analysis::rows::{GenerationRow, SnapshotRow};
use vsrlab_analysis::run_folder::{
    snapshot_file_name, RunFiles, RunFolder, BEST_ROBOT_FILE, GENERATIONS_FILE, SNAPSHOTS_DIR, SUMMARY_FILE,
    TIMINGS_FILE,
};
use vsrlab_evolution::{Evaluation, Individual, Sense, Told};
use vsrlab_field::FieldError;
use vsrlab_tasks::files::write_atomic;

pub use crate::checkpoint::CHECKPOINT_FORMAT;

/// Header of `timings.csv`.
pub const TIMINGS_HEADER: &str =
    "generation,elapsed_seconds,generation_seconds,evaluation_seconds,episode_cpu_seconds,overhead_seconds";

/// Why a run or an experiment could not go on.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// The experiment cannot run as configured; the error names the field (or the option,
    /// `threads`).
    #[error("{0}")]
    Field(#[from] FieldError),
    /// The output folder is used by another process, or cannot be locked.
    #[error(transparent)]
    Lock(#[from] LockError),
    /// A run would need more memory than allowed.
    #[error(transparent)]
    Memory(#[from] MemoryLimit),
    /// A file or folder of the output does not fit this experiment, or is damaged.
    #[error("{}: {problem}", file.display())]
    Folder {
        /// The file or folder.
        file: PathBuf,
        /// What is wrong with it and what to do.
        problem: String,
    },
    /// The optimizer refused its configuration or a batch.
    #[error("optimizer: {0}")]
    Optimizer(#[from] vsrlab_evolution::EvolutionError),
    /// The worker threads could not be started.
    #[error("thread pool: {0}")]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
    /// A batch of evaluations failed.
    #[error("evaluations: {0}")]
    Evaluations(#[source] EvaluatorError),
    /// The best robot of a run, or its replay, could not be written.
    #[error("best {what} of run {run}: {source}")]
    Best {
        /// `robot` or `replay`.
        what: &'static str,
        /// The run (from 0).
        run: usize,
        /// Why.
        source: EvaluatorError,
    },
    /// Anything else: an internal failure, such as a value that did not serialise.
    #[error("{0}")]
    Other(String),
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> RunError + '_ {
    move |source| RunError::Io {
        path: path.display().to_string(),
        source,
    }
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<(), RunError> {
    write_atomic(path, bytes).map_err(io_error(path))
}

/// Most worker threads a run may ask for.
pub const MAX_THREADS: usize = 1024;

/// How to run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Worker threads for evaluations (0: one per core).
    pub threads: usize,
    /// Continue runs from their checkpoints (and skip finished runs) instead of refusing a
    /// non-empty output folder.
    pub resume: bool,
    /// Most bytes one run may be estimated to need (`None`: [`DEFAULT_MEMORY_LIMIT`](crate::memory::DEFAULT_MEMORY_LIMIT)); see
    /// [`crate::memory`].
    pub memory_limit: Option<u64>,
    /// Where batches are evaluated: here (the default), sent elsewhere, or served to a worker
    /// ([`crate::remote`]).
    pub evaluations: Evaluations,
    /// A thread pool the evaluations share with other experiments (a campaign's); `None`: a
    /// pool of `threads` of the run's own.
    pub pool: Option<Arc<rayon::ThreadPool>>,
    /// Run an experiment's runs side by side, each on its own thread, their batches on the same
    /// pool (a campaign's: small batches of many runs keep the cores or a cluster busy). The
    /// results are the same: each run is a pure function of its seed.
    pub concurrent_runs: bool,
}

/// Whether the runner should go on after a generation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Go on.
    Continue,
    /// Stop now, as if the process were killed right after the checkpoint (no final files).
    Interrupt,
}

/// What the runner reports after each generation.
#[derive(Debug, Clone, PartialEq)]
pub struct Progress {
    /// Run index.
    pub run: usize,
    /// Number of runs.
    pub runs: usize,
    /// Completed generations.
    pub generation: u64,
    /// Evaluations so far.
    pub evaluations: u64,
    /// Best fitness so far.
    pub best_fitness: f64,
    /// Progress towards the nearest stop criterion, in [0, 1].
    pub fraction: f64,
    /// Wall-clock seconds of this run so far.
    pub elapsed: f64,
}

/// Receives progress; the CLI draws progress bars with it. `Send`: runs side by side report to
/// one observer from their threads.
pub trait Observer: Send {
    /// A run starts (or resumes, with `progress` where it left off).
    fn run_started(&mut self, _progress: &Progress) {}
    /// A generation ended (after its checkpoint was written).
    fn generation(&mut self, _progress: &Progress) -> Flow {
        Flow::Continue
    }
    /// A run ended, or was found finished when resuming.
    fn run_finished(&mut self, _summary: &RunSummary) {}
    /// Something the user should know that does not stop the experiment (a run restarted for
    /// lack of a checkpoint, an unverifiable old checkpoint, an output folder that cannot be
    /// locked).
    fn notice(&mut self, _message: &str) {}
}

/// An observer that does nothing.
pub struct Silent;

impl Observer for Silent {}

/// The result and timings of one run (`run-XX/summary.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Run index.
    pub run: usize,
    /// Run seed.
    pub seed: u64,
    /// Which stop criterion ended the run.
    pub stop_reason: String,
    /// Generations.
    pub generations: u64,
    /// Evaluations.
    pub evaluations: u64,
    /// Births.
    pub births: u64,
    /// Failed evaluations (worst fitness given).
    pub failures: u64,
    /// Best fitness (`None` if every evaluation failed).
    pub best_fitness: Option<f64>,
    /// Generation in which the best was born.
    pub best_birth_generation: Option<u64>,
    /// Body of the best.
    pub best_body: Option<String>,
    /// Wall-clock seconds (over all sessions of the run).
    pub wall_seconds: f64,
    /// Wall-clock seconds spent evaluating batches (episodes, in parallel).
    pub evaluation_seconds: f64,
    /// Wall-clock seconds outside batch evaluation: optimizer, logs, snapshots, checkpoints.
    pub overhead_seconds: f64,
    /// `overhead_seconds / wall_seconds`.
    pub overhead_fraction: f64,
    /// Sum over evaluations of their own duration (CPU seconds across threads).
    pub episode_cpu_seconds: f64,
    /// Threads used by the last session.
    pub threads: usize,
    /// Content hashes of the run's deterministic files (path inside the run folder → hash),
    /// verified when an experiment is resumed.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub files: BTreeMap<String, String>,
    /// Content hash of this summary as written without its seal, so that `--resume` can tell an
    /// edited or damaged summary from the one the run wrote (absent in older summaries).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seal: Option<String>,
}

impl RunSummary {
    /// This summary's file text, sealed.
    fn sealed_text(&self) -> String {
        let sealed = RunSummary {
            seal: Some(content_hash(self.unsealed_text().as_bytes())),
            ..self.clone()
        };
        serde_json::to_string_pretty(&sealed).expect("summaries serialise")
    }

    fn unsealed_text(&self) -> String {
        serde_json::to_string_pretty(&RunSummary {
            seal: None,
            ..self.clone()
        })
        .expect("summaries serialise")
    }

    /// Whether the seal matches the content (`None`: no seal, an older vsrlab's summary).
    fn seal_holds(&self) -> Option<bool> {
        let seal = self.seal.as_ref()?;
        Some(*seal == content_hash(self.unsealed_text().as_bytes()))
    }
}

/// What the runner needs of an experiment besides its optimizer and evaluator.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// A short name, for notes.
    pub name: Option<String>,
    /// The resolved configuration, written to `experiment.toml` and compared on resume.
    pub resolved: String,
    /// One seed per run.
    pub run_seeds: Vec<u64>,
    /// When each run stops.
    pub stop: StopConfig,
    /// What is written.
    pub output: OutputConfig,
    /// Snapshots hold each generation whole, not only its survivors
    /// (`GenotypeKind::snapshots_whole_generation`).
    pub snapshot_generation_pool: bool,
}

impl Plan {
    /// The plan of an experiment file.
    pub fn of(experiment: &Experiment) -> Plan {
        Plan {
            name: experiment.name.clone(),
            resolved: experiment.to_toml(),
            run_seeds: experiment.run_seeds(),
            stop: experiment.stop.clone(),
            output: experiment.output.clone(),
            snapshot_generation_pool: experiment.genotype_kind().snapshots_whole_generation(),
        }
    }
}

/// The element at index n/2 of the values sorted from worst to best (jgea's median), NaN
/// first (the worst).
fn median(values: &[f64], sense: Sense) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let mut v = values.to_vec();
    v.sort_by(|&a, &b| sense.compare(a, b));
    v[v.len() / 2]
}

/// The best value under `sense` (NaN when every value is NaN).
fn best_of(values: &[f64], sense: Sense) -> f64 {
    values
        .iter()
        .copied()
        .filter(|v| !v.is_nan())
        .reduce(|a, b| if sense.compare(b, a).is_gt() { b } else { a })
        .unwrap_or(f64::NAN)
}

/// The files of an output folder whose content is a pure function of the experiment and its
/// seed (every file but `timings.csv` and the `summary.json` files, which hold wall-clock
/// figures), as (path relative to `out`, bytes), sorted: what two runs of one experiment must
/// share, whatever their thread counts and interruptions.
pub fn deterministic_files(out: &Path) -> std::io::Result<Vec<(String, Vec<u8>)>> {
    let mut files = Vec::new();
    let mut stack = vec![out.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir)? {
            let path = entry?.path();
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
            if path.is_dir() {
                stack.push(path);
            } else if !matches!(name.as_deref(), Some(TIMINGS_FILE | SUMMARY_FILE | LOCK_FILE)) {
                let rel = path.strip_prefix(out).unwrap_or(&path).display().to_string();
                files.push((rel, std::fs::read(&path)?));
            }
        }
    }
    files.sort();
    Ok(files)
}

/// The folder of run `run` out of `runs` (the layout is [`RunFolder`]'s, shared with the
/// analyses that read it).
pub fn run_dir(out: &Path, run: usize, runs: usize) -> PathBuf {
    RunFolder::new(out).run_dir(run, runs)
}

/// Builds a run's optimizer from its seed (`Sync`: runs side by side build theirs on their own
/// threads).
pub type NewOptimizer<'a, O> = dyn Fn(u64) -> Result<O, RunError> + Sync + 'a;

/// Runs every run of a plan into `out` with optimizers of any genotype type: `new_optimizer`
/// builds the optimizer of a run from its seed.
pub fn run_search<G: Genotype, O: SearchOptimizer<G>>(
    plan: &Plan,
    new_optimizer: &NewOptimizer<'_, O>,
    evaluator: &dyn Evaluator<G>,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    check_threads(options)?;
    match &options.evaluations {
        Evaluations::Local => run_plan(plan, new_optimizer, evaluator, out, options, observer),
        Evaluations::Remote(transport) => {
            let sent = Sent {
                local: evaluator,
                transport: transport.as_ref(),
            };
            run_plan(plan, new_optimizer, &sent, out, options, observer)
        }
        Evaluations::Serve(hook) => {
            hook.call(&Serving {
                evaluator,
                pool: &*pool_of(options)?,
            });
            Ok(Vec::new())
        }
    }
}

/// [`run_search`] with the batches evaluated by `evaluator`.
fn run_plan<G: Genotype, O: SearchOptimizer<G>>(
    plan: &Plan,
    new_optimizer: &NewOptimizer<'_, O>,
    evaluator: &dyn Evaluator<G>,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    std::fs::create_dir_all(out).map_err(io_error(out))?;
    let lock = OutputLock::acquire(out)?;
    if lock.unsupported() {
        observer.notice(&format!(
            "{}: this file system cannot lock files, so nothing stops a second process from writing here",
            out.display()
        ));
    }
    let resolved = &plan.resolved;
    let folder = RunFolder::new(out);
    let config_path = folder.experiment_toml();
    match std::fs::read_to_string(&config_path) {
        Ok(existing) if !options.resume => {
            let _ = existing;
            return Err(RunError::Folder {
                file: out.to_path_buf(),
                problem: "holds an experiment already: pass --resume to continue it, or choose another output folder"
                    .into(),
            });
        }
        Ok(existing) if &existing != resolved => {
            return Err(RunError::Folder {
                file: out.to_path_buf(),
                problem: format!(
                    "written by a different experiment configuration: resuming needs the same file \
                     (compare with {})",
                    config_path.display()
                ),
            });
        }
        Ok(_) => {}
        Err(_) => {
            if options.resume {
                observer.notice(&format!(
                    "{} holds no experiment yet: nothing to resume, starting it",
                    out.display()
                ));
            }
            write_file(&config_path, resolved.as_bytes())?;
        }
    }
    let pool = pool_of(options)?;
    let session = Session {
        plan,
        evaluator,
        new_optimizer,
        options,
        pool: &pool,
    };
    let runs = plan.run_seeds.len();
    let slots: Vec<(usize, u64, RunFiles)> = (plan.run_seeds.iter().enumerate())
        .map(|(run, &seed)| (run, seed, folder.run(run, runs)))
        .collect();
    let one = |(run, seed, files): &(usize, u64, RunFiles), observer: &mut dyn Observer| {
        let slot = RunSlot {
            run: *run,
            seed: *seed,
            files,
        };
        run_one(&session, &slot, observer)
    };
    let mut outcomes = Vec::with_capacity(runs);
    if options.concurrent_runs && runs > 1 {
        let shared = Mutex::new(observer);
        outcomes = side_by_side(&slots, "run", |slot, failed| {
            one(
                slot,
                &mut Relay {
                    shared: &shared,
                    failed,
                },
            )
        });
    } else {
        for slot in &slots {
            let outcome = one(slot, observer);
            let go_on = matches!(outcome, Ok(Some(_)));
            outcomes.push(outcome);
            if !go_on {
                break;
            }
        }
    }
    let mut summaries = Vec::new();
    let mut interrupted = false;
    for outcome in outcomes {
        match outcome? {
            Some(summary) => summaries.push(summary),
            None => interrupted = true,
        }
    }
    if interrupted {
        return Ok(summaries);
    }
    let text = serde_json::to_string_pretty(&summaries).expect("summaries serialise");
    write_file(&folder.summary_json(), text.as_bytes())?;
    Ok(summaries)
}

/// The pool a run evaluates on: the shared one of its options, or its own of `threads`.
pub(crate) fn pool_of(options: &RunOptions) -> Result<Arc<rayon::ThreadPool>, RunError> {
    match &options.pool {
        Some(shared) => Ok(shared.clone()),
        None => Ok(Arc::new(
            rayon::ThreadPoolBuilder::new().num_threads(options.threads).build()?,
        )),
    }
}

/// Runs `work` on every item at once, each on a thread of its own named `<what>-<index>`; the
/// outcomes in the items' order. The flag `work` is given is set when any item fails, so that
/// the others can stop early (at their next checkpoint).
pub(crate) fn side_by_side<I: Sync, T: Send>(
    items: &[I],
    what: &str,
    work: impl Fn(&I, &AtomicBool) -> Result<T, RunError> + Sync,
) -> Vec<Result<T, RunError>> {
    let failed = AtomicBool::new(false);
    std::thread::scope(|scope| {
        let threads: Vec<_> = (items.iter().enumerate())
            .map(|(index, item)| {
                let (work, failed) = (&work, &failed);
                std::thread::Builder::new()
                    .name(format!("vsrlab-{what}-{index}"))
                    .stack_size(RUN_THREAD_STACK)
                    .spawn_scoped(scope, move || {
                        let outcome = work(item, failed);
                        if outcome.is_err() {
                            failed.store(true, Ordering::SeqCst);
                        }
                        outcome
                    })
            })
            .collect();
        (threads.into_iter())
            .map(|thread| match thread {
                Ok(handle) => handle
                    .join()
                    .unwrap_or_else(|_| Err(RunError::Other(format!("a {what}'s thread panicked")))),
                Err(e) => Err(RunError::Other(format!("a {what}'s thread could not start: {e}"))),
            })
            .collect()
    })
}

/// Stack of a run's own thread when runs go side by side (the optimizer's work runs there).
const RUN_THREAD_STACK: usize = 16 << 20;

/// One run's view of an observer that runs side by side share.
struct Relay<'a, 'b> {
    shared: &'a Mutex<&'b mut dyn Observer>,
    /// Set when a run failed: the others stop at their next checkpoint.
    failed: &'a AtomicBool,
}

impl<'a, 'b> Relay<'a, 'b> {
    fn lock(&self) -> std::sync::MutexGuard<'a, &'b mut dyn Observer> {
        self.shared.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl Observer for Relay<'_, '_> {
    fn run_started(&mut self, progress: &Progress) {
        self.lock().run_started(progress);
    }
    fn generation(&mut self, progress: &Progress) -> Flow {
        let flow = self.lock().generation(progress);
        if self.failed.load(Ordering::SeqCst) {
            Flow::Interrupt
        } else {
            flow
        }
    }
    fn run_finished(&mut self, summary: &RunSummary) {
        self.lock().run_finished(summary);
    }
    fn notice(&mut self, message: &str) {
        self.lock().notice(message);
    }
}

/// The worker threads a run asking for `requested` gets: one per core for 0, at most
/// [`MAX_THREADS`].
pub fn worker_threads(requested: usize) -> usize {
    match requested {
        0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
        n => n.min(MAX_THREADS),
    }
}

/// Refuses more than [`MAX_THREADS`] worker threads.
pub(crate) fn check_threads(options: &RunOptions) -> Result<(), RunError> {
    if options.threads > MAX_THREADS {
        return Err(RunError::Field(FieldError::new(
            "threads",
            format!("at most {MAX_THREADS} worker threads, got {}", options.threads),
        )));
    }
    Ok(())
}

/// Which stop criterion holds, if any: the configured ones first, then the optimizer's own
/// (e.g. `"cma-es:tolfun"`, see [`SearchOptimizer::stop_reason`]).
fn stop_reason<G, O: SearchOptimizer<G>>(stop: &StopConfig, optimizer: &O, wall: f64) -> Option<&'static str> {
    if let (Some(target), Some(best)) = (stop.target_fitness, optimizer.best()) {
        if first_sense(optimizer).reaches(best.fitness(), target) {
            return Some("target_fitness");
        }
    }
    if stop.evaluations.is_some_and(|n| optimizer.evaluations() >= n) {
        return Some("evaluations");
    }
    if stop.births.is_some_and(|n| optimizer.births() >= n) {
        return Some("births");
    }
    if stop.generations.is_some_and(|n| optimizer.generation() >= n) {
        return Some("generations");
    }
    if stop.wall_seconds.is_some_and(|s| wall >= s) {
        return Some("wall_seconds");
    }
    optimizer.stop_reason()
}

/// The sense of the first objective.
fn first_sense<G, O: SearchOptimizer<G>>(optimizer: &O) -> Sense {
    optimizer.senses().first().copied().unwrap_or_default()
}

fn fraction<G, O: SearchOptimizer<G>>(stop: &StopConfig, optimizer: &O, wall: f64) -> f64 {
    stop.fraction(
        optimizer.evaluations(),
        optimizer.births(),
        optimizer.generation(),
        wall,
    )
}

/// Reads a file and cuts it to `bytes` (what the checkpoint covers).
fn read_truncated(path: &Path, bytes: u64) -> Result<String, RunError> {
    let text = std::fs::read_to_string(path).map_err(io_error(path))?;
    let cut = usize::try_from(bytes).unwrap_or(usize::MAX);
    if text.len() < cut || !text.is_char_boundary(cut) {
        return Err(RunError::Folder {
            file: path.to_path_buf(),
            problem: format!(
                "shorter than its checkpoint says ({} < {cut} bytes): the run folder is damaged",
                text.len()
            ),
        });
    }
    Ok(text[..cut].to_string())
}

/// What every run of one call shares.
struct Session<'a, G, O> {
    plan: &'a Plan,
    evaluator: &'a dyn Evaluator<G>,
    new_optimizer: &'a NewOptimizer<'a, O>,
    options: &'a RunOptions,
    pool: &'a rayon::ThreadPool,
}

/// One run's place: which run, its seed and its files.
struct RunSlot<'a> {
    run: usize,
    seed: u64,
    files: &'a RunFiles,
}

/// The text of a run's two logs as written so far (`generations.csv`, `timings.csv`).
struct RunLogs {
    csv: String,
    timings: String,
}

/// What one generation's batch gave, besides what the optimizer was told.
struct BatchResult {
    fitness: Vec<f64>,
    failures: u64,
    evaluation_seconds: f64,
    episode_cpu: f64,
}

/// Runs (or resumes, or confirms as finished) one run; `None` when the observer interrupted it.
fn run_one<G: Genotype, O: SearchOptimizer<G>>(
    session: &Session<'_, G, O>,
    slot: &RunSlot<'_>,
    observer: &mut dyn Observer,
) -> Result<Option<RunSummary>, RunError> {
    if session.options.resume {
        if let Some(summary) = finished_summary(slot.files, observer)? {
            observer.run_finished(&summary);
            return Ok(Some(summary));
        }
    }
    let (mut optimizer, mut state, mut logs) = start_or_resume(session, slot, observer)?;
    let mut carried = if session.options.resume {
        carried_evaluations::<G>(slot, session.plan.run_seeds.len(), observer)
    } else {
        Carried::default()
    };
    let plan = session.plan;
    let every = plan.output.snapshot_every;
    let session_start = Instant::now();
    let wall_before = state.wall_seconds;
    let wall = |start: &Instant| wall_before + start.elapsed().as_secs_f64();
    let progress = |optimizer: &O, wall: f64| Progress {
        run: slot.run,
        runs: plan.run_seeds.len(),
        generation: optimizer.generation(),
        evaluations: optimizer.evaluations(),
        best_fitness: optimizer.best().map_or(f64::NAN, |b| b.fitness()),
        fraction: fraction(&plan.stop, optimizer, wall),
        elapsed: wall,
    };
    observer.run_started(&progress(&optimizer, wall_before));
    let mut last_checkpoint = Instant::now();
    let reason = loop {
        if let Some(reason) = stop_reason(&plan.stop, &optimizer, wall(&session_start)) {
            break reason;
        }
        let generation_start = Instant::now();
        let batch = evaluate_generation(session, slot.files, &mut optimizer, &mut state, &mut carried)?;
        log_generation(session.evaluator, &optimizer, &state, &batch, &mut logs.csv);
        write_file(&slot.files.generations_csv(), logs.csv.as_bytes())?;
        if every > 0 && optimizer.evaluations() >= state.next_snapshot {
            write_snapshot(slot.files, snapshot_members(plan, &optimizer), &optimizer, &mut state)?;
            while state.next_snapshot <= optimizer.evaluations() {
                state.next_snapshot += every;
            }
        }
        log_timings(
            &optimizer,
            &mut state,
            &batch,
            generation_start,
            wall(&session_start),
            &mut logs.timings,
        );
        write_file(&slot.files.timings_csv(), logs.timings.as_bytes())?;
        state.wall_seconds = wall(&session_start);
        if last_checkpoint.elapsed().as_secs_f64() >= plan.output.checkpoint_interval {
            state.csv_bytes = logs.csv.len() as u64;
            state.csv_hash = content_hash(logs.csv.as_bytes());
            state.timings_bytes = logs.timings.len() as u64;
            write_checkpoint(&slot.files.checkpoint_json(), slot.run, slot.seed, &state, &optimizer)?;
            forget_unfinished_generation(slot.files);
            last_checkpoint = Instant::now();
        }
        if observer.generation(&progress(&optimizer, wall(&session_start))) == Flow::Interrupt {
            return Ok(None);
        }
    };
    let summary = finish_run(
        session,
        slot,
        &optimizer,
        &mut state,
        &logs,
        reason,
        wall(&session_start),
    )?;
    observer.run_finished(&summary);
    Ok(Some(summary))
}

/// The summary of a run that a previous session finished, verified against its files.
fn finished_summary(files: &RunFiles, observer: &mut dyn Observer) -> Result<Option<RunSummary>, RunError> {
    let summary_path = files.summary_json();
    let Ok(text) = std::fs::read_to_string(&summary_path) else {
        return Ok(None);
    };
    let mut summary: RunSummary = serde_json::from_str(&text).map_err(|e| RunError::Folder {
        file: summary_path.clone(),
        problem: e.to_string(),
    })?;
    verify_finished(files, &summary, observer)?;
    summary.seal = None; // as a run that finishes in this session reports it
    Ok(Some(summary))
}

/// The evaluations saved from the generation a previous session left unfinished (none when
/// there are none, or when the file does not read: that generation is then evaluated again).
fn carried_evaluations<G: Genotype>(slot: &RunSlot<'_>, runs: usize, observer: &mut dyn Observer) -> Carried {
    match Carried::load::<G>(&slot.files.unfinished_generation()) {
        Ok(carried) => {
            if !carried.is_empty() {
                observer.notice(&format!(
                    "run {}/{runs}: {} evaluations of the generation under way when it stopped are reused",
                    slot.run + 1,
                    carried.len()
                ));
            }
            carried
        }
        Err(e) => {
            observer.notice(&format!("{e}: the generation it holds is evaluated again"));
            Carried::default()
        }
    }
}

/// Deletes the unfinished generation's evaluations once a checkpoint covers them.
fn forget_unfinished_generation(files: &RunFiles) {
    let _ = std::fs::remove_file(files.unfinished_generation());
}

/// The optimizer, state and logs a run goes on from: its checkpoint when resuming one, or a new
/// optimizer from the run seed.
fn start_or_resume<G: Genotype, O: SearchOptimizer<G>>(
    session: &Session<'_, G, O>,
    slot: &RunSlot<'_>,
    observer: &mut dyn Observer,
) -> Result<(O, RunState, RunLogs), RunError> {
    let Session {
        plan,
        evaluator,
        new_optimizer,
        options,
        ..
    } = *session;
    let files = slot.files;
    let started_before = files.generations_csv().exists();
    let snapshots = files.snapshots_dir();
    std::fs::create_dir_all(&snapshots).map_err(io_error(&snapshots))?;
    if options.resume {
        remove_stale_temporaries(files.dir());
        remove_stale_temporaries(&snapshots);
        match std::fs::read(files.checkpoint_json()) {
            Ok(bytes) => {
                let (optimizer, state, csv, timings) =
                    load_checkpoint::<G, O>(&bytes, files, slot.run, slot.seed, evaluator, observer)?;
                return Ok((optimizer, state, RunLogs { csv, timings }));
            }
            Err(_) if started_before => observer.notice(&format!(
                "run {}/{}: no checkpoint was written before it stopped; starting it from the beginning \
                 (it gives the same results)",
                slot.run + 1,
                plan.run_seeds.len()
            )),
            Err(_) => {}
        }
    }
    let state = RunState {
        next_snapshot: plan.output.snapshot_every,
        ..RunState::default()
    };
    let logs = RunLogs {
        csv: format!("{}\n", GenerationRow::header(evaluator.genotype_columns())),
        timings: format!("{TIMINGS_HEADER}\n"),
    };
    Ok((new_optimizer(slot.seed)?, state, logs))
}

/// Ask → evaluate the batch on the pool → tell; keeps the records of the population and the
/// best. Candidates whose evaluation a killed session saved (`carried`) are not evaluated again;
/// a long generation's evaluations are saved as they end ([`Recorder`]).
fn evaluate_generation<G: Genotype, O: SearchOptimizer<G>>(
    session: &Session<'_, G, O>,
    files: &RunFiles,
    optimizer: &mut O,
    state: &mut RunState,
    carried: &mut Carried,
) -> Result<BatchResult, RunError> {
    // The optimizer's own parallel steps (CMA-ES's sampling, covariance update and
    // decomposition) run on the run's pool too, so `--threads` bounds them as well.
    let batch = session.pool.install(|| optimizer.ask());
    let evaluation_start = Instant::now();
    let mut slots: Vec<Option<Evaluated>> = batch.iter().map(|c| carried.take(c.seed, &c.genotype)).collect();
    let recorder = Recorder::new(
        files.unfinished_generation(),
        session.plan.output.checkpoint_interval,
        batch.iter().map(|c| &c.genotype).collect(),
        batch.iter().map(|c| c.seed).collect(),
    );
    for (index, saved) in slots.iter().enumerate() {
        if let Some(saved) = saved {
            recorder.done(index, saved);
        }
    }
    let todo: Vec<usize> = (0..batch.len()).filter(|&i| slots[i].is_none()).collect();
    let genotypes: Vec<&G> = todo.iter().map(|&i| &batch[i].genotype).collect();
    let seeds: Vec<u64> = todo.iter().map(|&i| batch[i].seed).collect();
    let done = |j: usize, e: &Evaluated| recorder.done(todo[j], e);
    let fresh: Vec<Evaluated> = session
        .pool
        .install(|| session.evaluator.evaluate_batch_reporting(&genotypes, &seeds, &done))
        .map_err(RunError::Evaluations)?;
    if fresh.len() != todo.len() {
        return Err(RunError::Other(format!(
            "evaluations: {} results for a batch of {}",
            fresh.len(),
            todo.len()
        )));
    }
    if let Some(e) = recorder.into_error() {
        return Err(io_error(&files.unfinished_generation())(e));
    }
    for (i, evaluated) in todo.into_iter().zip(fresh) {
        slots[i] = Some(evaluated);
    }
    let results: Vec<Evaluated> = slots.into_iter().flatten().collect();
    let summary = BatchResult {
        fitness: results.iter().map(|e| e.fitness()).collect(),
        failures: results.iter().filter(|e| e.failed()).count() as u64,
        evaluation_seconds: evaluation_start.elapsed().as_secs_f64(),
        episode_cpu: results.iter().map(|e| e.seconds).sum(),
    };
    let mut told = Vec::with_capacity(batch.len());
    let mut records = Vec::with_capacity(batch.len());
    for (candidate, evaluated) in batch.iter().zip(results) {
        records.push((candidate.genotype.key(), evaluated.objectives.clone(), evaluated.record));
        told.push(Told {
            id: candidate.id,
            evaluation: Evaluation {
                objectives: evaluated.objectives,
                descriptor: evaluated.descriptor,
                outcome: evaluated.features,
            },
        });
    }
    session.pool.install(|| optimizer.tell(told))?;
    keep_best_record(optimizer.best(), &records, state);
    for (key, _, record) in records {
        state.records.insert(key, record);
    }
    let keep: BTreeSet<u64> = snapshot_members(session.plan, optimizer)
        .iter()
        .map(|i| i.genotype.key())
        .collect();
    state.records.retain(|k, _| keep.contains(k));
    state.failures += summary.failures;
    Ok(summary)
}

/// Keeps the record of the optimizer's best: the batch's own when the best is one of its
/// evaluations. A genotype can be evaluated more than once (NEAT's elites are, each time with a
/// new seed): the best robot must be the evaluation that earned the best fitness, so an
/// evaluation is matched by genotype and by its objectives' bits, not by genotype alone.
fn keep_best_record<G: Genotype>(
    best: Option<&Individual<G>>,
    batch: &[(u64, Vec<f64>, Record)],
    state: &mut RunState,
) {
    let Some(best) = best else {
        return;
    };
    let key = best.genotype.key();
    let same_bits = |objectives: &[f64]| {
        objectives.len() == best.objectives.len()
            && objectives
                .iter()
                .zip(&best.objectives)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    };
    if let Some((_, _, record)) = batch.iter().find(|(k, o, _)| *k == key && same_bits(o)) {
        state.best = Some((key, record.clone()));
    } else if state.best.as_ref().map(|b| b.0) != Some(key) {
        state.best = state.records.get(&key).map(|r| (key, r.clone()));
    }
}

/// Appends the generation's row (deterministic columns) to `generations.csv`'s text.
fn log_generation<G: Genotype, O: SearchOptimizer<G>>(
    evaluator: &dyn Evaluator<G>,
    optimizer: &O,
    state: &RunState,
    batch: &BatchResult,
    csv: &mut String,
) {
    let sense = first_sense(optimizer);
    let population = optimizer.population();
    let population_fitness: Vec<f64> = population.iter().map(|i| i.fitness()).collect();
    let records: Vec<Option<&Record>> = population
        .iter()
        .map(|i| state.records.get(&i.genotype.key()))
        .collect();
    let bodies: BTreeSet<&str> = records
        .iter()
        .filter_map(|r| r.and_then(|r| r.body.as_deref()))
        .collect();
    let voxels: Vec<usize> = records.iter().filter_map(|r| r.and_then(|r| r.voxels)).collect();
    let mean_voxels = if voxels.is_empty() {
        f64::NAN
    } else {
        voxels.iter().sum::<usize>() as f64 / voxels.len() as f64
    };
    // the best genotype's own statistics (graph size, …), when its kind logs any
    let names = evaluator.genotype_columns();
    let stats = match optimizer.best() {
        Some(b) if !names.is_empty() => evaluator.genotype_stats(&b.genotype),
        _ => Vec::new(),
    };
    let row = GenerationRow {
        generation: optimizer.generation(),
        evaluations: optimizer.evaluations(),
        births: optimizer.births(),
        failures: batch.failures,
        best_fitness: optimizer.best().map_or(f64::NAN, |b| b.fitness()),
        batch_best: best_of(&batch.fitness, sense),
        batch_median: median(&batch.fitness, sense),
        population_best: best_of(&population_fitness, sense),
        population_median: median(&population_fitness, sense),
        population_size: population.len() as u64,
        distinct_bodies: bodies.len() as u64,
        mean_voxels,
        species: optimizer.species().map(|s| s as u64),
        archive_cells: optimizer.archive_cells().map(|s| s as u64),
        best_stats: names
            .iter()
            .enumerate()
            .map(|(k, name)| (name.to_string(), stats.get(k).copied().unwrap_or(f64::NAN)))
            .collect(),
    };
    csv.push_str(&row.to_csv());
    csv.push('\n');
}

/// Appends the generation's wall-clock row to `timings.csv`'s text (kept apart from the
/// deterministic CSV) and adds its times to the run's totals.
fn log_timings<G, O: SearchOptimizer<G>>(
    optimizer: &O,
    state: &mut RunState,
    batch: &BatchResult,
    generation_start: Instant,
    wall: f64,
    timings: &mut String,
) {
    let generation_seconds = generation_start.elapsed().as_secs_f64();
    state.evaluation_seconds += batch.evaluation_seconds;
    state.episode_cpu_seconds += batch.episode_cpu;
    let _ = writeln!(
        timings,
        "{},{:.6},{:.6},{:.6},{:.6},{:.6}",
        optimizer.generation(),
        wall,
        generation_seconds,
        batch.evaluation_seconds,
        batch.episode_cpu,
        generation_seconds - batch.evaluation_seconds,
    );
}

/// The run is over: final population, best robot and replay, the summary with the hashes of
/// the deterministic files; the checkpoint is no longer needed.
fn finish_run<G: Genotype, O: SearchOptimizer<G>>(
    session: &Session<'_, G, O>,
    slot: &RunSlot<'_>,
    optimizer: &O,
    state: &mut RunState,
    logs: &RunLogs,
    reason: &str,
    wall_seconds: f64,
) -> Result<RunSummary, RunError> {
    let RunSlot { run, seed, files } = *slot;
    if state.last_snapshot != Some(optimizer.evaluations()) {
        write_snapshot(files, snapshot_members(session.plan, optimizer), optimizer, state)?;
    }
    // a run whose every evaluation failed has no best robot: its summary says so (no best
    // fitness, as many failures as evaluations) instead of the run failing on its replay
    let all_failed = optimizer.evaluations() > 0 && state.failures >= optimizer.evaluations();
    let best = optimizer.best().filter(|_| !all_failed);
    let mut manifest = BTreeMap::new();
    manifest.insert(GENERATIONS_FILE.to_string(), content_hash(logs.csv.as_bytes()));
    for snapshot in &state.snapshots {
        let name = format!("{SNAPSHOTS_DIR}/{}", snapshot_file_name(snapshot.evaluations));
        manifest.insert(name, snapshot.hash.clone());
    }
    if let (true, Some(best)) = (session.plan.output.save_best, best) {
        let record = state.best.as_ref().filter(|b| b.0 == best.genotype.key()).map(|b| &b.1);
        if let Some(hash) = save_best(session, slot, optimizer, best, record)? {
            manifest.insert(BEST_ROBOT_FILE.to_string(), hash);
        }
    }
    let overhead = (wall_seconds - state.evaluation_seconds).max(0.0);
    let best_record = state.best.as_ref().map(|b| &b.1).filter(|_| !all_failed);
    let summary = RunSummary {
        run,
        seed,
        stop_reason: reason.to_string(),
        generations: optimizer.generation(),
        evaluations: optimizer.evaluations(),
        births: optimizer.births(),
        failures: state.failures,
        best_fitness: best.map(|b| b.fitness()).filter(|f| !f.is_nan()),
        best_birth_generation: best.map(|b| b.birth_generation),
        best_body: best_record.and_then(|r| r.body.clone()),
        wall_seconds,
        evaluation_seconds: state.evaluation_seconds,
        overhead_seconds: overhead,
        overhead_fraction: if wall_seconds > 0.0 {
            overhead / wall_seconds
        } else {
            0.0
        },
        episode_cpu_seconds: state.episode_cpu_seconds,
        threads: session.pool.current_num_threads(),
        files: manifest,
        seal: None,
    };
    write_file(&files.summary_json(), summary.sealed_text().as_bytes())?;
    let _ = std::fs::remove_file(files.checkpoint_json());
    forget_unfinished_generation(files);
    Ok(summary)
}

/// Writes the best robot's file and replay; the robot file's hash when there is one.
fn save_best<G: Genotype, O: SearchOptimizer<G>>(
    session: &Session<'_, G, O>,
    slot: &RunSlot<'_>,
    optimizer: &O,
    best: &Individual<G>,
    record: Option<&Record>,
) -> Result<Option<String>, RunError> {
    let RunSlot { run, seed, files } = *slot;
    let name = session.plan.name.as_deref().unwrap_or("experiment");
    let note = format!(
        "{name}: run {run} (seed {seed}), best of {} evaluations, born in generation {}, fitness {}",
        optimizer.evaluations(),
        best.birth_generation,
        best.fitness()
    );
    session
        .evaluator
        .save_robot(&best.genotype, record, &files.best_robot(), &note)
        .map_err(|source| RunError::Best {
            what: "robot",
            run,
            source,
        })?;
    let hash = std::fs::read(files.best_robot()).ok().map(|bytes| content_hash(&bytes));
    let title = format!("{name} run {run}: best, fitness {}", best.fitness());
    session
        .evaluator
        .save_replay(&best.genotype, &files.best_replay(), &title)
        .map_err(|source| RunError::Best {
            what: "replay",
            run,
            source,
        })?;
    Ok(hash)
}

/// Removes the temporary files a killed process may have left mid-write (`.NAME.tmp-PID`, see
/// [`write_atomic`]).
fn remove_stale_temporaries(dir: &Path) {
    if let Ok(entries) = std::fs::read_dir(dir) {
        for entry in entries.flatten() {
            let name = entry.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') && name.contains(".tmp-") {
                let _ = std::fs::remove_file(entry.path());
            }
        }
    }
}

fn write_checkpoint<O: Serialize>(
    path: &Path,
    run: usize,
    seed: u64,
    state: &RunState,
    optimizer: &O,
) -> Result<(), RunError> {
    let bytes =
        checkpoint::encode(run, seed, state, optimizer).map_err(|e| RunError::Other(format!("checkpoint: {e}")))?;
    write_file(path, &bytes)
}

/// A resumed run: optimizer, run state, and the covered parts of the two CSV files.
type Resumed<O> = (O, RunState, String, String);

/// Reads a run's checkpoint and verifies it and the files it covers: content hash, run and seed,
/// every genotype and fitness against the representation, the covered part of
/// `generations.csv`, every snapshot written so far. Errors name the file and say what to do.
fn load_checkpoint<G: Genotype, O: SearchOptimizer<G>>(
    bytes: &[u8],
    files: &RunFiles,
    run: usize,
    seed: u64,
    evaluator: &dyn Evaluator<G>,
    observer: &mut dyn Observer,
) -> Result<Resumed<O>, RunError> {
    let path = files.checkpoint_json();
    let refuse = |problem: &dyn std::fmt::Display| RunError::Folder {
        file: path.clone(),
        problem: format!(
            "{problem}; restore the file, or delete it to restart this run from its beginning \
                 (a restarted run gives the same results)"
        ),
    };
    let loaded = checkpoint::decode::<O>(bytes).map_err(|e| refuse(&e))?;
    if !loaded.verified {
        observer.notice(&format!(
            "{}: written by an older vsrlab without a content hash; resuming without verifying it",
            path.display()
        ));
    }
    let Checkpoint {
        run: saved_run,
        seed: saved_seed,
        state,
        optimizer,
    } = loaded.checkpoint;
    if saved_run != run || saved_seed != seed {
        return Err(refuse(&format!(
            "belongs to run {saved_run} with seed {saved_seed}, not run {run} with seed {seed}"
        )));
    }
    check_individuals(&optimizer, evaluator).map_err(|e| refuse(&e))?;
    let csv = read_truncated(&files.generations_csv(), state.csv_bytes)?;
    if !state.csv_hash.is_empty() && content_hash(csv.as_bytes()) != state.csv_hash {
        return Err(damaged_run(
            files,
            &[format!(
                "{} (its first {} bytes differ from what the checkpoint recorded)",
                files.generations_csv().display(),
                state.csv_bytes
            )],
        ));
    }
    let timings = read_truncated(&files.timings_csv(), state.timings_bytes)?;
    let damaged: Vec<String> = state
        .snapshots
        .iter()
        .filter_map(|s| checkpoint::damage(&files.snapshot(s.evaluations), &s.hash))
        .collect();
    if !damaged.is_empty() {
        return Err(damaged_run(files, &damaged));
    }
    Ok((optimizer, state, csv, timings))
}

/// What is wrong with an individual a checkpoint holds (`who`: which one).
#[derive(Debug, thiserror::Error)]
enum IndividualProblem {
    #[error("{who}: genotype does not fit the representation: {source}")]
    Genotype { who: String, source: EvaluatorError },
    #[error("{who}: {got} fitness values, the task has {objectives} objective(s)")]
    Objectives { who: String, got: usize, objectives: usize },
    #[error("{who}: fitness {value} is not finite")]
    Infinite { who: String, value: f64 },
}

/// Checks every individual an optimizer holds (population and best) against the evaluator: the
/// genotype fits the representation, and there is one fitness value per objective, each finite
/// or NaN (a failed evaluation).
fn check_individuals<G, O: SearchOptimizer<G>>(
    optimizer: &O,
    evaluator: &dyn Evaluator<G>,
) -> Result<(), IndividualProblem> {
    let objectives = evaluator.objectives();
    let members = optimizer
        .population()
        .into_iter()
        .enumerate()
        .map(|(i, m)| (format!("population member {i}"), m));
    for (who, individual) in members.chain(optimizer.best().map(|b| ("best individual".to_string(), b))) {
        if let Err(source) = evaluator.check(&individual.genotype) {
            return Err(IndividualProblem::Genotype { who, source });
        }
        if individual.objectives.len() != objectives {
            let got = individual.objectives.len();
            return Err(IndividualProblem::Objectives { who, got, objectives });
        }
        if let Some(&value) = individual.objectives.iter().find(|f| f.is_infinite()) {
            return Err(IndividualProblem::Infinite { who, value });
        }
    }
    Ok(())
}

/// The error for files of a run that are missing or damaged and cannot be rebuilt from the
/// checkpoint.
fn damaged_run(files: &RunFiles, damaged: &[String]) -> RunError {
    RunError::Folder {
        file: files.dir().to_path_buf(),
        problem: format!(
            "the run folder is damaged: {}. Restore these files, or delete the folder and resume again \
             to recompute the run from its seed (it gives the same files)",
            damaged.join(", ")
        ),
    }
}

/// Verifies the files of a finished run against the hashes in its `summary.json`.
fn verify_finished(files: &RunFiles, summary: &RunSummary, observer: &mut dyn Observer) -> Result<(), RunError> {
    if summary.seal_holds() == Some(false) {
        let what = format!(
            "{} (content differs from its seal: edited or damaged)",
            files.summary_json().display()
        );
        return Err(damaged_run(files, &[what]));
    }
    if summary.files.is_empty() {
        observer.notice(&format!(
            "{}: written by an older vsrlab without file hashes; its files are not verified",
            files.summary_json().display()
        ));
        return Ok(());
    }
    let damaged: Vec<String> = summary
        .files
        .iter()
        .filter_map(|(name, hash)| match safe_relative(name) {
            Some(rel) => checkpoint::damage(&files.dir().join(rel), hash),
            None => Some(format!(
                "{} (a file name outside the run folder: {name:?})",
                files.summary_json().display()
            )),
        })
        .collect();
    if damaged.is_empty() {
        Ok(())
    } else {
        Err(damaged_run(files, &damaged))
    }
}

/// A path from a summary's manifest, if it stays inside the run folder (plain names only).
fn safe_relative(name: &str) -> Option<&Path> {
    let path = Path::new(name);
    path.components()
        .all(|c| matches!(c, std::path::Component::Normal(_)))
        .then_some(path)
}

/// The individuals a snapshot holds (their records are kept until the next generation): the
/// population, or the whole last generation when the plan says so.
fn snapshot_members<'o, G: Genotype, O: SearchOptimizer<G>>(plan: &Plan, optimizer: &'o O) -> Vec<&'o Individual<G>> {
    if plan.snapshot_generation_pool {
        optimizer.generation_pool()
    } else {
        optimizer.population()
    }
}

fn write_snapshot<G: Genotype, O: SearchOptimizer<G>>(
    files: &RunFiles,
    members: Vec<&Individual<G>>,
    optimizer: &O,
    state: &mut RunState,
) -> Result<(), RunError> {
    let mut text = String::new();
    for (index, individual) in members.into_iter().enumerate() {
        let line = SnapshotRow {
            generation: optimizer.generation(),
            evaluations: optimizer.evaluations(),
            index,
            birth_generation: individual.birth_generation,
            record: state.records.get(&individual.genotype.key()),
            descriptor: individual.descriptor.clone(),
            genotype: &individual.genotype,
        };
        text.push_str(&serde_json::to_string(&line).map_err(|e| RunError::Other(format!("snapshot: {e}")))?);
        text.push('\n');
    }
    write_file(&files.snapshot(optimizer.evaluations()), text.as_bytes())?;
    state.last_snapshot = Some(optimizer.evaluations());
    state.snapshots.push(SnapshotEntry {
        evaluations: optimizer.evaluations(),
        hash: content_hash(text.as_bytes()),
    });
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(seed: u64, fitness: f64) -> Record {
        Record {
            fitness: Some(fitness),
            ..Record::new(seed)
        }
    }

    fn individual(genotype: Vec<f64>, fitness: f64) -> Individual<Vec<f64>> {
        Individual {
            genotype,
            objectives: vec![fitness],
            descriptor: vec![],
            birth_generation: 0,
        }
    }

    /// NEAT evaluates its elites again, each time with a new seed: the best robot must come
    /// from the evaluation that earned the best fitness, not from the genotype's first one.
    #[test]
    fn the_best_record_is_the_evaluation_that_earned_the_best_fitness() {
        let elite = vec![1.0, 2.0];
        let key = elite.key();
        let mut state = RunState {
            best: Some((key, record(1, 0.5))),
            ..RunState::default()
        };
        // the same genotype twice in a batch, with seeds 2 and 3; the optimizer's best is seed 3's
        let batch = vec![
            (key, vec![0.4], record(2, 0.4)),
            (key, vec![0.75], record(3, 0.75)),
            (vec![0.0].key(), vec![0.1], record(4, 0.1)),
        ];
        keep_best_record(Some(&individual(elite.clone(), 0.75)), &batch, &mut state);
        assert_eq!(state.best.as_ref().map(|(k, r)| (*k, r.seed)), Some((key, 3)));
        // a later evaluation of the elite that does worse leaves the best where it was
        let worse = vec![(key, vec![0.2], record(5, 0.2))];
        keep_best_record(Some(&individual(elite, 0.75)), &worse, &mut state);
        assert_eq!(state.best.as_ref().map(|(_, r)| r.seed), Some(3));
        // a new best genotype from an earlier batch is found among the kept records
        let other = vec![9.0];
        state.records.insert(other.key(), record(6, 0.9));
        keep_best_record(Some(&individual(other.clone(), 0.9)), &[], &mut state);
        assert_eq!(state.best.as_ref().map(|(k, r)| (*k, r.seed)), Some((other.key(), 6)));
    }
}
