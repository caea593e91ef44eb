//! The simulation speed benchmark (`vsrlab bench`): the standard robots, single-threaded and on
//! every core, compared with the original simulator (2D-VSR-Sim).
//!
//! Each row runs locomotion episodes until a minimum CPU time is spent. The cross-simulator unit
//! is voxel·seconds simulated per CPU-second (voxels × simulated seconds / CPU seconds), the
//! figure the developers' guide compares across simulators. The pressure-based soft agents
//! (`psa:small|medium|large`) run on flat ground with the thesis's `heads` brain (random weights);
//! their "voxels" column counts masses, and they are compared with the original PSA code's
//! steps/s (psa-model.md, flat, MLP controller). The EvoGym rows run a full 5 × 5 body of
//! horizontal actuators with a random centralized MLP on each of EvoGym's four tasks, on the
//! mass-spring engine, compared with EvoGym 2.0.0's own environments (docs/multimaterial.md).
//! The learning rows (`ppo-walker`, `ppo-bridge-walker`, `bench_learning`) time PPO iterations
//! on two of those tasks against EvoGym's own PPO.

use crate::bench_learning::LEARNING_CASES;
use crate::bench_population::{has_population_row, measure_population, MAX_POPULATION};
use crate::cpu_time::{process_cpu_seconds, thread_cpu_seconds};
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;
use vsrlab_tasks::kinds::voxel::short_forms::DEFAULT_SENSORS;
use vsrlab_tasks::kinds::{self, AnyRobot, RobotArgs};
use vsrlab_tasks::{EpisodeError, Locomotion, RobotArgsError, TaskSpec, TraceLevel};

/// One standard case of the benchmark.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandardCase {
    /// The row's name (what `--robots` selects).
    pub name: &'static str,
    /// The robot's command-line body.
    pub body: &'static str,
    /// The task's command-line short form.
    pub task: &'static str,
    /// What the rows call the world it runs in.
    pub terrain: &'static str,
    /// Whether the options' brain and sensors apply to it (otherwise it keeps its kind's
    /// published brain and sensors: a PSA's `heads`, an EvoGym robot's MLP over the observation).
    pub takes_options: bool,
    /// The brain of a row that does not take the options', when not its kind's default (the
    /// affordance row's voting `elman`).
    pub brain: Option<&'static str>,
    /// Longest episode it runs (s), whatever the options' duration: a 3D episode takes some
    /// 21,000 engine steps per simulated second.
    pub longest: f64,
}

const fn case(
    name: &'static str,
    body: &'static str,
    task: &'static str,
    terrain: &'static str,
    takes_options: bool,
) -> StandardCase {
    StandardCase {
        name,
        body,
        task,
        terrain,
        takes_options,
        brain: None,
        longest: f64::INFINITY,
    }
}

/// A 3D case: its episodes last at most 2 s.
const fn case_3d(name: &'static str, body: &'static str) -> StandardCase {
    StandardCase {
        longest: 2.0,
        ..case(name, body, "locomotion3d", "floor", false)
    }
}

/// The affordance row (ch. 5.1): the starfish with the study's Elman brain and sensors walking
/// to the impassable aperture, wall and target colliding, in episodes of at most 2 s.
const AFFORDANCE: StandardCase = StandardCase {
    brain: Some("elman"),
    ..case_3d("affordance-starfish", "3d:starfish")
};

