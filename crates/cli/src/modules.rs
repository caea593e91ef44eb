//! The graph-brain commands of thesis §4.1: `vsrlab modules` (automatic module discovery),
//! `vsrlab reassemble` (hybrids of evolved robots and their re-optimisation experiment) and
//! `vsrlab transferability` (ρ and η per setting). The pipelines are
//! `vsrlab_pipelines::{modules, reassemble}`.

use clap::Args;
use std::path::PathBuf;
use vsrlab_analysis::progress::Stderr;
use vsrlab_experiment::config;
use vsrlab_pipelines::{
    modules, reassemble, transferability, ModulesOptions, ReassembleOptions, TransferabilityOptions,
};

/// Arguments of `vsrlab modules`.
#[derive(Args, Debug)]
pub struct ModulesArgs {
    /// Output folders of `vsrlab run` whose robots have graph brains.
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Output folder for `modules.csv`.
    #[arg(long, default_value = "modules")]
    pub out: PathBuf,
    /// Smallest and largest candidate module in voxels, as MIN..MAX (the thesis: 2..5).
    #[arg(long, default_value = "2..5")]
    pub sizes: String,
}

/// Arguments of `vsrlab reassemble`.
#[derive(Args, Debug)]
pub struct ReassembleArgs {
    /// Output folder(s) of one setting of `vsrlab run` with graph brains: the donors.
    #[arg(required = true)]
    pub donors: Vec<PathBuf>,
    /// The region each hybrid takes from the next run's robot: legs, back-half, front-half,
    /// discovered (its most compact module), or rows of '#' and '.' such as "#..#/#..#/#..#".
    #[arg(long)]
    pub cut: String,
    /// Output folder for the hybrids, transfer.csv and reoptimise.toml.
    #[arg(long)]
    pub out: PathBuf,
    /// Generations of the re-optimisation (the thesis: 510).
    #[arg(long, default_value_t = 510)]
    pub generations: u64,
}

/// Arguments of `vsrlab transferability`.
#[derive(Args, Debug)]
pub struct TransferabilityArgs {
    /// Folders written by `vsrlab reassemble`, each re-optimised into <folder>/reoptimised.
    #[arg(required = true)]
    pub reassemblies: Vec<PathBuf>,
    /// Output folder for the table and figures.
    #[arg(long, default_value = "transferability")]
    pub out: PathBuf,
}

fn parse_sizes(text: &str) -> Result<(usize, usize), String> {
    let bad = || format!("--sizes: expected MIN..MAX such as 2..5, got '{text}'");
    let (lo, hi) = text.split_once("..").ok_or_else(bad)?;
    Ok((
        lo.trim().parse().map_err(|_| bad())?,
        hi.trim().parse().map_err(|_| bad())?,
    ))
}

pub fn run_modules(a: ModulesArgs) -> Result<(), String> {
    let options = ModulesOptions {
        sizes: parse_sizes(&a.sizes)?,
        results: a.results,
        out: a.out,
    };
    let report = modules(&options, &Stderr).map_err(|e| e.to_string())?;
    print!("{}", report.to_text());
    println!(
        "{} robot(s); partitions in {} (0 = the module)",
        report.robots.len(),
        options.out.join("modules.csv").display()
    );
    Ok(())
}

pub fn run_reassemble(a: ReassembleArgs) -> Result<(), String> {
    let options = ReassembleOptions {
        donors: a.donors,
        cut: a.cut,
        out: a.out,
        generations: a.generations,
    };
    let report = reassemble(&options, &Stderr).map_err(|e| e.to_string())?;
    // the experiment written must be one `vsrlab run` accepts
    config::load_all(&report.config).map_err(|e| format!("the re-optimisation experiment is invalid: {e}"))?;
    for p in &report.pairs {
        println!(
            "{}: {} + {} (region {}): {} neurons, {} edges, η_num {:.3}, η_weight {:.3}",
            p.label, p.outside_run, p.inside_run, p.region, p.size.0, p.size.1, p.eta.0, p.eta.1
        );
    }
    println!(
        "{} hybrids of {}; re-optimise them with:\n  vsrlab run {} --out {}",
        report.pairs.len(),
        report.setting,
        report.config.display(),
        options
            .out
            .join(vsrlab_pipelines::reassemble::REOPTIMISED_DIR)
            .display()
    );
    Ok(())
}

pub fn run_transferability(a: TransferabilityArgs) -> Result<(), String> {
    let options = TransferabilityOptions {
        reassemblies: a.reassemblies,
        out: a.out,
    };
    let report = transferability(&options, &Stderr).map_err(|e| e.to_string())?;
    println!("{}", report.to_markdown());
    println!("wrote {} files to {}", report.files.len(), options.out.display());
    Ok(())
}
