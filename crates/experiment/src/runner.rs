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
//! OUT/run-00/summary.json        the run's result, timings and overhead (written at its end)
//! OUT/run-00/checkpoint.json     optimizer + run state (while the run is unfinished)
//! ```
//!
//! Determinism: evaluations run on a rayon pool but their results are collected in candidate
//! order, and every random number comes from the run seed, so `generations.csv`, the snapshots
//! and the best robot do not depend on the number of threads, nor on whether the run was
//! interrupted and resumed. Only `timings.csv` and the `summary.json` files hold wall-clock
//! figures. (A `stop.wall_seconds` criterion makes the stopping point machine-dependent.)

use crate::config::{Experiment, OutputConfig, StopConfig};
use crate::evaluator::{Evaluated, Evaluator, Record};
use crate::genotype::Genotype;
use crate::optimizers::{AnyOptimizer, SearchOptimizer};
use rayon::prelude::*;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;
use vsrlab_analysis::run_folder::{RunFiles, RunFolder, SUMMARY_FILE, TIMINGS_FILE};
use vsrlab_evolution::{Evaluation, Sense, Told};
use vsrlab_tasks::files::write_atomic;

/// Format tag of checkpoint files.
pub const CHECKPOINT_FORMAT: &str = "vsrlab-checkpoint/1";

/// Header of `generations.csv`.
pub const GENERATIONS_HEADER: &str = "generation,evaluations,births,failures,best_fitness,batch_best,batch_median,\
population_best,population_median,population_size,distinct_bodies,mean_voxels,species,archive_cells";

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
    /// The output folder or a checkpoint does not fit this experiment.
    #[error("{0}")]
    Mismatch(String),
    /// The optimizer refused its configuration or a batch.
    #[error("optimizer: {0}")]
    Optimizer(#[from] vsrlab_evolution::EvolutionError),
    /// Anything else (e.g. the best robot could not be built).
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

/// Receives progress; the CLI draws progress bars with it.
pub trait Observer {
    /// A run starts (or resumes, with `progress` where it left off).
    fn run_started(&mut self, _progress: &Progress) {}
    /// A generation ended (after its checkpoint was written).
    fn generation(&mut self, _progress: &Progress) -> Flow {
        Flow::Continue
    }
    /// A run ended, or was found finished when resuming.
    fn run_finished(&mut self, _summary: &RunSummary) {}
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
}

/// Run state that is not the optimizer's: saved in checkpoints.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
struct RunState {
    /// Records of the current population's genotypes, by genotype hash.
    records: BTreeMap<u64, Record>,
    /// Evaluation count at which the next snapshot is due.
    next_snapshot: u64,
    /// Evaluation count of the last snapshot written.
    last_snapshot: Option<u64>,
    failures: u64,
    /// Genotype hash and record of the best individual so far.
    best: Option<(u64, Record)>,
    wall_seconds: f64,
    evaluation_seconds: f64,
    episode_cpu_seconds: f64,
    /// Bytes of `generations.csv` and `timings.csv` covered by this checkpoint.
    csv_bytes: u64,
    timings_bytes: u64,
}

#[derive(Serialize, Deserialize)]
#[serde(bound(deserialize = "O: DeserializeOwned"))]
struct Checkpoint<O> {
    format: String,
    run: usize,
    seed: u64,
    state: RunState,
    optimizer: O,
}

/// A snapshot line: one population member.
#[derive(Serialize)]
struct SnapshotLine<'a, G> {
    generation: u64,
    evaluations: u64,
    index: usize,
    birth_generation: u64,
    #[serde(flatten)]
    record: Option<&'a Record>,
    descriptor: &'a [f64],
    genotype: &'a G,
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
        }
    }
}

