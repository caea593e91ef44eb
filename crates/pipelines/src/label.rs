//! `vsrlab label`: a labelling aid for the species classifiers (thesis §3.3.2.2). It draws a
//! sample of evolved robots stratified by the three morphology descriptors, replays each one,
//! saves its robot file and a video, and writes a local HTML page (no network) where a person
//! picks a morphology and a behaviour class per robot and saves `labels.csv` for
//! `vsrlab analyze --labels`.

use crate::candidates::{candidates, Candidate};
use crate::classes::{check_classes, nearest_class, THESIS_BEHAVIOURS, THESIS_SHAPES};
use crate::error::AnalysisError;
use crate::label_page::{manifest_csv, page, page_data, Evidence, PageRobot};
use crate::output::{create_folder, write_output};
use crate::replay::{BoxError, ReplaySetup, SetupReader};
use crate::thread_pool;
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use vsrlab_analysis::diversity::{propose_behaviour, propose_shape};
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::labels::{write_labels, LabelRow};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results::{self, ExperimentData};
use vsrlab_analysis::sampling::stratified_sample;
use vsrlab_tasks::files::write_text;
use vsrlab_tasks::{TaskSpec, Trace};

/// What to put on the labelling page and how (the options of `vsrlab label`).
#[derive(Debug, Clone, PartialEq)]
pub struct LabelOptions {
    /// Output folders of `vsrlab run` to draw robots from (every snapshot of every run).
    pub results: Vec<PathBuf>,
    /// Folder for the page, the robot files and the videos.
    pub out: PathBuf,
    /// Number of robots on the page.
    pub count: usize,
    /// Equal-size bins per descriptor (voxels, elongation, compactness): bins³ strata.
    pub bins: usize,
    /// Leave out robots slower than this (the thesis discarded poor walkers before sampling).
    pub min_velocity: Option<f64>,
    /// Seed of the sampling.
    pub seed: u64,
    /// Morphology classes (at least two; no quotes or `<>&`).
    pub shape_classes: Vec<String>,
    /// Behaviour classes (at least two; no quotes or `<>&`).
    pub behaviour_classes: Vec<String>,
    /// Pre-select the rule-of-thumb proposals on the page (otherwise they are only shown).
    pub prefill: bool,
    /// Also write `labels.csv` from the proposals (to try the pipeline; not a substitute for
    /// looking at the robots).
    pub auto: bool,
    /// Video width in pixels (16:9, at least 90 pixels high).
    pub video_width: u32,
    /// Worker threads (None: every core).
    pub threads: Option<usize>,
}

impl LabelOptions {
    /// Label robots of `results` into `out` with the defaults of `vsrlab label` (64 robots,
    /// 4 bins, seed 1, the thesis' classes, 360-pixel videos, every core).
    pub fn new(results: Vec<PathBuf>, out: impl Into<PathBuf>) -> LabelOptions {
        let owned = |c: &[&str]| c.iter().map(|s| s.to_string()).collect();
        LabelOptions {
            results,
            out: out.into(),
            count: 64,
            bins: 4,
            min_velocity: None,
            seed: 1,
            shape_classes: owned(&THESIS_SHAPES),
            behaviour_classes: owned(&THESIS_BEHAVIOURS),
            prefill: false,
            auto: false,
            video_width: 360,
            threads: None,
        }
    }

    /// Size and frame rate of the videos.
    pub fn video_spec(&self) -> VideoSpec {
        VideoSpec {
            width: self.video_width,
            height: (self.video_width * 9 / 16).max(90),
            fps: 20.0,
        }
    }
}

/// Size and frame rate of the labelling videos.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VideoSpec {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Frames per second.
    pub fps: f64,
}

/// Draws an episode as a video file (the renderer comes after this crate, so the caller
/// supplies it). Called from several threads at once, for different files.
pub trait VideoWriter: Sync {
    /// Writes `trace` as a video of `spec` at `path` (a `.gif`), atomically.
    fn write_video(&self, trace: &Trace, spec: &VideoSpec, path: &Path) -> Result<(), BoxError>;
}

impl<F> VideoWriter for F
where
    F: Fn(&Trace, &VideoSpec, &Path) -> Result<(), BoxError> + Sync,
{
    fn write_video(&self, trace: &Trace, spec: &VideoSpec, path: &Path) -> Result<(), BoxError> {
        self(trace, spec, path)
    }
}

/// What `label` wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct LabelReport {
    /// The labelling page.
    pub index: PathBuf,
    /// `labels.csv` from the proposals, with `auto`.
    pub labels: Option<PathBuf>,
    /// Distinct evaluated individuals found in the snapshots.
    pub candidates: usize,
    /// Robots on the page.
    pub robots: usize,
}

/// Draws a stratified sample of the individuals in `options.results`, replays each (with
/// `setups`), saves `robots/r-NNNN.robot.json` and `videos/r-NNNN.gif` (with `videos`), and
/// writes `manifest.csv`, `index.html` and, with `auto`, `labels.csv` into `options.out`.
pub fn label(
    options: &LabelOptions,
    setups: &dyn SetupReader,
    videos: &dyn VideoWriter,
    progress: &dyn Progress,
) -> Result<LabelReport, AnalysisError> {
    check_classes(&options.shape_classes, &options.shape_classes.join(","))?;
    check_classes(&options.behaviour_classes, &options.behaviour_classes.join(","))?;
    if !(1..=100).contains(&options.bins) {
        return Err(AnalysisError::Option {
            option: "bins",
            message: format!("must be in 1..=100 (bins³ strata), got {}", options.bins),
        });
    }
    let experiments = results::discover(&options.results)?;
    let (pool, picked) = draw_sample(options, &experiments, progress)?;
    let setups: Vec<Result<ReplaySetup, BoxError>> =
        experiments.iter().map(|e| setups.read_setup(&e.folder())).collect();
    for dir in ["robots", "videos"] {
        create_folder(&options.out.join(dir))?;
    }
    let maker = PageRobotMaker {
        options,
        experiments: &experiments,
        setups: &setups,
        pool: &pool,
        videos,
    };
    let robots: Vec<Result<PageRobot, AnalysisError>> = thread_pool(options.threads)?
        .install(|| picked.par_iter().enumerate().map(|(k, &i)| maker.make(k, i)).collect());
    let robots: Vec<PageRobot> = robots.into_iter().collect::<Result<_, _>>()?;
    let (index, labels) = write_page(options, &robots, &pool)?;
    Ok(LabelReport {
        index,
        labels,
        candidates: pool.len(),
        robots: robots.len(),
    })
}

