//! `vsrlab validate`: checks experiment files and prints what each will do.

use clap::Args;
use std::path::PathBuf;
use vsrlab_experiment::memory::gib;
use vsrlab_experiment::validate::validate;
use vsrlab_experiment::{config, Experiment};

use crate::run::duration;

/// Arguments of `vsrlab validate`.
#[derive(Args, Debug)]
pub struct ValidateArgs {
    /// Experiment files (TOML).
    #[arg(required = true)]
    pub experiments: Vec<PathBuf>,
    /// Threads the time estimate assumes (default: every core).
    #[arg(long)]
    pub threads: Option<usize>,
    /// Print only the summary line of each file, not its resolved configuration.
    #[arg(long)]
    pub brief: bool,
    /// Refuse, as `vsrlab run` would, a file whose estimated memory per run exceeds this many GiB.
    #[arg(long, default_value_t = 8.0, value_name = "GIB")]
    pub max_memory_gib: f64,
}

/// Runs `vsrlab validate`: fails on the first bad file.
pub fn run(a: ValidateArgs) -> Result<(), String> {
    let limit = crate::run::memory_limit(a.max_memory_gib)?;
    let files: Vec<(PathBuf, Experiment)> = a
        .experiments
        .iter()
        .map(|path| Ok(config::load_all(path)?.into_iter().map(move |e| (path.clone(), e))))
        .collect::<Result<Vec<_>, config::ConfigError>>()
        .map_err(|e| e.to_string())?
        .into_iter()
        .flatten()
        .collect();
    for (path, experiment) in &files {
        let shown = match &experiment.name {
            Some(name) if files.iter().filter(|(p, _)| p == path).count() > 1 => {
                format!("{} [{name}]", path.display())
            }
            _ => path.display().to_string(),
        };
        let v = validate(experiment, a.threads.unwrap_or(0)).map_err(|e| format!("{shown}: {e}"))?;
        v.memory.check(limit).map_err(|e| format!("{shown}: {e}"))?;
        if !a.brief {
            println!("# {shown} (resolved)\n{}", v.resolved);
        }
        let time = match v.estimated_seconds {
            Some(s) => format!(
                "about {} for {} run(s) of {} evaluations on {} thread(s)",
                duration(s),
                experiment.runs,
                v.evaluations_per_run.unwrap_or(0),
                v.threads
            ),
            None => "no evaluation bound (wall-clock stop only)".to_string(),
        };
        println!(
            "{shown}: ok; {} genes per genotype; about {} per run; {:.3} s per evaluation of a random genotype; {time}",
            v.genes,
            gib(v.memory.bytes),
            v.seconds_per_evaluation
        );
    }
    Ok(())
}