/// Formats a float for the CSV: shortest round-trip form, `NaN` for failures.
fn num(v: f64) -> String {
    format!("{v}")
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
            } else if !matches!(name.as_deref(), Some(TIMINGS_FILE | SUMMARY_FILE)) {
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

/// Runs every run of a flat-vector experiment file into `out` (see the module docs for the
/// files), with the optimizer its `[optimizer]` table names.
pub fn run_experiment(
    experiment: &Experiment,
    evaluator: &dyn Evaluator<Vec<f64>>,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    let dimension = experiment
        .representation
        .genotype_length()
        .map_err(|e| RunError::Other(e.to_string()))?;
    let senses: Vec<Sense> = experiment
        .task
        .spec
        .task()
        .objectives()
        .iter()
        .map(|o| match o.sense {
            vsrlab_tasks::Sense::Maximize => Sense::Maximize,
            vsrlab_tasks::Sense::Minimize => Sense::Minimize,
        })
        .collect();
    let new_optimizer = |seed: u64| -> Result<AnyOptimizer, RunError> {
        Ok(experiment.optimizer.kind().build(dimension, &senses, seed)?)
    };
    run_search(&Plan::of(experiment), &new_optimizer, evaluator, out, options, observer)
}

/// Runs every run of a plan into `out` with optimizers of any genotype type: `new_optimizer`
/// builds the optimizer of a run from its seed.
pub fn run_search<G: Genotype, O: SearchOptimizer<G>>(
    plan: &Plan,
    new_optimizer: &dyn Fn(u64) -> Result<O, RunError>,
    evaluator: &dyn Evaluator<G>,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    if options.threads > MAX_THREADS {
        return Err(RunError::Mismatch(format!(
            "threads: at most {MAX_THREADS} worker threads, got {}",
            options.threads
        )));
    }
    std::fs::create_dir_all(out).map_err(io_error(out))?;
    let resolved = &plan.resolved;
    let folder = RunFolder::new(out);
    let config_path = folder.experiment_toml();
    match std::fs::read_to_string(&config_path) {
        Ok(existing) if !options.resume => {
            let _ = existing;
            return Err(RunError::Mismatch(format!(
                "{} already holds an experiment: pass --resume to continue it, or choose another output folder",
                out.display()
            )));
        }
        Ok(existing) if &existing != resolved => {
            return Err(RunError::Mismatch(format!(
                "{} was written by a different experiment configuration: resuming needs the same file \
                 (compare with {})",
                out.display(),
                config_path.display()
            )));
        }
        _ => write_file(&config_path, resolved.as_bytes())?,
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(options.threads)
        .build()
        .map_err(|e| RunError::Other(format!("thread pool: {e}")))?;
    let mut summaries = Vec::new();
    for (run, &seed) in plan.run_seeds.iter().enumerate() {
        let files = folder.run(run, plan.run_seeds.len());
        let session = Session {
            plan,
            evaluator,
            new_optimizer,
            options,
            pool: &pool,
        };
        match run_one(&session, run, seed, &files, observer)? {
            Some(summary) => summaries.push(summary),
            None => return Ok(summaries),
        }
    }
    let text = serde_json::to_string_pretty(&summaries).expect("summaries serialise");
    write_file(&folder.summary_json(), text.as_bytes())?;
    Ok(summaries)
}

/// Which stop criterion holds, if any.
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
    None
}

/// The sense of the first objective.
fn first_sense<G, O: SearchOptimizer<G>>(optimizer: &O) -> Sense {
    optimizer.senses().first().copied().unwrap_or_default()
}

fn fraction<G, O: SearchOptimizer<G>>(stop: &StopConfig, optimizer: &O, wall: f64) -> f64 {
    let mut f: f64 = 0.0;
    if let Some(n) = stop.evaluations {
        f = f.max(optimizer.evaluations() as f64 / n.max(1) as f64);
    }
    if let Some(n) = stop.births {
        f = f.max(optimizer.births() as f64 / n.max(1) as f64);
    }
    if let Some(n) = stop.generations {
        f = f.max(optimizer.generation() as f64 / n.max(1) as f64);
    }
    if let Some(s) = stop.wall_seconds {
        f = f.max(wall / s);
    }
    f.clamp(0.0, 1.0)
}

/// Reads a file and cuts it to `bytes` (what the checkpoint covers).
fn read_truncated(path: &Path, bytes: u64) -> Result<String, RunError> {
    let text = std::fs::read_to_string(path).map_err(io_error(path))?;
    let cut = usize::try_from(bytes).unwrap_or(usize::MAX);
    if text.len() < cut || !text.is_char_boundary(cut) {
        return Err(RunError::Mismatch(format!(
            "{} is shorter than its checkpoint says ({} < {cut} bytes): the run folder is damaged",
            path.display(),
            text.len()
        )));
    }
    Ok(text[..cut].to_string())
}

/// What every run of one call shares.
struct Session<'a, G, O> {
    plan: &'a Plan,
    evaluator: &'a dyn Evaluator<G>,
    new_optimizer: &'a dyn Fn(u64) -> Result<O, RunError>,
    options: &'a RunOptions,
    pool: &'a rayon::ThreadPool,
}

