//! `vsrlab analyze`: figures and a summary table from the output of `vsrlab run`
//! (docs/analysis.md). The pipeline is `vsrlab_pipelines::analyze`; this file turns
//! the arguments into its options and prints its report.

use clap::Args;
use std::path::PathBuf;
use vsrlab_analysis::progress::Stderr;
use vsrlab_pipelines::setup::read_setup;
use vsrlab_pipelines::{analyze, AnalyzeOptions};

/// Arguments of `vsrlab analyze`.
#[derive(Args, Debug)]
pub struct AnalyzeArgs {
    /// Output folders of `vsrlab run`: experiment folders, or folders holding several. Runs of
    /// experiments with the same name are pooled into one setting.
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Labels CSV (made with `vsrlab label`): trains the shape and behaviour classifiers, which
    /// enables the species figures and the Inverse Simpson Index.
    #[arg(long)]
    pub labels: Option<PathBuf>,
    /// Output folder for figures and tables (default: `analysis` inside the results folder, or
    /// inside the folder that holds all of them when several are given).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// With --labels: individuals replayed per snapshot (evenly spread over the population;
    /// 0 = all). Every individual is a full episode, so this bounds the cost.
    #[arg(long, default_value_t = 0)]
    pub sample: usize,
    /// Cross-validation folds of the classifiers.
    #[arg(long, default_value_t = 5)]
    pub folds: usize,
    /// Seed of the random forests.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Worker threads for replays (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Pool runs by these settings instead of by experiment name: dotted keys of each
    /// experiment.toml, comma separated, e.g. `task.terrain` to compare terrains across a sweep's
    /// brains (settings are named `task.terrain=flat`, …).
    #[arg(long, value_delimiter = ',')]
    pub group_by: Vec<String>,
}

impl From<AnalyzeArgs> for AnalyzeOptions {
    fn from(a: AnalyzeArgs) -> AnalyzeOptions {
        let out = a.out.unwrap_or_else(|| default_out(&a.results));
        AnalyzeOptions {
            out,
            results: a.results,
            labels: a.labels,
            sample: a.sample,
            folds: a.folds,
            seed: a.seed,
            threads: a.threads,
            group_by: a.group_by,
        }
    }
}

/// `analysis` inside the one results folder, or inside the deepest folder that holds all of
/// them (the current folder when they share none).
fn default_out(results: &[PathBuf]) -> PathBuf {
    let mut common: Option<PathBuf> = None;
    for r in results {
        let r = std::path::absolute(r).unwrap_or_else(|_| r.clone());
        common = Some(match common {
            None => r,
            Some(c) => c
                .components()
                .zip(r.components())
                .take_while(|(a, b)| a == b)
                .map(|(a, _)| a)
                .collect(),
        });
    }
    common.unwrap_or_default().join("analysis")
}

pub fn run(args: AnalyzeArgs) -> Result<(), String> {
    let options = AnalyzeOptions::from(args);
    let report = analyze(&options, &read_setup, &Stderr).map_err(|e| e.to_string())?;
    println!("{}", report.summary.to_markdown());
    println!(
        "wrote {} figures and the tables to {}",
        report.figures.len(),
        report.out.display()
    );
    Ok(())
}
