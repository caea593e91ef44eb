//! `vsrlab inflate`: the PSA inflation protocol (thesis §6.4.1) for each size, φ and p/p_max per
//! step as a CSV and a figure. The pipeline is `vsrlab_pipelines::inflation`.

use clap::Args;
use std::path::PathBuf;
use vsrlab_body::psa::PsaSize;
use vsrlab_pipelines::{inflation, InflationOptions};

/// Arguments of `vsrlab inflate`.
#[derive(Args, Debug)]
pub struct InflateArgs {
    /// PSA sizes, comma separated (small, medium, large).
    #[arg(long, value_delimiter = ',', default_value = "small,medium,large")]
    pub sizes: Vec<String>,
    /// Simulated seconds per size (the pressure reaches p_max after 100 steps, 1.67 s).
    #[arg(long, default_value_t = 20.0)]
    pub duration: f64,
    /// Without gravity: the balloon alone, with no ground to rest on.
    #[arg(long)]
    pub zero_gravity: bool,
    /// Output folder for inflation.csv and the figure.
    #[arg(long, default_value = "inflation")]
    pub out: PathBuf,
}

pub fn run(a: InflateArgs) -> Result<(), String> {
    let sizes = a
        .sizes
        .iter()
        .map(|s| {
            serde_json::from_value::<PsaSize>(serde_json::Value::String(s.trim().to_string()))
                .map_err(|_| format!("--sizes: unknown size '{s}': expected small, medium or large"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let options = InflationOptions {
        sizes,
        duration: a.duration,
        zero_gravity: a.zero_gravity,
        out: a.out,
    };
    let report = inflation(&options).map_err(|e| format!("--{e}"))?;
    println!("| size | φ when p reaches p_max | φ over the last second: mean [min, max] | largest φ |");
    println!("|---|---|---|---|");
    for s in &report.sizes {
        let (mean, lo, hi) = s.last_second;
        println!(
            "| {} | {:.4} | {mean:.4} [{lo:.4}, {hi:.4}] | {:.4} |",
            s.size.name(),
            s.at_max,
            s.max
        );
    }
    println!("wrote {} files to {}", report.files.len(), options.out.display());
    Ok(())
}
