//! `vsrlab plasticity`: the frozen-weight test and weight histograms of evolved Hebbian robots
//! (thesis §5.3.4.2–3). The pipeline is `vsrlab_pipelines::plasticity`.

use crate::overrides::TaskOverrides;
use clap::Args;
use std::path::PathBuf;
use vsrlab_analysis::progress::Stderr;
use vsrlab_pipelines::setup::read_setup;
use vsrlab_pipelines::{plasticity, PlasticityOptions};

/// Arguments of `vsrlab plasticity`.
#[derive(Args, Debug)]
pub struct PlasticityArgs {
    /// Output folders of `vsrlab run` whose robots have Hebbian brains.
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Output folder for the tables and figures.
    #[arg(long, default_value = "plasticity")]
    pub out: PathBuf,
    /// Freeze times in seconds, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "0,2,5,10,15,20,30,45,60")]
    pub freeze_at: Vec<f64>,
    /// Times (s) of the weight histograms, comma separated (the thesis: 1, 15, 60).
    #[arg(long, value_delimiter = ',', default_value = "1,15,60")]
    pub weights_at: Vec<f64>,
    /// Seed of the learning episode in which the weights are recorded.
    #[arg(long, default_value_t = 999_999)]
    pub learning_seed: u64,
    /// Unseen episodes per robot and freeze time.
    #[arg(long, default_value_t = 3)]
    pub episodes: usize,
    /// Seed of the first unseen episode.
    #[arg(long, default_value_t = 1_000_000)]
    pub first_seed: u64,
    /// Bins of the weight histograms.
    #[arg(long, default_value_t = 40)]
    pub bins: usize,
    #[command(flatten)]
    pub task: TaskOverrides,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
}

pub fn run(a: PlasticityArgs) -> Result<(), String> {
    let options = PlasticityOptions {
        overrides: a.task.settings()?,
        results: a.results,
        out: a.out,
        freeze_at: a.freeze_at,
        weights_at: a.weights_at,
        learning_seed: a.learning_seed,
        episodes: a.episodes,
        first_seed: a.first_seed,
        bins: a.bins,
        threads: a.threads,
    };
    let report = plasticity(&options, &read_setup, &Stderr).map_err(|e| e.to_string())?;
    println!("{}", report.to_markdown());
    println!("wrote {} files to {}", report.files.len(), options.out.display());
    Ok(())
}
