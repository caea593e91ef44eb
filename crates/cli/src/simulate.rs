//! `vsrlab simulate`: one episode, its outcome, optionally a video.

use clap::Args;
use serde_json::json;
use std::path::PathBuf;
use std::time::Instant;
use vsrlab_tasks::files::{load_any_robot, save_any_robot_as};
use vsrlab_tasks::{episode, kinds, AnyRobot, RobotArgs, RobotArgsError, TaskSpec, TraceLevel};

/// Arguments of `vsrlab simulate`.
#[derive(Args, Debug)]
pub struct SimulateArgs {
    /// Body: a named shape (biped-4x3, worm-10x4, comb-7x2, box-5x5, tripod-5x3, t-5x4, ball-5) or a
    /// text grid with rows separated by '/', top row first ('#' voxel, '.' empty), e.g. "###/#.#";
    /// or a pressure-based soft agent, psa[:small|medium|large] (docs/psa.md); an EvoGym robot,
    /// evogym:<rows of material digits> (docs/multimaterial.md); or a 3D voxel body, 3d:<shape>
    /// (quadruped, cube-2, worm, box-WxHxD) or 3d:<layers bottom first joined by '|', rows by '/'>
    /// (docs/voxels3d.md).
    #[arg(long, default_value = "biped-4x3")]
    pub body: String,
    /// Brain: `phase` (open-loop a = sin(2πt + πx/W)), `constant:<v>`, `random[:<period>]`,
    /// `phase-grid`, `mlp[:<hidden,…>|none]`, `distributed-mlp[:<signals>]`,
    /// `distributed-mlp-hetero[:<signals>]`, `step:<period>:<brain>`, `smoothed:<speed>:<brain>`,
    /// `hebbian[:full|incoming|dew|l2]` (Hebbian ABCD rules, docs/ch5.3.md), `attention[:hetero|slow]`
    /// and `local-mlp[:<signals>]` (self-attention and its baselines, docs/ch4.2.md),
    /// `graph[:<added hidden neurons>]` (the self-organizing graph controller, docs/ch4.1.md),
    /// `heads[:<linear outputs>]` (the PSA controller, docs/psa.md), `elman[:<memory units>]` (the
    /// affordance study's voting voxels, docs/ch5.1.md). Default: phase for voxel bodies, heads for
    /// a PSA.
    /// Brains with parameters get seeded random ones in [-1, 1]; evolved ones come in robot files.
    #[arg(long)]
    pub brain: Option<String>,
    /// Task: locomotion:<terrain> (terrain = flat | hilly-H-W[-SEED] | steppy-H-W[-SEED] | uphill-DEG |
    /// downhill-DEG | psa-hilly-H-W[-SEED]), jump, escape (or escape:SIDE, the cage side) or carrier (PSA tasks,
    /// docs/psa.md), or one of EvoGym's: walker, bridge-walker, beam-toppler, cave-crawler (also
    /// evogym:BridgeWalker-v0, …; EvoGym robots, docs/multimaterial.md), or locomotion3d (3D voxel
    /// robots, docs/voxels3d.md).
    #[arg(long, default_value = "locomotion:flat")]
    pub task: String,
    /// Sensors: uniform-<s1>+<s2>…-<noise σ>, spinedTouch-…, spinedTouchSighted-…,
    /// <high|medium|low>_<biped|worm>-<σ>-<cpg t|f> (the Hebbian study's), or empty. Default:
    /// uniform-a+vxy+t-0 on voxel bodies; a PSA has its own sensors and takes none. A 3D body's:
    /// a comma-separated list of cpg or cpg:HZ, touch, floor, vx, vy, vz (default cpg,touch,floor,vy,vx).
    #[arg(long)]
    pub sensors: Option<String>,
    /// Take the task (kind and every setting: terrain, cage, ball, physics, start) from an
    /// experiment file, or from the experiment.toml of a `vsrlab run` output folder, instead of
    /// --task; --duration, --transient, --substeps and --damage still apply when given.
    #[arg(long, conflicts_with = "task")]
    pub task_of: Option<PathBuf>,
    /// Episode length in simulated seconds (default: the task's own, e.g. 30 s for locomotion,
    /// `locomotion3d:2`'s 2 s, or the --task-of experiment's).
    #[arg(long, value_parser = finite_number)]
    pub duration: Option<f64>,
    /// Initial seconds excluded from distance and velocity (locomotion).
    #[arg(long, value_parser = finite_number)]
    pub transient: Option<f64>,
    /// Voxels break during the episode: `<time s>:<probability>`, e.g. 30:0.5 (each voxel breaks
    /// at that time with that probability, drawn from the seed; a broken voxel stops actuating).
    #[arg(long)]
    pub damage: Option<String>,
    /// Start position: the robot's bounding-box left edge (locomotion and carrier tasks; default
    /// 11, the original's).
    #[arg(long, allow_negative_numbers = true, value_parser = finite_number)]
    pub initial_x: Option<f64>,
    /// Run N episodes from starts shifted right by k·--shift (k = ±1 … ±N/2) on every core and
    /// print the distribution of --metric (median, quartiles, mean, sd, range) and the time the
    /// trajectories from 0 and --shift part by 1e-3 (docs/fidelity.md), instead of one episode.
    #[arg(long, conflicts_with_all = ["video", "replay", "save_robot"])]
    pub ensemble: Option<usize>,
    /// Step between the ensemble's starts.
    #[arg(long, default_value_t = 1e-6, allow_negative_numbers = true, value_parser = finite_number)]
    pub shift: f64,
    /// The metric the ensemble summarises.
    #[arg(long, default_value = "velocity")]
    pub metric: String,
    /// Seed of the episode (random terrains, sensor noise).
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Physical preset of voxel robots: 2021 (thesis era, default) or 2022 (2D-VSR-Sim HEAD).
    #[arg(long)]
    pub preset: Option<String>,
    /// Physics sub-steps per step (default: the engine's default).
    #[arg(long)]
    pub substeps: Option<u32>,
    /// Physics solver: soft-substeps (vsrlab's, fast) or sequential-impulses (dyn4j's pipeline,
    /// as 2D-VSR-Sim; docs/physics.md). Default: the task's.
    #[arg(long)]
    pub solver: Option<String>,
    /// Print the outcome as JSON.
    #[arg(long)]
    pub json: bool,
    /// Render the episode to this file (.gif, .mp4 with ffmpeg, or .png for the last frame).
    #[arg(long)]
    pub video: Option<PathBuf>,
    /// What videos draw besides the world and the robot: a comma-separated list of ticks (distance
    /// marks on the ground), trail (the centre's path), sensors, lidar, attention (each voxel's
    /// attention matrix, attention brains, in place of its sensors), graph (a graph brain's
    /// neurons and edges, in place of the sensors), votes (each 3D voxel coloured by its vote:
    /// blue passable, red impassable; touching voxels bordered in yellow with sensors), overlay
    /// (time, distance, velocity), legend (voxel colours, vote counts); or all, or none.
    #[arg(long, default_value = "ticks,sensors,lidar,attention,graph,votes,overlay,legend")]
    pub draw: String,
    /// Draw the share of voxels voting "passable" at every frame (brains that vote, e.g. elman on
    /// the affordance task) into this figure (.png, and .svg beside it).
    #[arg(long)]
    pub votes: Option<PathBuf>,
    /// Write a replay file (JSON) for the browser viewer: `vsrlab view FILE` (docs/viewer.md).
    #[arg(long)]
    pub replay: Option<PathBuf>,
    /// Frames per second kept in the replay file (the viewer interpolates between them).
    #[arg(long, default_value_t = 30.0)]
    pub replay_fps: f64,
    /// Replay a robot file instead of --body/--sensors/--brain/--preset: vsrlab's JSON, or
    /// EvoGym's robots (its JSON or `.npz` files).
    #[arg(long, conflicts_with_all = ["body", "sensors", "brain", "preset"])]
    pub robot: Option<PathBuf>,
    /// Save the robot that was simulated as a robot file (JSON; a `.npz` name saves an EvoGym
    /// robot in EvoGym's `.npz` form).
    #[arg(long)]
    pub save_robot: Option<PathBuf>,
    /// The format of --save-robot: vsrlab, evogym-json or evogym-npz (EvoGym's forms hold the
    /// body only). Default: by the file's extension.
    #[arg(long, requires = "save_robot")]
    pub robot_format: Option<String>,
}