/// The standard cases, in the order of the rows. The EvoGym robots are a full 5 × 5 body of
/// horizontal actuators, as in the side-by-side runs with EvoGym. The 3D rows run the 3D engine
/// (voxcraft-sim's settings, collisions on) with the default open-loop phase brain and the
/// affordance study's sensors, in episodes of at most 2 s; the affordance row adds its Elman
/// brain and its world of fixed voxels.
pub const STANDARD_CASES: [StandardCase; 14] = [
    case("biped-4x3", "biped-4x3", "locomotion:flat", "flat", true),
    case("worm-10x4", "worm-10x4", "locomotion:flat", "flat", true),
    case("box-5x5", "box-5x5", "locomotion:hilly-1-10", "hilly-1-10", true),
    case("box-10x10", "box-10x10", "locomotion:flat", "flat", true),
    case("psa:small", "psa:small", "locomotion:flat", "flat", false),
    case("psa:medium", "psa:medium", "locomotion:flat", "flat", false),
    case("psa:large", "psa:large", "locomotion:flat", "flat", false),
    case(
        "evogym-walker",
        concat!("evogym:Walker-v0:", "33333/33333/33333/33333/33333"),
        "walker",
        "Walker-v0",
        false,
    ),
    case(
        "evogym-bridge-walker",
        concat!("evogym:BridgeWalker-v0:", "33333/33333/33333/33333/33333"),
        "bridge-walker",
        "BridgeWalker-v0",
        false,
    ),
    case(
        "evogym-beam-toppler",
        concat!("evogym:BeamToppler-v0:", "33333/33333/33333/33333/33333"),
        "beam-toppler",
        "BeamToppler-v0",
        false,
    ),
    case(
        "evogym-cave-crawler",
        concat!("evogym:CaveCrawler-v0:", "33333/33333/33333/33333/33333"),
        "cave-crawler",
        "CaveCrawler-v0",
        false,
    ),
    case_3d("3d-quadruped", "3d:quadruped"),
    case_3d("3d-box-6x6x6", "3d:box-6x6x6"),
    StandardCase {
        task: "affordance:impassable",
        terrain: "aperture",
        ..AFFORDANCE
    },
];

/// What to measure. Robots are given by short forms, as on the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchOptions {
    /// Simulated seconds per episode.
    pub duration: f64,
    /// Minimum CPU seconds to spend on each single-threaded row (more episodes are run until it
    /// is reached; the parallel row runs as many episodes per thread).
    pub min_cpu_seconds: f64,
    /// Threads of the parallel rows; `None`: every core.
    pub threads: Option<usize>,
    /// Physical preset (`2021` or `2022`).
    pub preset: String,
    /// Only these of [`STANDARD_CASES`], by robot name, in the standard order; `None`: all.
    pub robots: Option<Vec<String>>,
    /// Physics sub-steps per step; `None`: the engine's default.
    pub substeps: Option<u32>,
    /// Physics solver; `None`: the engine's default.
    pub solver: Option<vsrlab_physics::Solver>,
    /// Brain of every voxel robot (parameterised brains get seeded random parameters; PSAs
    /// always get `heads`).
    pub brain: String,
    /// Sensors of every voxel; `empty` measures the body and the physics alone (not PSAs).
    pub sensors: String,
    /// Whether to measure the parallel rows too.
    pub parallel: bool,
    /// Genotypes of a population row per voxel robot and PSA (`bench_population`); `None`: no
    /// such rows.
    pub population: Option<usize>,
}

impl Default for BenchOptions {
    fn default() -> Self {
        BenchOptions {
            duration: 30.0,
            min_cpu_seconds: 2.0,
            threads: None,
            preset: "2021".into(),
            robots: None,
            substeps: None,
            solver: None,
            brain: "phase".into(),
            sensors: DEFAULT_SENSORS.into(),
            parallel: true,
            population: None,
        }
    }
}

/// How a row was measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// One episode after another on one thread; rates per CPU-second.
    Single,
    /// Episodes spread over the thread pool; rates per wall-clock second.
    Parallel,
    /// A batch of different genotypes of one body through the runner's evaluator, on the thread
    /// pool; rates per wall-clock second.
    Population,
}

impl Mode {
    /// `single` or `parallel`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Single => "single",
            Mode::Parallel => "parallel",
            Mode::Population => "population",
        }
    }
}

/// The original simulator's speed on one robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OriginalSpeed {
    /// Steps per second, one thread, phase controller, after JIT warm-up.
    pub steps_per_s: f64,
    /// Which version of the original was measured.
    pub version: &'static str,
}

