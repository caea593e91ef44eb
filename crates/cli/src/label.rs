//! `vsrlab label`: a page for labelling a stratified sample of evolved robots by hand
//! (docs/analysis.md). The pipeline is `vsrlab_pipelines::label`; this file turns the
//! arguments into its options, draws the videos with `vsrlab-render` and prints what to do next.

use clap::Args;
use std::path::{Path, PathBuf};
use vsrlab_analysis::progress::Stderr;
use vsrlab_pipelines::replay::BoxError;
use vsrlab_pipelines::setup::read_setup;
use vsrlab_pipelines::{label, parse_classes, LabelOptions, VideoSpec};
use vsrlab_render::{RenderOptions, Trace};

/// Arguments of `vsrlab label`.
#[derive(Args, Debug)]
pub struct LabelArgs {
    /// Output folders of `vsrlab run` to draw robots from (every snapshot of every run).
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Folder for the page, the robot files and the videos.
    #[arg(long, default_value = "labelling")]
    pub out: PathBuf,
    /// Number of robots on the page.
    #[arg(long, default_value_t = 64)]
    pub count: usize,
    /// Equal-size bins per descriptor (voxels, elongation, compactness): bins³ strata.
    #[arg(long, default_value_t = 4)]
    pub bins: usize,
    /// Leave out robots slower than this (the thesis discarded poor walkers before sampling).
    #[arg(long)]
    pub min_velocity: Option<f64>,
    /// Seed of the sampling.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Morphology classes, comma-separated (default: the thesis').
    #[arg(long, default_value = "blob,limbed,elongated,other")]
    pub shape_classes: String,
    /// Behaviour classes, comma-separated (default: the thesis').
    #[arg(long, default_value = "jumping,walking,rolling,other")]
    pub behaviour_classes: String,
    /// Pre-select the rule-of-thumb proposals on the page (otherwise they are only shown).
    #[arg(long)]
    pub prefill: bool,
    /// Also write labels.csv right away from the proposals (rule-of-thumb labels, for trying the
    /// pipeline; not a substitute for looking at the robots).
    #[arg(long)]
    pub auto: bool,
    /// Video width in pixels.
    #[arg(long, default_value_t = 360)]
    pub width: u32,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
}

impl LabelArgs {
    fn options(self) -> Result<LabelOptions, String> {
        Ok(LabelOptions {
            shape_classes: parse_classes(&self.shape_classes).map_err(|e| e.to_string())?,
            behaviour_classes: parse_classes(&self.behaviour_classes).map_err(|e| e.to_string())?,
            results: self.results,
            out: self.out,
            count: self.count,
            bins: self.bins,
            min_velocity: self.min_velocity,
            seed: self.seed,
            prefill: self.prefill,
            auto: self.auto,
            video_width: self.width,
            threads: self.threads,
        })
    }
}

/// Draws a labelling video (no sensors, no lidar) at `videos/r-NNNN.gif`, and writes the same
/// episode as `replays/r-NNNN.replay.json` for `vsrlab view` (docs/viewer.md).
fn write_video(trace: &Trace, spec: &VideoSpec, path: &Path) -> Result<(), BoxError> {
    if let (Some(videos), Some(stem)) = (path.parent(), path.file_stem()) {
        let replays = videos.parent().unwrap_or(Path::new(".")).join("replays");
        std::fs::create_dir_all(&replays)?;
        let replay = replays.join(format!("{}.replay.json", stem.to_string_lossy()));
        let options = vsrlab_render::replay::ReplayOptions {
            title: stem.to_string_lossy().to_string(),
            ..Default::default()
        };
        vsrlab_render::replay::save_replay(trace, &options, &replay)?;
    }
    let options = RenderOptions {
        width: spec.width,
        height: spec.height,
        fps: spec.fps,
        draw_sensors: false,
        draw_lidar: false,
        ..RenderOptions::default()
    };
    vsrlab_render::save_video(trace, &options, path)?;
    Ok(())
}

pub fn run(args: LabelArgs) -> Result<(), String> {
    let options = args.options()?;
    let report = label(&options, &read_setup, &write_video, &Stderr).map_err(|e| e.to_string())?;
    if let Some(labels) = &report.labels {
        println!("wrote rule-of-thumb labels to {}", labels.display());
    }
    let results: Vec<String> = options.results.iter().map(|p| p.display().to_string()).collect();
    println!(
        "open {} in a browser, pick a class per robot and save labels.csv into {}\n(or label them in the replay viewer: vsrlab view {}); then run\n  vsrlab analyze {} --labels {}",
        report.index.display(),
        options.out.display(),
        options.out.display(),
        results.join(" "),
        options.out.join("labels.csv").display()
    );
    Ok(())
}
