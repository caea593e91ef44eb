//! `vsrlab evaluate`: the fitness of given genotypes on an experiment's robot and task, for
//! optimisers outside vsrlab (the same evaluations as `vsrlab run` and Python's
//! `vsrlab.evaluate_batch`).

use clap::Args;
use std::io::Write;
use std::path::PathBuf;
use vsrlab_experiment::{config, BatchEvaluator};

/// Arguments of `vsrlab evaluate`.
#[derive(Args, Debug)]
pub struct EvaluateArgs {
    /// Experiment file (TOML): its representation maps genes to a robot, its task scores it.
    pub experiment: PathBuf,
    /// Genotypes: one per line, genes separated by commas or spaces (CSV without a header);
    /// `-` reads standard input. `vsrlab evaluate EXPERIMENT --genes` prints the length.
    #[arg(required_unless_present = "genes")]
    pub genotypes: Option<PathBuf>,
    /// Candidate seeds, one per genotype, comma-separated (default 0, 1, 2, …): the seed of the
    /// episode when the task draws a random terrain per evaluation, as `vsrlab run` gives each
    /// candidate.
    #[arg(long, value_delimiter = ',')]
    pub seeds: Option<Vec<u64>>,
    /// Worker threads (default: every core); results never depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Print each evaluation's record as a JSON line (fitness, distance, velocity, body, error)
    /// instead of its fitness alone.
    #[arg(long)]
    pub records: bool,
    /// Print the number of genes per genotype and exit.
    #[arg(long)]
    pub genes: bool,
}

/// Runs `vsrlab evaluate`: one line per genotype, in file order.
pub fn run(a: EvaluateArgs) -> Result<(), String> {
    let experiment = config::load(&a.experiment).map_err(|e| e.to_string())?;
    let batch = BatchEvaluator::new(experiment).map_err(|e| e.to_string())?;
    if a.genes {
        println!("{}", batch.genotype_length());
        return Ok(());
    }
    let path = a.genotypes.expect("clap requires genotypes without --genes");
    let text = if path.as_os_str() == "-" {
        std::io::read_to_string(std::io::stdin()).map_err(|e| format!("standard input: {e}"))?
    } else {
        std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?
    };
    let (genes, rows) =
        parse_genotypes(&text, batch.genotype_length()).map_err(|e| format!("{}: {e}", path.display()))?;
    let seeds = a.seeds.unwrap_or_else(|| (0..rows as u64).collect());
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(a.threads.unwrap_or(0))
        .build()
        .map_err(|e| format!("thread pool: {e}"))?;
    let mut out = std::io::stdout().lock();
    let mut print = |line: String| writeln!(out, "{line}").map_err(|e| format!("standard output: {e}"));
    if a.records {
        let evaluated = pool
            .install(|| batch.evaluate(&genes, &seeds))
            .map_err(|e| format!("--{e}"))?;
        for e in evaluated {
            print(serde_json::to_string(&e.record).map_err(|e| e.to_string())?)?;
        }
    } else {
        let fitness = pool
            .install(|| batch.fitness(&genes, &seeds))
            .map_err(|e| format!("--{e}"))?;
        for f in fitness {
            // Display prints the shortest text that reads back as the same f64
            print(format!("{f}"))?;
        }
    }
    Ok(())
}

/// The genes of every non-empty line, row after row, and the number of rows; errors name the
/// line.
fn parse_genotypes(text: &str, width: usize) -> Result<(Vec<f64>, usize), String> {
    let mut genes = Vec::new();
    let mut rows = 0;
    for (i, line) in text.lines().enumerate() {
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        if fields.is_empty() {
            continue;
        }
        if fields.len() != width {
            return Err(format!(
                "line {}: {} genes, the experiment's genotypes have {width}",
                i + 1,
                fields.len()
            ));
        }
        for f in fields {
            let v: f64 = f
                .parse()
                .map_err(|_| format!("line {}: '{f}' is not a number", i + 1))?;
            genes.push(v);
        }
        rows += 1;
    }
    Ok((genes, rows))
}