/// The original simulator's speed on the same robot and terrain, from the version each preset
/// reproduces (vsr-model.md §7): HEAD for preset 2022, v1.10.0 for preset 2021. `None` where the
/// original was not measured.
pub fn original_speed(preset: &str, robot: &str) -> Option<OriginalSpeed> {
    let (steps_per_s, version) = match (preset, robot) {
        ("2022", "biped-4x3") => (2300.0, "HEAD"),
        ("2022", "worm-10x4") => (910.0, "HEAD"),
        ("2022", "box-5x5") => (900.0, "HEAD"),
        ("2021", "biped-4x3") => (1900.0, "v1.10.0"),
        ("2021", "worm-10x4") => (1150.0, "v1.10.0"),
        // the PSA paper's code (PressureSoftAgents stable-release, pybox2d), flat, MLP controller
        (_, "psa:small") => (2782.0, "PSA stable-release"),
        // EvoGym 2.0.0's environments, the same body, this project's 2-core machine, 2026-11-27
        // (bench/evogym/tasks.py: 2,024 / 3,340 / 1,978 / 3,158 µs per step)
        (_, "evogym-walker") => (494.0, "EvoGym 2.0.0"),
        (_, "evogym-bridge-walker") => (299.0, "EvoGym 2.0.0"),
        (_, "evogym-beam-toppler") => (506.0, "EvoGym 2.0.0"),
        (_, "evogym-cave-crawler") => (317.0, "EvoGym 2.0.0"),
        (_, "psa:medium") => (1967.0, "PSA stable-release"),
        (_, "psa:large") => (1716.0, "PSA stable-release"),
        _ => return None,
    };
    Some(OriginalSpeed { steps_per_s, version })
}

/// One measured row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Row {
    /// The robot's name (one of [`STANDARD_CASES`]).
    pub robot: String,
    /// The terrain it walked on (the task's world, for EvoGym's tasks).
    pub terrain: String,
    /// Simulated seconds per step.
    pub step_seconds: f64,
    /// Its voxel count.
    pub voxels: usize,
    /// Single-threaded or parallel.
    pub mode: Mode,
    /// Threads used.
    pub threads: usize,
    /// Episodes run.
    pub episodes: usize,
    /// Simulation steps run, all episodes together.
    pub steps: u64,
    /// CPU seconds spent (the thread's for single rows, the process's for parallel ones).
    pub cpu_seconds: f64,
    /// Wall-clock seconds spent.
    pub wall_seconds: f64,
    /// Steps per CPU-second (single rows) or per wall-clock second (parallel rows).
    pub steps_per_s: f64,
    /// [`Row::steps_per_s`] × voxels.
    pub voxel_steps_per_s: f64,
    /// Voxel·seconds simulated per CPU-second, the cross-simulator unit.
    pub voxel_seconds_per_cpu_s: f64,
    /// The original simulator's single-thread steps/s on this robot (vsr-model.md §7), if measured.
    pub original_steps_per_s: Option<f64>,
    /// Which version of the original that figure is for.
    pub original_version: Option<&'static str>,
    /// steps/s ÷ the original's (single-threaded rows only).
    pub ratio_to_original: Option<f64>,
}

/// The benchmark's result: its settings and one or two rows per robot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BenchReport {
    /// Simulated seconds per step of the rigid-body rows (each row has its own).
    pub dt: f64,
    /// Simulated seconds per episode (at most: EvoGym's tasks have their own lengths).
    pub duration: f64,
    /// Physical preset.
    pub preset: String,
    /// The rows, robot by robot (single, then parallel).
    pub rows: Vec<Row>,
}

impl BenchReport {
    /// Steps/s of `row` ÷ those of the single-threaded row of the same robot (1 if there is none).
    pub fn speedup(&self, row: &Row) -> f64 {
        self.rows
            .iter()
            .find(|single| single.robot == row.robot && single.mode == Mode::Single)
            .map(|single| row.steps_per_s / single.steps_per_s)
            .unwrap_or(1.0)
    }
}

