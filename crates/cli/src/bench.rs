//! `vsrlab bench`: simulation speed on the standard robots, single-threaded and on every core.
//!
//! Unit: voxel·seconds simulated per CPU-second (voxels × simulated seconds / CPU seconds), the
//! figure the developers' guide compares across simulators.

use crate::cpu_time::{process_cpu_seconds, thread_cpu_seconds};
use crate::simulate::{robot_from_args, DEFAULT_SENSORS};
use clap::Args;
use rayon::prelude::*;
use serde::Serialize;
use std::time::Instant;
use vsrlab_tasks::{Locomotion, RobotSpec, TraceLevel};

/// Arguments of `vsrlab bench`.
#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Simulated seconds per episode.
    #[arg(long, default_value_t = 30.0)]
    pub duration: f64,
    /// Minimum CPU seconds to spend on each row (more episodes are run until it is reached).
    #[arg(long, default_value_t = 2.0)]
    pub min_seconds: f64,
    /// Threads for the parallel rows (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Physical preset.
    #[arg(long, default_value = "2021")]
    pub preset: String,
    /// Only these robots (comma-separated: biped-4x3, worm-10x4, box-5x5, box-10x10).
    #[arg(long)]
    pub robots: Option<String>,
    /// Physics sub-steps per step (default: the engine's default).
    #[arg(long)]
    pub substeps: Option<u32>,
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
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// One measured row.
#[derive(Debug, Serialize)]
pub struct Row {
    robot: String,
    terrain: String,
    voxels: usize,
    mode: &'static str,
    threads: usize,
    episodes: usize,
    steps: u64,
    cpu_seconds: f64,
    wall_seconds: f64,
    steps_per_s: f64,
    voxel_steps_per_s: f64,
    voxel_seconds_per_cpu_s: f64,
    /// The original simulator's single-thread steps/s on this robot (vsr-model.md §7), if measured.
    original_steps_per_s: Option<f64>,
    /// Which version of the original that figure is for.
    original_version: Option<&'static str>,
    /// steps/s ÷ the original's (single-threaded rows only).
    ratio_to_original: Option<f64>,
}

const CASES: [(&str, &str); 4] = [
    ("biped-4x3", "flat"),
    ("worm-10x4", "flat"),
    ("box-5x5", "hilly-1-10"),
    ("box-10x10", "flat"),
];

/// The original simulator's speed (steps/s, one thread, phase controller, after JIT warm-up) on the
/// same robot and terrain, from the version each preset reproduces (vsr-model.md §7): HEAD for
/// preset 2022, v1.10.0 for preset 2021. `None` where the original was not measured.
fn original_speed(preset: &str, robot: &str) -> Option<(f64, &'static str)> {
    match (preset, robot) {
        ("2022", "biped-4x3") => Some((2300.0, "HEAD")),
        ("2022", "worm-10x4") => Some((910.0, "HEAD")),
        ("2022", "box-5x5") => Some((900.0, "HEAD")),
        ("2021", "biped-4x3") => Some((1900.0, "v1.10.0")),
        ("2021", "worm-10x4") => Some((1150.0, "v1.10.0")),
        _ => None,
    }
}

fn episode(robot: &RobotSpec, task: &Locomotion, seed: u64) -> Result<u64, String> {
    vsrlab_tasks::episode::run(robot, task, seed, TraceLevel::None)
        .map(|o| o.steps)
        .map_err(|e| e.to_string())
}

#[allow(clippy::too_many_arguments)]
fn row(
    body: &str,
    terrain: &str,
    voxels: usize,
    mode: &'static str,
    threads: usize,
    episodes: usize,
    steps: u64,
    cpu: f64,
    wall: f64,
    dt: f64,
    preset: &str,
) -> Row {
    // single-threaded rates use CPU time (robust to other load on the machine); parallel rates use
    // wall time (throughput of the whole machine); the cross-simulator unit always uses CPU time
    let steps_per_s = if mode == "single" {
        steps as f64 / cpu
    } else {
        steps as f64 / wall
    };
    let original = original_speed(preset, body);
    Row {
        robot: body.into(),
        terrain: terrain.into(),
        voxels,
        mode,
        threads,
        episodes,
        steps,
        cpu_seconds: cpu,
        wall_seconds: wall,
        steps_per_s,
        voxel_steps_per_s: steps_per_s * voxels as f64,
        voxel_seconds_per_cpu_s: voxels as f64 * steps as f64 * dt / cpu,
        original_steps_per_s: original.map(|o| o.0),
        original_version: original.map(|o| o.1),
        ratio_to_original: original.filter(|_| mode == "single").map(|o| steps_per_s / o.0),
    }
}