/// Physics settings given on the command line (`--substeps`, `--solver`).
#[derive(Debug, Clone, Copy, Default)]
pub struct PhysicsOptions<'a> {
    pub substeps: Option<u32>,
    pub solver: Option<&'a str>,
}

/// The task of `--task`, with the episode settings of the other options (no `duration`: the
/// task's own length).
pub fn task_from_args(
    task: &str,
    duration: Option<f64>,
    transient: Option<f64>,
    physics: PhysicsOptions,
    damage: Option<&str>,
) -> Result<TaskSpec, String> {
    let spec = TaskSpec::parse(task).map_err(|e| format!("--task: {e}"))?;
    with_episode_settings(spec, duration, transient, physics, damage)
}

/// `spec` starting with the robot's left edge at `x`, when given.
fn with_initial_x(spec: TaskSpec, x: Option<f64>) -> Result<TaskSpec, String> {
    match x {
        None => Ok(spec),
        Some(x) if !x.is_finite() => Err(format!("--initial-x: must be a finite number, got {x}")),
        Some(x) => spec.with_settings(&[("initial_x", json!(x))]).map_err(|e| {
            if e.path == "initial_x" {
                format!("--initial-x: a {} task has no start position to set", spec.kind())
            } else {
                format!("--initial-x: {}", e.message)
            }
        }),
    }
}