/// Why the benchmark could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The thread pool could not be built.
    #[error("{0}")]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
    /// A robot short form (preset, sensors, brain) is wrong.
    #[error("{0}")]
    Robot(#[from] RobotArgsError),
    /// A terrain of the standard cases is not understood.
    #[error("{0}")]
    Terrain(String),
    /// An episode failed.
    #[error("{0}")]
    Episode(#[from] EpisodeError),
    /// An option is out of range or names nothing; the message names the option.
    #[error("{0}")]
    Option(String),
    /// A learning row's training failed; the message names the row.
    #[error("{0}")]
    Learning(String),
    /// A population row's batch could not be evaluated.
    #[error("{robot}: population: {source}")]
    Population {
        /// The row's robot.
        robot: &'static str,
        /// The evaluator's error.
        source: crate::evaluator::EvaluatorError,
    },
    /// An episode of a population row failed (its record's reason).
    #[error("{robot}: population: an evaluation failed: {reason}")]
    FailedEvaluation {
        /// The row's robot.
        robot: &'static str,
        /// Why, as the evaluation's record gives it.
        reason: String,
    },
}

/// Checks the options that no episode would reject: known robots, a finite positive time budget
/// and duration, a sane thread count.
fn check_options(options: &BenchOptions) -> Result<(), BenchError> {
    let known: Vec<&str> = STANDARD_CASES
        .iter()
        .map(|c| c.name)
        .chain(LEARNING_CASES.iter().map(|c| c.name))
        .collect();
    if let Some(unknown) = options.robots.iter().flatten().find(|r| !known.contains(&r.as_str())) {
        return Err(BenchError::Option(format!(
            "robots: unknown robot '{unknown}': expected some of {}",
            known.join(", ")
        )));
    }
    if !(options.min_cpu_seconds.is_finite() && (0.0..=3600.0).contains(&options.min_cpu_seconds)) {
        return Err(BenchError::Option(format!(
            "min-seconds: must be in [0, 3600], got {}",
            options.min_cpu_seconds
        )));
    }
    if options.threads.is_some_and(|t| t == 0 || t > 1024) {
        return Err(BenchError::Option("threads: must be in 1..=1024".into()));
    }
    if options.population.is_some_and(|n| n == 0 || n > MAX_POPULATION) {
        return Err(BenchError::Option(format!(
            "population: must be in 1..={MAX_POPULATION}"
        )));
    }
    Ok(())
}

/// Runs the benchmark: for each selected standard robot, a single-threaded row and, if
/// [`BenchOptions::parallel`], a parallel row.
pub fn run_bench(options: &BenchOptions) -> Result<BenchReport, BenchError> {
    check_options(options)?;
    let threads = options
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
    let mut rows = Vec::new();
    for standard in STANDARD_CASES {
        if !is_selected(options, standard.name) {
            continue;
        }
        let case = Case::new(standard, options)?;
        let single = case.measure_single(options.min_cpu_seconds)?;
        let single_episodes = single.episodes;
        let steps_per_episode = single.steps / single.episodes as u64;
        rows.push(case.row(Mode::Single, 1, single));
        if options.parallel {
            let episodes = (single_episodes * threads).max(threads);
            let parallel = case.measure_parallel(&pool, episodes)?;
            rows.push(case.row(Mode::Parallel, threads, parallel));
        }
        if let Some(n) = options.population.filter(|_| has_population_row(&standard)) {
            let per_episode = (steps_per_episode, case.robot.description().size());
            rows.push(measure_population(
                &standard,
                options,
                &case.task,
                &pool,
                n,
                per_episode,
            )?);
        }
    }
    for learning in LEARNING_CASES.iter().filter(|c| is_selected(options, c.name)) {
        rows.extend(learning.rows(options, &pool)?);
    }
    Ok(BenchReport {
        dt: Locomotion::default().physics.dt,
        duration: options.duration,
        preset: options.preset.clone(),
        rows,
    })
}

/// Whether `robot` is among the robots the options ask for.
fn is_selected(options: &BenchOptions, robot: &str) -> bool {
    match &options.robots {
        Some(wanted) => wanted.iter().any(|w| w == robot),
        None => true,
    }
}

/// One standard robot, ready to be measured.
struct Case<'a> {
    name: &'static str,
    terrain: &'static str,
    robot: AnyRobot,
    task: TaskSpec,
    preset: &'a str,
}

