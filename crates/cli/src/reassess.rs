//! `vsrlab reassess`: the best robot of every run on unseen episodes (new terrains, optionally
//! damage), compared between settings. The pipeline is `vsrlab_pipelines::reassess`.

use crate::overrides::TaskOverrides;
use clap::Args;
use std::path::PathBuf;
use vsrlab_analysis::progress::Stderr;
use vsrlab_pipelines::setup::read_setup;
use vsrlab_pipelines::{reassess, ReassessOptions};

/// Arguments of `vsrlab reassess`.
#[derive(Args, Debug)]
pub struct ReassessArgs {
    /// Output folders of `vsrlab run` (experiments with the same name form one setting).
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Output folder for the table and figures.
    #[arg(long, default_value = "reassess")]
    pub out: PathBuf,
    /// Episodes per robot (the thesis: 10 unseen terrains).
    #[arg(long, default_value_t = 10)]
    pub episodes: usize,
    /// Seed of the first episode (the others follow); evolution's seeds stay below it.
    #[arg(long, default_value_t = 1_000_000)]
    pub first_seed: u64,
    /// Window (s) of the velocity-over-time figure.
    #[arg(long, default_value_t = 5.0)]
    pub window: f64,
    #[command(flatten)]
    pub task: TaskOverrides,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
}

pub fn run(a: ReassessArgs) -> Result<(), String> {
    let options = ReassessOptions {
        overrides: a.task.settings()?,
        results: a.results,
        out: a.out,
        episodes: a.episodes,
        first_seed: a.first_seed,
        window: a.window,
        threads: a.threads,
    };
    let report = reassess(&options, &read_setup, &Stderr).map_err(|e| e.to_string())?;
    println!("{}", report.to_markdown());
    println!("wrote {} files to {}", report.files.len(), options.out.display());
    Ok(())
}