fn run_one<G: Genotype, O: SearchOptimizer<G>>(
    session: &Session<'_, G, O>,
    run: usize,
    seed: u64,
    files: &RunFiles,
    observer: &mut dyn Observer,
) -> Result<Option<RunSummary>, RunError> {
    let Session {
        plan,
        evaluator,
        new_optimizer,
        options,
        pool,
    } = *session;
    let dir = files.dir();
    let summary_path = files.summary_json();
    let checkpoint_path = files.checkpoint_json();
    let csv_path = files.generations_csv();
    let timings_path = files.timings_csv();
    let snapshots = files.snapshots_dir();
    if options.resume {
        if let Ok(text) = std::fs::read_to_string(&summary_path) {
            let summary: RunSummary = serde_json::from_str(&text)
                .map_err(|e| RunError::Mismatch(format!("{}: {e}", summary_path.display())))?;
            observer.run_finished(&summary);
            return Ok(Some(summary));
        }
    }
    std::fs::create_dir_all(&snapshots).map_err(io_error(&snapshots))?;
    if options.resume {
        remove_stale_temporaries(dir);
        remove_stale_temporaries(&snapshots);
    }
    let every = plan.output.snapshot_every;
    let (mut optimizer, mut state, mut csv, mut timings) = match std::fs::read(&checkpoint_path) {
        Ok(bytes) if options.resume => {
            let checkpoint: Checkpoint<O> = serde_json::from_slice(&bytes)
                .map_err(|e| RunError::Mismatch(format!("{}: {e}", checkpoint_path.display())))?;
            if checkpoint.format != CHECKPOINT_FORMAT || checkpoint.run != run || checkpoint.seed != seed {
                return Err(RunError::Mismatch(format!(
                    "{} belongs to another run or format",
                    checkpoint_path.display()
                )));
            }
            let csv = read_truncated(&csv_path, checkpoint.state.csv_bytes)?;
            let timings = read_truncated(&timings_path, checkpoint.state.timings_bytes)?;
            (checkpoint.optimizer, checkpoint.state, csv, timings)
        }
        _ => {
            let optimizer = new_optimizer(seed)?;
            let state = RunState {
                next_snapshot: every,
                ..RunState::default()
            };
            (
                optimizer,
                state,
                format!("{GENERATIONS_HEADER}\n"),
                format!("{TIMINGS_HEADER}\n"),
            )
        }
    };
    let session_start = Instant::now();
    let wall_before = state.wall_seconds;
    let wall = |start: &Instant| wall_before + start.elapsed().as_secs_f64();
    let progress = |optimizer: &O, wall: f64| Progress {
        run,
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
        let batch = optimizer.ask();
        let evaluation_start = Instant::now();
        let results: Vec<Evaluated> = pool.install(|| {
            batch
                .par_iter()
                .map(|c| evaluate_guarded(evaluator, &c.genotype, c.seed))
                .collect()
        });
        let evaluation_seconds = evaluation_start.elapsed().as_secs_f64();
        let batch_fitness: Vec<f64> = results.iter().map(|e| e.fitness()).collect();
        let sense = first_sense(&optimizer);
        let failures = results.iter().filter(|e| e.failed()).count() as u64;
        let episode_cpu: f64 = results.iter().map(|e| e.seconds).sum();
        let mut told = Vec::with_capacity(batch.len());
        for (candidate, evaluated) in batch.iter().zip(results) {
            state.records.insert(candidate.genotype.key(), evaluated.record);
            told.push(Told {
                id: candidate.id,
                evaluation: Evaluation {
                    objectives: evaluated.objectives,
                    descriptor: evaluated.descriptor,
                    outcome: evaluated.features,
                },
            });
        }
        optimizer.tell(told)?;
        if let Some(best) = optimizer.best() {
            let hash = best.genotype.key();
            if state.best.as_ref().map(|b| b.0) != Some(hash) {
                state.best = state.records.get(&hash).map(|r| (hash, r.clone()));
            }
        }
        let population = optimizer.population();
        let keep: BTreeSet<u64> = population.iter().map(|i| i.genotype.key()).collect();
        state.records.retain(|k, _| keep.contains(k));

        // Per-generation statistics (deterministic columns).
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
        state.failures += failures;
        let best = optimizer.best().map_or(f64::NAN, |b| b.fitness());
        let _ = writeln!(
            csv,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            optimizer.generation(),
            optimizer.evaluations(),
            optimizer.births(),
            failures,
            num(best),
            num(best_of(&batch_fitness, sense)),
            num(median(&batch_fitness, sense)),
            num(best_of(&population_fitness, sense)),
            num(median(&population_fitness, sense)),
            population.len(),
            bodies.len(),
            num(mean_voxels),
            optimizer.species().map_or(String::new(), |s| s.to_string()),
            optimizer.archive_cells().map_or(String::new(), |s| s.to_string()),
        );
        drop(population);
        write_file(&csv_path, csv.as_bytes())?;

        // Snapshots.
        if every > 0 && optimizer.evaluations() >= state.next_snapshot {
            write_snapshot(files, &optimizer, &state)?;
            state.last_snapshot = Some(optimizer.evaluations());
            while state.next_snapshot <= optimizer.evaluations() {
                state.next_snapshot += every;
            }
        }

        // Timings (wall clock: kept apart from the deterministic CSV).
        let generation_seconds = generation_start.elapsed().as_secs_f64();
        state.evaluation_seconds += evaluation_seconds;
        state.episode_cpu_seconds += episode_cpu;
        let _ = writeln!(
            timings,
            "{},{:.6},{:.6},{:.6},{:.6},{:.6}",
            optimizer.generation(),
            wall(&session_start),
            generation_seconds,
            evaluation_seconds,
            episode_cpu,
            generation_seconds - evaluation_seconds,
        );
        write_file(&timings_path, timings.as_bytes())?;

        // Checkpoint.
        state.wall_seconds = wall(&session_start);
        if last_checkpoint.elapsed().as_secs_f64() >= plan.output.checkpoint_interval {
            state.csv_bytes = csv.len() as u64;
            state.timings_bytes = timings.len() as u64;
            write_checkpoint(&checkpoint_path, run, seed, &state, &optimizer)?;
            last_checkpoint = Instant::now();
        }
        if observer.generation(&progress(&optimizer, wall(&session_start))) == Flow::Interrupt {
            return Ok(None);
        }
    };

    // The run is over: final population, best robot, summary; the checkpoint is no longer needed.
    if state.last_snapshot != Some(optimizer.evaluations()) {
        write_snapshot(files, &optimizer, &state)?;
    }
    let best = optimizer.best();
    if plan.output.save_best {
        if let Some(best) = best {
            let note = format!(
                "{}: run {run} (seed {seed}), best of {} evaluations, born in generation {}, fitness {}",
                plan.name.as_deref().unwrap_or("experiment"),
                optimizer.evaluations(),
                best.birth_generation,
                best.fitness()
            );
            evaluator
                .save_robot(&best.genotype, &files.best_robot(), &note)
                .map_err(|e| RunError::Other(format!("best robot of run {run}: {e}")))?;
        }
    }
    let wall_seconds = wall(&session_start);
    let overhead = (wall_seconds - state.evaluation_seconds).max(0.0);
    let best_record = state.best.as_ref().map(|b| &b.1);
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
        threads: pool.current_num_threads(),
    };
    let text = serde_json::to_string_pretty(&summary).expect("summaries serialise");
    write_file(&summary_path, text.as_bytes())?;
    let _ = std::fs::remove_file(&checkpoint_path);
    observer.run_finished(&summary);
    Ok(Some(summary))
}