impl<'a> Case<'a> {
    /// The case's robot with the options' preset (and sensors and brain, where it takes them) on
    /// its task, for the options' duration (the robot kind's physics on a rigid-body task).
    fn new(standard: StandardCase, options: &'a BenchOptions) -> Result<Self, BenchError> {
        let robot = kinds::from_short_forms(&RobotArgs {
            body: standard.body,
            brain: match standard.takes_options {
                true => Some(options.brain.as_str()),
                false => standard.brain,
            },
            sensors: standard.takes_options.then_some(options.sensors.as_str()),
            preset: standard.takes_options.then_some(options.preset.as_str()),
        })?;
        let task_error = |e: String| BenchError::Terrain(format!("{}: {e}", standard.task));
        let mut task = TaskSpec::parse(standard.task).map_err(|e| task_error(e.to_string()))?;
        let mut settings = vec![("duration", serde_json::json!(options.duration.min(standard.longest)))];
        if task.task().rigid().is_some() {
            let mut physics = (robot.kind().physics)();
            if let Some(n) = options.substeps {
                physics.substeps = n;
            }
            if let Some(solver) = options.solver {
                physics.solver = solver;
            }
            let physics = serde_json::to_value(physics).map_err(|e| task_error(e.to_string()))?;
            settings.push(("physics", physics));
        }
        task = task.with_settings(&settings).map_err(|e| task_error(e.to_string()))?;
        Ok(Case {
            name: standard.name,
            terrain: standard.terrain,
            robot,
            task,
            preset: &options.preset,
        })
    }

    /// Steps of one episode with episode seed `seed`.
    fn episode(&self, seed: u64) -> Result<u64, EpisodeError> {
        vsrlab_tasks::episode::run(self.robot.as_robot(), self.task.task(), seed, TraceLevel::None).map(|o| o.steps)
    }

    /// A warm-up episode, then episodes on this thread until `min_cpu_seconds` of its CPU time.
    fn measure_single(&self, min_cpu_seconds: f64) -> Result<Measurement, BenchError> {
        self.episode(0)?;
        let (c0, w0) = (thread_cpu_seconds(), Instant::now());
        let (mut episodes, mut steps) = (0usize, 0u64);
        while episodes == 0 || thread_cpu_seconds() - c0 < min_cpu_seconds {
            steps += self.episode(episodes as u64)?;
            episodes += 1;
        }
        Ok(Measurement {
            episodes,
            steps,
            cpu_seconds: thread_cpu_seconds() - c0,
            wall_seconds: w0.elapsed().as_secs_f64(),
        })
    }

    /// `episodes` episodes spread over `pool`, timed with the whole process's CPU time.
    fn measure_parallel(&self, pool: &rayon::ThreadPool, episodes: usize) -> Result<Measurement, BenchError> {
        let (c0, w0) = (process_cpu_seconds(), Instant::now());
        let results: Result<Vec<u64>, EpisodeError> =
            pool.install(|| (0..episodes).into_par_iter().map(|i| self.episode(i as u64)).collect());
        let steps: u64 = results?.iter().sum();
        Ok(Measurement {
            episodes,
            steps,
            cpu_seconds: process_cpu_seconds() - c0,
            wall_seconds: w0.elapsed().as_secs_f64(),
        })
    }

    /// The row of a measurement.
    fn row(&self, mode: Mode, threads: usize, m: Measurement) -> Row {
        let what = Measured {
            robot: self.name,
            terrain: self.terrain,
            step_seconds: self.task.task().step_seconds(),
            voxels: self.robot.description().size(),
            mode,
            threads,
        };
        Row::measured(what, m, original_speed(self.preset, self.name))
    }
}

/// Episodes (or iterations), steps and time of one measurement.
pub(crate) struct Measurement {
    pub episodes: usize,
    pub steps: u64,
    pub cpu_seconds: f64,
    pub wall_seconds: f64,
}

/// What a row measured: the robot, its world, its step and size, and how it was run.
pub(crate) struct Measured<'a> {
    pub robot: &'a str,
    pub terrain: &'a str,
    pub step_seconds: f64,
    pub voxels: usize,
    pub mode: Mode,
    pub threads: usize,
}

