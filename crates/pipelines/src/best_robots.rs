//! The best robot of every run: its morphology descriptors (from its robot kind), and, for a 2D
//! voxel robot, its features from a replay on the experiment's task (for the PCA and
//! `best.csv`).

use crate::replay::{replay, ReplaySetup};
use crate::settings::Setting;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::morphology::MorphologyDescriptors;
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::report::csv_field;
use vsrlab_analysis::results::ExperimentData;
use vsrlab_tasks::files::load_any_robot;
use vsrlab_tasks::RobotSpec;
use vsrlab_tasks::TraceLevel;

/// The best robot of one run and what was computed from it.
#[derive(Debug, Clone)]
pub(crate) struct BestRobot {
    /// Its setting (colour index).
    pub setting: usize,
    /// Its run, as tables name it.
    pub run: String,
    /// The run's best fitness.
    pub fitness: f64,
    /// Morphology descriptors of its body.
    pub descriptors: MorphologyDescriptors,
    /// Features of its replay (None when it could not be replayed).
    pub features: Option<RobotFeatures>,
}

/// One best robot to load and replay.
struct Job<'a> {
    setting: usize,
    setup: Option<&'a ReplaySetup>,
    run: String,
    path: PathBuf,
    fitness: f64,
}

/// Loads the best robot of every run that saved one and replays the 2D voxel robots, on `pool`.
/// Robots that cannot be loaded are left out, and robots that cannot be replayed have no
/// features; both with a warning. Robots of kinds without morphology descriptors are left out
/// with one note.
pub(crate) fn best_robots(
    settings: &[Setting],
    experiments: &[ExperimentData],
    setups: &[Option<ReplaySetup>],
    pool: &rayon::ThreadPool,
    progress: &dyn Progress,
) -> Vec<BestRobot> {
    let mut jobs = Vec::new();
    for s in settings {
        for &e in &s.experiments {
            let exp = &experiments[e];
            for r in &exp.runs {
                if let Some(path) = &r.best_robot {
                    jobs.push(Job {
                        setting: s.color,
                        setup: setups[e].as_ref(),
                        run: exp.run_label(r),
                        path: path.clone(),
                        fitness: r.final_best(),
                    });
                }
            }
        }
    }
    let found: Vec<Found> = pool.install(|| jobs.par_iter().map(|job| best_robot(job, progress)).collect());
    // best robots of kinds without morphology descriptors (3D voxels, PSAs) are left out with
    // one note, not a warning per run
    let mut others: Vec<&'static str> = Vec::new();
    let mut bests = Vec::new();
    for f in found {
        match f {
            Found::Robot(best) => bests.push(*best),
            Found::Unreadable => {}
            Found::WithoutDescriptors(kind) => others.push(kind),
        }
    }
    if !others.is_empty() {
        let count = others.len();
        others.sort_unstable();
        others.dedup();
        progress.note(&format!(
            "note: {count} best robot(s) of kind {}: the morphology descriptors (best.csv and its figures) are defined for 2D grids of cells, so they are left out",
            others.join(", ")
        ));
    }
    bests
}

/// What loading one best robot gave.
enum Found {
    Robot(Box<BestRobot>),
    /// Not loaded (a warning was given).
    Unreadable,
    /// A robot of a kind without morphology descriptors (3D voxels, PSAs).
    WithoutDescriptors(&'static str),
}

fn best_robot(job: &Job, progress: &dyn Progress) -> Found {
    let robot = match load_any_robot(&job.path) {
        Ok(robot) => robot,
        Err(err) => {
            progress.note(&format!("warning: {err}"));
            return Found::Unreadable;
        }
    };
    let Some(descriptors) = robot.description().morphology() else {
        return Found::WithoutDescriptors(robot.kind().name);
    };
    // the gait features read a 2D voxel robot's replay
    let voxel_robot = robot.downcast_ref::<RobotSpec>();
    let features = job.setup.zip(voxel_robot).and_then(|(setup, robot)| {
        replay(robot, setup.task.task(), setup.best_robot_seed(), TraceLevel::Full)
            .map_err(|err| progress.note(&format!("warning: {}: {err}", job.path.display())))
            .ok()
            .map(|t| RobotFeatures::from_trace(&t, &FeatureParams::default()))
    });
    Found::Robot(Box::new(BestRobot {
        setting: job.setting,
        run: job.run.clone(),
        fitness: job.fitness,
        descriptors,
        features,
    }))
}

/// `best.csv`: every run's best robot with its fitness, descriptors and gait features (empty
/// gait columns without a replay).
pub(crate) fn best_csv(settings: &[Setting], bests: &[BestRobot]) -> String {
    let mut s = String::from("setting,run,best_fitness,voxels,elongation,compactness,gait_duration,gait_touch_area,gait_occurrences,gait_mode_interval,gait_purity\n");
    for b in bests {
        let g = b
            .features
            .as_ref()
            .map(|f| f.gait.features().map(|v| v.to_string()).join(","))
            .unwrap_or_else(|| ",,,,".into());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{g}",
            csv_field(&settings[b.setting].name),
            csv_field(&b.run),
            b.fitness,
            b.descriptors.voxels,
            b.descriptors.elongation,
            b.descriptors.compactness
        );
    }
    s
}
