//! `vsrlab fidelity`: the 2D fidelity protocol's table for a solver (docs/fidelity.md, "The
//! protocol").

use clap::Args;
use std::path::PathBuf;
use vsrlab_pipelines::fidelity::{read_cases, run_case, CaseResult, FidelityOptions, ORIGINAL_2D};

/// Arguments of `vsrlab fidelity`.
#[derive(Args, Debug)]
pub struct FidelityArgs {
    /// Physics solver: soft-substeps or sequential-impulses (default: the task's).
    #[arg(long)]
    pub solver: Option<String>,
    /// Only the cases whose name (`preset/body/terrain/brain`, e.g. `2022/worm-6x2/flat/phase`)
    /// contains one of these comma-separated parts.
    #[arg(long)]
    pub cases: Option<String>,
    /// Only the N starts nearest the unshifted one (|k| ≤ N/2) of each case (default: all the
    /// reference has).
    #[arg(long, value_name = "N")]
    pub starts: Option<usize>,
    /// The original's ensembles from this CSV (`preset,body,terrain,brain,k,velocity`) instead
    /// of the ones shipped with vsrlab.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// A task setting to change, `KEY=VALUE` (repeatable), e.g. `physics.contact_hertz=30`: a
    /// solver variant under the protocol. VALUE is read as JSON, else as a string.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub settings: Vec<String>,
    /// Print JSON (every case's tests and velocities) instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// `KEY=VALUE` into a key and a JSON value (a string when VALUE is not JSON).
fn setting(text: &str) -> Result<(String, serde_json::Value), String> {
    let (key, value) = text
        .split_once('=')
        .ok_or_else(|| format!("--set {text:?}: KEY=VALUE expected"))?;
    let value = serde_json::from_str(value).unwrap_or_else(|_| serde_json::Value::String(value.to_string()));
    Ok((key.trim().to_string(), value))
}

/// Runs `vsrlab fidelity`.
pub fn run(a: FidelityArgs) -> Result<(), String> {
    let text = match &a.reference {
        Some(path) => std::fs::read_to_string(path).map_err(|e| format!("--reference {}: {e}", path.display()))?,
        None => ORIGINAL_2D.to_string(),
    };
    let filters: Vec<&str> = a
        .cases
        .as_deref()
        .map_or(Vec::new(), |c| c.split(',').map(str::trim).collect());
    let cases: Vec<_> = read_cases(&text)
        .map_err(|e| e.to_string())?
        .into_iter()
        .filter(|c| filters.is_empty() || filters.iter().any(|f| c.name().contains(f)))
        .collect();
    if cases.is_empty() {
        return Err(format!(
            "--cases: no reference case matches {:?}",
            a.cases.unwrap_or_default()
        ));
    }
    if a.starts.is_some_and(|n| n < 4) {
        return Err("--starts: at least 4".into());
    }
    let options = FidelityOptions {
        solver: a.solver.clone(),
        max_k: a.starts.map(|n| (n / 2) as i64),
        settings: a.settings.iter().map(|s| setting(s)).collect::<Result<_, _>>()?,
    };
    let mut results = Vec::with_capacity(cases.len());
    if !a.json {
        print_header();
    }
    for case in &cases {
        let result = run_case(case, &options).map_err(|e| e.to_string())?;
        if !a.json {
            print_row(&result);
        }
        results.push(result);
    }
    let passed = results.iter().filter(|r| r.passed).count();
    let (steps, seconds): (u64, f64) = results.iter().fold((0, 0.0), |(s, c), r| (s + r.steps, c + r.seconds));
    if a.json {
        let answer = serde_json::json!({
            "solver": a.solver.as_deref().unwrap_or("default"),
            "settings": a.settings,
            "passed": passed,
            "cases": results,
            "steps": steps,
            "cpu_seconds": seconds,
        });
        println!("{}", serde_json::to_string_pretty(&answer).map_err(|e| e.to_string())?);
    } else {
        let share = 100.0 * passed as f64 / results.len() as f64;
        println!();
        println!(
            "passed {passed} of {} cases ({share:.0} %), solver {}{}",
            results.len(),
            a.solver.as_deref().unwrap_or("default"),
            a.settings.iter().map(|s| format!(", {s}")).collect::<String>()
        );
        println!(
            "{} episodes, {steps} steps in {seconds:.1} CPU-s: {:.0} steps per CPU-second",
            results.iter().map(|r| r.n).sum::<usize>(),
            steps as f64 / seconds.max(1e-9)
        );
    }
    Ok(())
}

fn print_header() {
    println!("| case | n | original median [IQR] | vsrlab median [IQR] | Δ median [90 % CI] | margin | MW p | KS D (p) | verdict |");
    println!("|---|---:|---|---|---|---:|---:|---|---|");
}

fn print_row(r: &CaseResult) {
    let e = &r.equivalence;
    let verdict = if r.passed {
        "pass"
    } else if !e.equivalent {
        "fail: median"
    } else {
        "fail: shape"
    };
    println!(
        "| {} | {} | {:.4} [{:.4}, {:.4}] | {:.4} [{:.4}, {:.4}] | {:+.4} [{:+.4}, {:+.4}] | {:.4} | {:.3} | {:.2} ({:.3}) | {verdict} |",
        r.case,
        r.n,
        r.original.median,
        r.original.q1,
        r.original.q3,
        r.ours.median,
        r.ours.q1,
        r.ours.q3,
        e.difference,
        e.low,
        e.high,
        e.margin,
        r.mann_whitney_p,
        r.ks.d,
        r.ks.p
    );
}
