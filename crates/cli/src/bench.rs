//! `vsrlab bench`: simulation speed on the standard robots, single-threaded and on every core
//! (the benchmark itself is `vsrlab_experiment::bench`).

use crate::simulate::robot_option_error;
use clap::Args;
use vsrlab_experiment::bench::{run_bench, BenchError, BenchOptions, BenchReport};
use vsrlab_physics::Solver;
use vsrlab_tasks::kinds::voxel::short_forms::DEFAULT_SENSORS;

/// Arguments of `vsrlab bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Simulated seconds per episode (EvoGym rows: at most their task's length; 3D rows: at most 2 s;
    /// PPO rows: rollouts of at most 128 steps per environment, 0.384 s).
    #[arg(long, default_value_t = 30.0)]
    pub duration: f64,
    /// Minimum CPU seconds to spend on each row (more episodes are run until it is reached; 0: one
    /// episode per row, and no warm-up iteration in the PPO rows).
    #[arg(long, default_value_t = 2.0)]
    pub min_seconds: f64,
    /// Threads for the parallel rows (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Physical preset.
    #[arg(long, default_value = "2021")]
    pub preset: String,
    /// Only these robots (comma-separated: biped-4x3, worm-10x4, box-5x5, box-10x10, psa:small, psa:medium, psa:large,
    /// evogym-walker, evogym-bridge-walker, evogym-beam-toppler, evogym-cave-crawler, 3d-quadruped, 3d-box-6x6x6, affordance-starfish,
    /// and the PPO rows ppo-walker, ppo-bridge-walker: PPO iterations, "episodes" counting iterations).
    #[arg(long)]
    pub robots: Option<String>,
    /// Physics sub-steps per step (default: the engine's default).
    #[arg(long)]
    pub substeps: Option<u32>,
    /// Physics solver: soft-substeps or sequential-impulses (default: the engine's default).
    #[arg(long)]
    pub solver: Option<String>,
    /// Brain of every robot (as `vsrlab simulate --brain`; parameterised brains get random
    /// weights), to measure what a brain costs per step.
    #[arg(long, default_value = "phase")]
    pub brain: String,
    /// Sensors of every voxel (as `vsrlab simulate --sensors`); `empty` measures the body and the
    /// physics alone.
    #[arg(long, default_value = DEFAULT_SENSORS)]
    pub sensors: String,
    /// Skip the parallel rows.
    #[arg(long)]
    pub single_only: bool,
    /// Add a population row per robot (2D and 3D voxel robots, PSAs, EvoGym robots): N genotypes
    /// of its body (random brain weights) evaluated as one batch by the runner's evaluator, as
    /// `vsrlab run` does a generation (3D and EvoGym batches step in population lanes; rates
    /// per wall-clock second on --threads).
    #[arg(long, value_name = "N")]
    pub population: Option<usize>,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

impl BenchArgs {
    /// The library's options for these arguments.
    fn options(&self) -> Result<BenchOptions, String> {
        let solver = match self.solver.as_deref() {
            None => None,
            Some(name) => Some(name.parse::<Solver>().map_err(|e| format!("--solver: {e}"))?),
        };
        Ok(BenchOptions {
            duration: self.duration,
            min_cpu_seconds: self.min_seconds,
            threads: self.threads,
            preset: self.preset.clone(),
            robots: self.robots.as_ref().map(|s| s.split(',').map(String::from).collect()),
            substeps: self.substeps,
            solver,
            brain: self.brain.clone(),
            sensors: self.sensors.clone(),
            parallel: !self.single_only,
            population: self.population,
        })
    }
}

/// Runs `vsrlab bench`.
pub fn run(a: BenchArgs) -> Result<(), String> {
    let report = run_bench(&a.options()?).map_err(|e| match e {
        BenchError::Robot(e) => robot_option_error(&e),
        BenchError::Option(message) => format!("--{message}"),
        other => other.to_string(),
    })?;
    if a.json {
        // through a JSON value, whose keys are sorted, as the output has always been
        let value = serde_json::to_value(&report).map_err(|e| e.to_string())?;
        println!("{}", serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?);
    } else {
        print_table(&report);
    }
    Ok(())
}

fn print_table(report: &BenchReport) {
    // columns as wide as the longest robot and terrain names
    let robot_width = report.rows.iter().map(|r| r.robot.len()).max().unwrap_or(0).max(10);
    let terrain_width = report.rows.iter().map(|r| r.terrain.len()).max().unwrap_or(0).max(11);
    println!(
        "{:<robot_width$} {:<terrain_width$} {:>6} {:<10} {:>7} {:>8} {:>10} {:>14} {:>14} {:>8} {:>22}",
        "robot",
        "terrain",
        "voxels",
        "mode",
        "threads",
        "episodes",
        "steps/s",
        "voxel-steps/s",
        "voxel·s/CPU-s",
        "speedup",
        "vs original"
    );
    for r in &report.rows {
        let speedup = report.speedup(r);
        // e.g. "25.9× of 910 (HEAD)": the single-thread ratio to the original's steps/s
        let original = match (r.ratio_to_original, r.original_steps_per_s, r.original_version) {
            (Some(x), Some(o), Some(v)) => format!("{x:.1}× of {o:.0} ({v})"),
            _ => "-".into(),
        };
        println!(
            "{:<robot_width$} {:<terrain_width$} {:>6} {:<10} {:>7} {:>8} {:>10.0} {:>14.0} {:>14.0} {:>7.2}x {:>22}",
            r.robot,
            r.terrain,
            r.voxels,
            r.mode.name(),
            r.threads,
            r.episodes,
            r.steps_per_s,
            r.voxel_steps_per_s,
            r.voxel_seconds_per_cpu_s,
            speedup,
            original
        );
    }
}