/// The candidates of `experiments` and the ones drawn for the page (indices into them, in
/// drawing order), stratified by their morphology descriptors.
fn draw_sample(
    options: &LabelOptions,
    experiments: &[ExperimentData],
    progress: &dyn Progress,
) -> Result<(Vec<Candidate>, Vec<usize>), AnalysisError> {
    let pool = candidates(experiments, options.min_velocity)?;
    if pool.is_empty() {
        return Err(AnalysisError::NoIndividuals);
    }
    let keys: Vec<Vec<f64>> = pool.iter().map(|c| c.descriptors.to_vec().to_vec()).collect();
    let picked = stratified_sample(&keys, options.bins, options.count, options.seed);
    progress.note(&format!(
        "{} distinct individuals in the snapshots; replaying {} of them…",
        pool.len(),
        picked.len()
    ));
    Ok((pool, picked))
}

/// The labelling data (robots, classes) for the replay viewer, in a `vsrlab label` folder.
pub const LABELLING_FILE: &str = "labelling.json";

/// Writes `manifest.csv`, `labelling.json`, `index.html` and, with `auto`, `labels.csv`; returns the paths of
/// the page and of the labels.
fn write_page(
    options: &LabelOptions,
    robots: &[PageRobot],
    pool: &[Candidate],
) -> Result<(PathBuf, Option<PathBuf>), AnalysisError> {
    write_output(&options.out.join("manifest.csv"), manifest_csv(robots, pool).as_bytes())?;
    let data = page_data(
        robots,
        pool,
        &options.shape_classes,
        &options.behaviour_classes,
        options.prefill,
    );
    write_output(&options.out.join(LABELLING_FILE), data.to_string().as_bytes())?;
    let html = page(&data);
    let index = options.out.join("index.html");
    write_output(&index, html.as_bytes())?;
    if !options.auto {
        return Ok((index, None));
    }
    let path = options.out.join("labels.csv");
    let rows: Vec<LabelRow> = robots.iter().map(PageRobot::proposed_labels).collect();
    write_labels(&path, &rows)?;
    Ok((index, Some(path)))
}

/// Replays a drawn candidate and saves its robot file and video.
struct PageRobotMaker<'a> {
    options: &'a LabelOptions,
    experiments: &'a [ExperimentData],
    setups: &'a [Result<ReplaySetup, BoxError>],
    pool: &'a [Candidate],
    videos: &'a dyn VideoWriter,
}

impl PageRobotMaker<'_> {
    /// Robot number `k` (0-based) on the page: candidate `i` of the pool.
    fn make(&self, k: usize, i: usize) -> Result<PageRobot, AnalysisError> {
        let c = &self.pool[i];
        let exp = &self.experiments[c.experiment];
        let setup = self.setups[c.experiment].as_ref().map_err(|err| AnalysisError::Setup {
            folder: exp.dir.clone(),
            source: err.to_string().into(),
        })?;
        let note = format!(
            "{} run {} evaluations {} index {}",
            c.setting, c.run, c.row.evaluations, c.row.index
        );
        // the labels file records a locomotion task (terrain, duration, transient) per robot
        let TaskSpec::Locomotion(locomotion) = &setup.task else {
            return Err(AnalysisError::Setup {
                folder: exp.dir.clone(),
                source: format!("labelling needs a locomotion task, not {}", setup.task.kind()).into(),
            });
        };
        let (robot, trace) = setup.replay_row(&c.row).map_err(|source| AnalysisError::Replay {
            robot: note.clone(),
            source,
        })?;
        let id = format!("r-{:04}", k + 1);
        let robot_rel = format!("robots/{id}.robot.json");
        let video_rel = format!("videos/{id}.gif");
        let out = &self.options.out;
        let text = robot
            .description()
            .map(|d| d.to_json(Some(&note)))
            .ok_or_else(|| AnalysisError::Setup {
                folder: exp.dir.clone(),
                source: "this kind of robot has no robot file".into(),
            })?;
        write_text(&out.join(&robot_rel), &text)?;
        let video = out.join(&video_rel);
        self.videos
            .write_video(&trace, &self.options.video_spec(), &video)
            .map_err(|source| AnalysisError::Video { path: video, source })?;
        let f = RobotFeatures::from_trace(&trace, &FeatureParams::default());
        let proposal = (
            nearest_class(propose_shape(&c.descriptors), &self.options.shape_classes),
            nearest_class(propose_behaviour(&f), &self.options.behaviour_classes),
        );
        Ok(PageRobot {
            id,
            robot: robot_rel,
            video: video_rel,
            terrain: locomotion.terrain.to_string(),
            duration: locomotion.duration,
            transient: locomotion.transient,
            seed: c.row.seed(),
            candidate: i,
            proposal,
            evidence: Evidence {
                airborne: f.airborne,
                turns: f.turns,
                displacement: f.displacement,
                occurrences: f.gait.occurrences,
                purity: f.gait.purity,
            },
        })
    }
}