/// Runs `--ensemble N`: the distribution of `--metric` over N shifted starts, and the time two
/// starts `--shift` apart part by 1e-3 (docs/fidelity.md).
fn run_ensemble(
    a: &SimulateArgs,
    n: usize,
    robot: &AnyRobot,
    task: &TaskSpec,
    names: (&str, &str),
) -> Result<(), String> {
    use vsrlab_tasks::ensemble;
    if n < 2 {
        return Err(format!("--ensemble: at least 2 starts, got {n}"));
    }
    if !(a.shift.is_finite() && a.shift > 0.0) {
        return Err(format!("--shift: must be a positive number, got {}", a.shift));
    }
    const TOLERANCE: f64 = 1e-3;
    let start = Instant::now();
    let shifts = ensemble::shifts(n, a.shift);
    let values = ensemble::run_shifted(robot.as_robot(), task, &shifts, a.seed, &a.metric)
        .map_err(|e| format!("--ensemble: {e}"))?;
    if values.iter().all(|v| v.is_nan()) {
        return Err(format!(
            "--metric: a {} task does not report '{}'",
            task.kind(),
            a.metric
        ));
    }
    let summary = ensemble::Summary::of(&values)
        .ok_or_else(|| format!("--ensemble: some episodes gave a non-finite {}", a.metric))?;
    let parting = ensemble::parting_time(robot.as_robot(), task, a.shift, TOLERANCE, a.seed)
        .map_err(|e| format!("--ensemble: {e}"))?;
    let wall = start.elapsed().as_secs_f64();
    if a.json {
        let v = json!({
            "body": names.0, "task": names.1, "seed": a.seed, "metric": a.metric,
            "shift": a.shift, "shifts": shifts, "values": values, "summary": summary,
            "parting_tolerance": TOLERANCE, "parting_time": parting, "wall_seconds": wall,
        });
        println!("{}", serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?);
        return Ok(());
    }
    let s = summary;
    println!("body      {}", names.0);
    println!(
        "task      {} for {} s (seed {})",
        names.1,
        task.task().duration(),
        a.seed
    );
    println!(
        "ensemble  {n} starts shifted by k·{:e} (k = ±1 … ±{}{})",
        a.shift,
        n / 2,
        if n % 2 == 1 { ", and 0" } else { "" }
    );
    println!(
        "{:<9} median {:.4}   IQR [{:.4}, {:.4}]   mean {:.4}   sd {:.4}   min {:.4}   max {:.4}",
        a.metric, s.median, s.q1, s.q3, s.mean, s.sd, s.min, s.max
    );
    match parting {
        Some(t) => println!(
            "parting   starts {:e} apart differ by more than {TOLERANCE:e} in centre x after {t:.3} s",
            a.shift
        ),
        None => println!(
            "parting   starts {:e} apart never differ by more than {TOLERANCE:e} in centre x",
            a.shift
        ),
    }
    println!("wall      {wall:.2} s");
    Ok(())
}