impl Row {
    /// The row of a measurement. Single-threaded rates use CPU time (robust to other load on the
    /// machine); parallel rates use wall time (throughput of the whole machine); the
    /// cross-simulator unit always uses CPU time. The ratio to `original` is for single rows.
    pub(crate) fn measured(what: Measured<'_>, m: Measurement, original: Option<OriginalSpeed>) -> Row {
        let steps_per_s = match what.mode {
            Mode::Single => m.steps as f64 / m.cpu_seconds,
            Mode::Parallel | Mode::Population => m.steps as f64 / m.wall_seconds,
        };
        let voxels = what.voxels as f64;
        Row {
            robot: what.robot.into(),
            terrain: what.terrain.into(),
            step_seconds: what.step_seconds,
            voxels: what.voxels,
            mode: what.mode,
            threads: what.threads,
            episodes: m.episodes,
            steps: m.steps,
            cpu_seconds: m.cpu_seconds,
            wall_seconds: m.wall_seconds,
            steps_per_s,
            voxel_steps_per_s: steps_per_s * voxels,
            voxel_seconds_per_cpu_s: voxels * m.steps as f64 * what.step_seconds / m.cpu_seconds,
            original_steps_per_s: original.map(|o| o.steps_per_s),
            original_version: original.map(|o| o.version),
            ratio_to_original: original
                .filter(|_| what.mode == Mode::Single)
                .map(|o| steps_per_s / o.steps_per_s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny(robots: &[&str]) -> BenchOptions {
        BenchOptions {
            duration: 1.0,
            min_cpu_seconds: 0.0,
            threads: Some(2),
            robots: Some(robots.iter().map(|r| r.to_string()).collect()),
            ..BenchOptions::default()
        }
    }

    #[test]
    fn a_3d_row_runs_episodes_of_at_most_2_s_on_the_3d_engine() {
        let options = BenchOptions {
            duration: 30.0,
            ..tiny(&["3d-quadruped"])
        };
        let report = run_bench(&options).unwrap();
        let row = &report.rows[0];
        assert_eq!((row.robot.as_str(), row.voxels), ("3d-quadruped", 28));
        // 2 s of 0.95 × the recommended step (4.78e-5 s)
        let per_episode = row.steps / row.episodes as u64;
        assert_eq!(per_episode, (2.0 / row.step_seconds).ceil() as u64, "{row:?}");
        assert!((row.step_seconds - 4.7813e-5).abs() < 1e-8);
    }

    #[test]
    fn the_affordance_row_runs_the_starfish_with_its_voting_brain() {
        let report = run_bench(&tiny(&["affordance-starfish"])).unwrap();
        let row = &report.rows[0];
        assert_eq!((row.robot.as_str(), row.voxels), ("affordance-starfish", 17));
        let per_episode = row.steps / row.episodes as u64;
        assert_eq!(per_episode, (1.0 / row.step_seconds).ceil() as u64, "{row:?}");
    }

    #[test]
    fn unknown_robots_and_bad_budgets_are_refused_naming_the_option() {
        let err = run_bench(&tiny(&["nosuch"])).unwrap_err().to_string();
        assert!(
            err.starts_with("robots: unknown robot 'nosuch'") && err.contains("biped-4x3"),
            "{err}"
        );
        for min_cpu_seconds in [f64::NAN, -1.0, 1e9] {
            let options = BenchOptions {
                min_cpu_seconds,
                ..tiny(&["biped-4x3"])
            };
            let err = run_bench(&options).unwrap_err().to_string();
            assert!(err.starts_with("min-seconds:"), "{err}");
        }
        let options = BenchOptions {
            threads: Some(100_000),
            ..tiny(&["biped-4x3"])
        };
        assert!(run_bench(&options).unwrap_err().to_string().starts_with("threads:"));
    }

    #[test]
    fn original_speeds_are_those_of_the_version_each_preset_reproduces() {
        assert_eq!(original_speed("2022", "worm-10x4").map(|o| o.version), Some("HEAD"));
        assert_eq!(original_speed("2021", "biped-4x3").map(|o| o.steps_per_s), Some(1900.0));
        assert_eq!(original_speed("2021", "box-10x10"), None);
        assert_eq!(
            original_speed("2021", "psa:medium").map(|o| o.steps_per_s),
            Some(1967.0)
        );
    }

    #[test]
    fn psa_rows_count_masses_and_compare_with_the_original_psa_code() {
        let report = run_bench(&tiny(&["psa:small"])).unwrap();
        let single = &report.rows[0];
        assert_eq!((single.robot.as_str(), single.voxels), ("psa:small", 10));
        assert_eq!(single.steps, 60 * single.episodes as u64);
        assert_eq!(single.original_version, Some("PSA stable-release"));
        // the ratio is measured speed over the original's figure: its value depends on the
        // machine, only its presence and sign are the code's
        let ratio = single.ratio_to_original.unwrap();
        assert!(ratio.is_finite() && ratio > 0.0, "{ratio}");
    }

    #[test]
    fn a_single_and_a_parallel_row_per_selected_robot() {
        let report = run_bench(&tiny(&["worm-10x4", "biped-4x3"])).unwrap();
        let rows: Vec<(&str, Mode)> = report.rows.iter().map(|r| (r.robot.as_str(), r.mode)).collect();
        assert_eq!(
            rows,
            [
                ("biped-4x3", Mode::Single),
                ("biped-4x3", Mode::Parallel),
                ("worm-10x4", Mode::Single),
                ("worm-10x4", Mode::Parallel)
            ]
        );
        for row in &report.rows {
            assert_eq!(row.steps, 60 * row.episodes as u64);
            assert_eq!(row.ratio_to_original.is_some(), row.mode == Mode::Single);
        }
        assert_eq!(report.speedup(&report.rows[0]), 1.0);
    }

    /// An EvoGym row steps its own engine (30 substeps of 1e-4 s), counts cells, stops at the
    /// bench's duration and compares with EvoGym's own environment; a rigid row keeps 1/60 s.
    #[test]
    fn evogym_rows_run_on_their_own_engine_and_compare_with_evogym() {
        let report = run_bench(&tiny(&["evogym-walker", "biped-4x3"])).unwrap();
        let (biped, walker) = (&report.rows[0], &report.rows[2]);
        assert_eq!(
            (walker.robot.as_str(), walker.terrain.as_str(), walker.voxels),
            ("evogym-walker", "Walker-v0", 25)
        );
        assert_eq!(walker.step_seconds, 30.0 * 1e-4);
        assert_eq!(walker.steps, 334 * walker.episodes as u64, "1 s of 3 ms steps");
        assert_eq!(walker.original_version, Some("EvoGym 2.0.0"));
        let expected = 25.0 * walker.steps as f64 * 0.003 / walker.cpu_seconds;
        assert!((walker.voxel_seconds_per_cpu_s - expected).abs() < 1e-9 * expected);
        assert_eq!(biped.step_seconds, report.dt);
    }

    /// A population row evaluates N different genotypes of each voxel robot and PSA through the
    /// runner's evaluator (N full episodes), EvoGym robots too (their row's brain); N is checked.
    #[test]
    fn population_rows_evaluate_a_batch_of_genotypes_of_each_body() {
        let options = BenchOptions {
            brain: "distributed-mlp".into(),
            population: Some(3),
            parallel: false,
            ..tiny(&["biped-4x3", "psa:small", "evogym-walker"])
        };
        let report = run_bench(&options).unwrap();
        let rows: Vec<(&str, Mode)> = report.rows.iter().map(|r| (r.robot.as_str(), r.mode)).collect();
        assert_eq!(
            rows,
            [
                ("biped-4x3", Mode::Single),
                ("biped-4x3", Mode::Population),
                ("psa:small", Mode::Single),
                ("psa:small", Mode::Population),
                ("evogym-walker", Mode::Single),
                ("evogym-walker", Mode::Population),
            ]
        );
        for pair in report.rows.chunks(2) {
            let (single, population) = (&pair[0], &pair[1]);
            assert_eq!(population.episodes, 3, "{population:?}");
            assert_eq!(
                population.steps,
                3 * single.steps / single.episodes as u64,
                "{population:?}"
            );
            assert_eq!((population.voxels, population.threads), (single.voxels, 2));
            assert!(population.voxel_seconds_per_cpu_s > 0.0 && population.ratio_to_original.is_none());
        }
        for population in [Some(0), Some(MAX_POPULATION + 1)] {
            let error = run_bench(&BenchOptions {
                population,
                ..tiny(&["biped-4x3"])
            })
            .unwrap_err();
            assert!(error.to_string().starts_with("population: must be in 1..="), "{error}");
        }
    }

    #[test]
    fn a_wrong_short_form_is_a_robot_error() {
        let options = BenchOptions {
            brain: "nope".into(),
            ..tiny(&["biped-4x3"])
        };
        let error = run_bench(&options).unwrap_err();
        assert!(matches!(error, BenchError::Robot(ref e) if e.part() == vsrlab_tasks::RobotPart::Brain));
    }
}