/// Evaluates a genotype, turning a panic inside the evaluation into a failed evaluation so that
/// one bad genotype never ends a run.
fn evaluate_guarded<G>(evaluator: &dyn Evaluator<G>, genotype: &G, seed: u64) -> Evaluated {
    let start = Instant::now();
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| evaluator.evaluate(genotype, seed))).unwrap_or_else(
        |panic| {
            let message = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            let mut failed = evaluator.failure(seed, format!("the evaluation panicked: {message}"));
            failed.seconds = start.elapsed().as_secs_f64();
            failed
        },
    )
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
    #[derive(Serialize)]
    struct CheckpointRef<'a, O> {
        format: &'a str,
        run: usize,
        seed: u64,
        state: &'a RunState,
        optimizer: &'a O,
    }
    let bytes = serde_json::to_vec(&CheckpointRef {
        format: CHECKPOINT_FORMAT,
        run,
        seed,
        state,
        optimizer,
    })
    .map_err(|e| RunError::Other(format!("checkpoint: {e}")))?;
    write_file(path, &bytes)
}

fn write_snapshot<G: Genotype, O: SearchOptimizer<G>>(
    files: &RunFiles,
    optimizer: &O,
    state: &RunState,
) -> Result<(), RunError> {
    let mut text = String::new();
    for (index, individual) in optimizer.population().into_iter().enumerate() {
        let line = SnapshotLine {
            generation: optimizer.generation(),
            evaluations: optimizer.evaluations(),
            index,
            birth_generation: individual.birth_generation,
            record: state.records.get(&individual.genotype.key()),
            descriptor: &individual.descriptor,
            genotype: &individual.genotype,
        };
        text.push_str(&serde_json::to_string(&line).map_err(|e| RunError::Other(format!("snapshot: {e}")))?);
        text.push('\n');
    }
    write_file(&files.snapshot(optimizer.evaluations()), text.as_bytes())
}