/// The task of an experiment file (or of the `experiment.toml` in a results folder).
fn task_of_experiment(path: &std::path::Path) -> Result<TaskSpec, String> {
    vsrlab_experiment::config::load_task(path).map_err(|e| format!("--task-of: {e}"))
}

/// `spec` with the episode settings given on the command line.
fn with_episode_settings(
    spec: TaskSpec,
    duration: Option<f64>,
    transient: Option<f64>,
    physics: PhysicsOptions,
    damage: Option<&str>,
) -> Result<TaskSpec, String> {
    let mut settings = Vec::new();
    if let Some(d) = duration {
        settings.push(("duration", json!(d)));
    }
    if let Some(t) = transient {
        settings.push(("transient", json!(t)));
    }
    if let Some(n) = physics.substeps {
        settings.push(("physics.substeps", json!(n)));
    }
    if let Some(name) = physics.solver {
        settings.push(("physics.solver", json!(name)));
    }
    if let Some(d) = damage {
        settings.push(("damage", damage_value(d).map_err(|e| format!("--damage: {e}"))?));
    }
    let spec = spec.with_settings(&settings).map_err(|e| {
        let option = match e.path.as_str() {
            "physics.substeps" => "substeps",
            "physics.solver" => "solver",
            other => other,
        };
        format!("--{option}: {}", e.message)
    })?;
    spec.task().validate().map_err(|e| e.to_string())?;
    Ok(spec)
}

/// A finite number (`nan` and `inf` are refused here, naming the option, rather than deep in a
/// task as a JSON `null`).
pub fn finite_number(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(v) => Err(format!("must be a finite number, got {v}")),
        Err(_) => Err(format!("'{text}' is not a number")),
    }
}

/// The JSON value of a `--damage` option: `<time>:<probability>`, or `none` (no damage).
pub fn damage_value(text: &str) -> Result<serde_json::Value, String> {
    if text.trim() == "none" {
        return Ok(serde_json::Value::Null);
    }
    let d = vsrlab_tasks::Damage::parse(text).map_err(|e| e.to_string())?;
    Ok(json!({"at": d.at, "probability": d.probability}))
}

/// A robot short form's error, prefixed by its option (`--body: …`, `--brain: …`).
pub fn robot_option_error(e: &RobotArgsError) -> String {
    format!("--{}: {}", e.part(), e.message())
}