/// Runs `vsrlab bench`.
pub fn run(a: BenchArgs) -> Result<(), String> {
    let threads = a
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map(|n| n.get()).unwrap_or(1));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| e.to_string())?;
    let wanted: Option<Vec<&str>> = a.robots.as_deref().map(|s| s.split(',').collect());
    let mut rows = Vec::new();
    for (body, terrain) in CASES {
        if wanted.as_ref().is_some_and(|w| !w.contains(&body)) {
            continue;
        }
        let robot = robot_from_args(body, &a.preset, &a.sensors, &a.brain)?;
        let mut task = Locomotion {
            terrain: terrain.parse()?,
            duration: a.duration,
            ..Default::default()
        };
        if let Some(n) = a.substeps {
            task.physics.substeps = n;
        }
        let voxels = robot.body.voxel_count();
        let dt = task.physics.dt;
        // warm-up, then single thread: run episodes until min_seconds of CPU time
        episode(&robot, &task, 0)?;
        let (c0, w0) = (thread_cpu_seconds(), Instant::now());
        let (mut episodes, mut steps) = (0usize, 0u64);
        while episodes == 0 || thread_cpu_seconds() - c0 < a.min_seconds {
            steps += episode(&robot, &task, episodes as u64)?;
            episodes += 1;
        }
        let (cpu, wall) = (thread_cpu_seconds() - c0, w0.elapsed().as_secs_f64());
        rows.push(row(
            body, terrain, voxels, "single", 1, episodes, steps, cpu, wall, dt, &a.preset,
        ));
        if !a.single_only {
            let n = (episodes * threads).max(threads);
            let (c0, w0) = (process_cpu_seconds(), Instant::now());
            let results: Result<Vec<u64>, String> = pool.install(|| {
                (0..n)
                    .into_par_iter()
                    .map(|i| episode(&robot, &task, i as u64))
                    .collect()
            });
            let steps: u64 = results?.iter().sum();
            let (cpu, wall) = (process_cpu_seconds() - c0, w0.elapsed().as_secs_f64());
            rows.push(row(
                body, terrain, voxels, "parallel", threads, n, steps, cpu, wall, dt, &a.preset,
            ));
        }
    }
    if a.json {
        let out = serde_json::json!({ "duration": a.duration, "preset": a.preset, "dt": 1.0 / 60.0, "rows": rows });
        println!("{}", serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?);
    } else {
        print_table(&rows);
    }
    Ok(())
}

fn print_table(rows: &[Row]) {
    println!(
        "{:<10} {:<11} {:>6} {:<8} {:>7} {:>8} {:>10} {:>14} {:>14} {:>8} {:>22}",
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
    for r in rows {
        let speedup = rows
            .iter()
            .find(|s| s.robot == r.robot && s.mode == "single")
            .map(|s| r.steps_per_s / s.steps_per_s)
            .unwrap_or(1.0);
        // e.g. "25.9× of 910 (HEAD)": the single-thread ratio to the original's steps/s
        let original = match (r.ratio_to_original, r.original_steps_per_s, r.original_version) {
            (Some(x), Some(o), Some(v)) => format!("{x:.1}× of {o:.0} ({v})"),
            _ => "-".into(),
        };
        println!(
            "{:<10} {:<11} {:>6} {:<8} {:>7} {:>8} {:>10.0} {:>14.0} {:>14.0} {:>7.2}x {:>22}",
            r.robot,
            r.terrain,
            r.voxels,
            r.mode,
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
