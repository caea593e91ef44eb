//! `vsrlab codesign`: learning curves, learning radius and morphology over evolution of
//! co-design runs (thesis §5.2.5). The pipeline is `vsrlab_pipelines::codesign`.

use clap::Args;
use std::path::PathBuf;
use vsrlab_analysis::progress::Stderr;
use vsrlab_pipelines::{codesign, CodesignOptions};

/// Arguments of `vsrlab codesign`.
#[derive(Args, Debug)]
pub struct CodesignArgs {
    /// Output folders of `vsrlab run` of co-design experiments (or folders above them).
    #[arg(required = true)]
    pub results: Vec<PathBuf>,
    /// Output folder for the tables and figures.
    #[arg(long, default_value = "codesign")]
    pub out: PathBuf,
    /// PPO iterations of the learning curves' moving average (the thesis: 10).
    #[arg(long, default_value_t = 10)]
    pub window: usize,
}

pub fn run(a: CodesignArgs) -> Result<(), String> {
    let options = CodesignOptions {
        results: a.results,
        out: a.out,
        window: a.window,
    };
    let report = codesign(&options, &Stderr).map_err(|e| e.to_string())?;
    println!("{}", report.to_markdown());
    println!("wrote {} files to {}", report.files.len(), options.out.display());
    Ok(())
}