/// Runs `vsrlab simulate`.
pub fn run(a: SimulateArgs) -> Result<(), String> {
    let robot = match &a.robot {
        Some(path) => load_any_robot(path).map_err(|e| e.to_string())?,
        None => kinds::from_short_forms(&RobotArgs {
            body: &a.body,
            brain: a.brain.as_deref(),
            sensors: a.sensors.as_deref(),
            preset: a.preset.as_deref(),
        })
        .map_err(|e| robot_option_error(&e))?,
    };
    let body_name = match &a.robot {
        Some(path) => path.display().to_string(),
        None => a.body.clone(),
    };
    let physics = PhysicsOptions {
        substeps: a.substeps,
        solver: a.solver.as_deref(),
    };
    let task = match &a.task_of {
        Some(path) => with_episode_settings(
            task_of_experiment(path)?,
            a.duration,
            a.transient,
            physics,
            a.damage.as_deref(),
        )?,
        None => task_from_args(&a.task, a.duration, a.transient, physics, a.damage.as_deref())?,
    };
    let task = with_initial_x(task, a.initial_x)?;
    // a robot whose brain depends on the task (EvoGym's) is run, saved and printed as the task
    // runs it
    let robot = robot
        .description()
        .for_task(task.task(), a.robot.is_none())
        .unwrap_or(robot);
    if let Some(path) = &a.save_robot {
        save_any_robot_as(path, &robot, None, a.robot_format.as_deref()).map_err(|e| e.to_string())?;
    }
    let (sensors, preset) = (robot.description().sensors_label(), robot.description().preset_label());
    let brain = robot.brain();
    let duration = task.task().duration();
    let task_name = match &a.task_of {
        Some(path) => format!("{} of {}", task.kind(), path.display()),
        None => a.task.clone(),
    };
    if let Some(n) = a.ensemble {
        return run_ensemble(&a, n, &robot, &task, (&body_name, &task_name));
    }
    let level = if a.video.is_some() || a.replay.is_some() || a.votes.is_some() {
        TraceLevel::Full
    } else {
        TraceLevel::None
    };
    let start = Instant::now();
    let outcome = episode::run(robot.as_robot(), task.task(), a.seed, level).map_err(|e| e.to_string())?;
    let wall = start.elapsed().as_secs_f64();
    let mut video_note = None;
    if let (Some(path), Some(trace)) = (&a.video, &outcome.trace) {
        let options = vsrlab_render::RenderOptions::default()
            .with_layers(&a.draw)
            .map_err(|e| e.to_string())?;
        let info = vsrlab_render::save_video(trace, &options, path).map_err(|e| e.to_string())?;
        video_note = Some(format!("{} ({} frames)", path.display(), info.frames));
    }
    let mut votes_note = None;
    if let (Some(path), Some(trace)) = (&a.votes, &outcome.trace) {
        let title = format!("Votes over time (seed {})", a.seed);
        let files = vsrlab_pipelines::votes::save_votes(trace, &title, path).map_err(|e| e.to_string())?;
        votes_note = Some(
            files
                .iter()
                .map(|f| f.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        );
    }
    let mut replay_note = None;
    if let (Some(path), Some(trace)) = (&a.replay, &outcome.trace) {
        let options = vsrlab_render::replay::ReplayOptions {
            fps: a.replay_fps,
            title: format!("{body_name}, {task_name}, seed {}", a.seed),
            ..Default::default()
        };
        let bytes = vsrlab_render::replay::save_replay(trace, &options, path).map_err(|e| format!("--replay: {e}"))?;
        replay_note = Some(format!(
            "{} ({:.0} kB; vsrlab view {})",
            path.display(),
            bytes as f64 / 1e3,
            path.display()
        ));
    }
    let transient = a.transient.unwrap_or(0.0);
    if a.json {
        let mut v = json!({
            "body": body_name, "brain": brain.kind(), "task": task_name, "sensors": sensors,
            "preset": preset,
            "seed": a.seed, "duration": duration, "transient": transient,
            "steps": outcome.steps, "voxels": outcome.units, "wall_seconds": wall,
            "video": a.video.as_ref().map(|p| p.display().to_string()),
            "replay": a.replay.as_ref().map(|p| p.display().to_string()),
            "votes": a.votes.as_ref().map(|p| p.display().to_string()),
        });
        for (name, value) in &outcome.metrics {
            if v.get(name).is_none() {
                v[name] = json!(value);
            }
        }
        println!("{}", serde_json::to_string_pretty(&v).map_err(|e| e.to_string())?);
    } else {
        println!(
            "body      {} ({})",
            body_name,
            robot.description().body_details(outcome.units)
        );
        let mut transient_note = a.transient.map(|t| format!(", transient {t} s")).unwrap_or_default();
        if let Some(d) = &a.damage {
            transient_note += &format!(", damage {d}");
        }
        println!(
            "task      {} for {} s (seed {}{transient_note})",
            task_name, duration, a.seed
        );
        println!("brain     {} ({} parameters)", brain.kind(), brain.parameters().len());
        println!("sensors   {sensors}");
        for (name, value) in &outcome.metrics {
            if name != "elapsed" && name != "voxels" {
                println!("{name:<9} {value:.4}");
            }
        }
        println!(
            "steps     {} in {:.3} s wall ({:.0} steps/s)",
            outcome.steps,
            wall,
            outcome.steps as f64 / wall
        );
        if let Some(v) = video_note {
            println!("video     {v}");
        }
        if let Some(r) = replay_note {
            println!("replay    {r}");
        }
        if let Some(v) = votes_note {
            println!("votes     {v}");
        }
    }
    Ok(())
}
