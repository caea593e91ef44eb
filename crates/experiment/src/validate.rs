//! `vsrlab validate`: what an experiment file will do, before it runs: the resolved
//! configuration (every default written out), the genotype size, the memory estimate, and a
//! time estimate from one timed evaluation.

use crate::config::Experiment;
use crate::memory::MemoryEstimate;
use crate::optimizers::FieldError;
use std::time::Instant;

/// Initial genotypes timed for the estimate.
const TIMED_EVALUATIONS: usize = 3;

/// What an experiment will do.
#[derive(Debug, Clone, PartialEq)]
pub struct Validation {
    /// The resolved configuration, as `experiment.toml` will hold it.
    pub resolved: String,
    /// Genes per genotype (a graph genotype: the starting graph's parameters, 2 per edge).
    pub genes: usize,
    /// The per-run memory estimate.
    pub memory: MemoryEstimate,
    /// Evaluations per run, when a stop criterion bounds them (`None` for a wall-clock stop only).
    pub evaluations_per_run: Option<u64>,
    /// Mean seconds of one evaluation of an initial genotype (flat vectors: genes uniform in
    /// [-1, 1], seeded; other kinds: their first initial genotypes): evolved bodies are often
    /// larger, so the time estimate is a lower figure.
    pub seconds_per_evaluation: f64,
    /// Estimated wall seconds of the whole experiment on `threads` threads (`None` when the
    /// evaluations are not bounded).
    pub estimated_seconds: Option<f64>,
    /// Threads the estimate assumes.
    pub threads: usize,
}

/// Checks an experiment (already parsed and validated) and estimates its cost on `threads`
/// threads (0: every core). Runs a few evaluations of initial genotypes.
pub fn validate(experiment: &Experiment, threads: usize) -> Result<Validation, FieldError> {
    let threads = crate::runner::worker_threads(threads);
    let start = Instant::now();
    let kind = experiment.genotype_kind();
    kind.time_evaluations(experiment, TIMED_EVALUATIONS)?;
    let genes = kind.size(experiment)?.genes;
    let seconds_per_evaluation = start.elapsed().as_secs_f64() / TIMED_EVALUATIONS as f64;
    let optimizer = experiment.optimizer.kind();
    let stop = &experiment.stop;
    let evaluations_per_run = stop.evaluations.or(stop.births).or_else(|| {
        stop.generations
            .map(|g| g.saturating_mul(optimizer.batch_size(genes) as u64))
    });
    let estimated_seconds = evaluations_per_run.map(|n| {
        let per_run = n as f64 * seconds_per_evaluation / threads as f64;
        let per_run = stop.wall_seconds.map_or(per_run, |w| per_run.min(w));
        per_run * experiment.runs as f64
    });
    Ok(Validation {
        resolved: experiment.to_toml(),
        genes,
        memory: MemoryEstimate::of(experiment, genes, threads),
        evaluations_per_run,
        seconds_per_evaluation,
        estimated_seconds,
        threads,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config;

    #[test]
    fn the_quickstart_is_resolved_sized_and_timed() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/quickstart.toml");
        let experiment = config::load(path.as_ref()).unwrap();
        let v = validate(&experiment, 2).unwrap();
        assert_eq!(v.genes, 45);
        assert_eq!(v.evaluations_per_run, Some(8000));
        assert!(v.resolved.contains("population_size = 40"), "{}", v.resolved);
        assert!(v.seconds_per_evaluation > 0.0);
        let estimate = v.estimated_seconds.unwrap();
        assert!((estimate - 8000.0 * v.seconds_per_evaluation / 2.0).abs() < 1e-9);
    }

    #[test]
    fn generations_are_counted_in_batches_and_cma_es_writes_its_population_size() {
        let text = r#"
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }
[task]
duration = 1.0
[optimizer]
kind = "cma-es"
[stop]
generations = 10
"#;
        let experiment = config::parse(text, "cma.toml").unwrap();
        let v = validate(&experiment, 1).unwrap();
        // λ = 4 + ⌊3 ln 45⌋ = 15
        assert!(v.resolved.contains("population_size = 15"), "{}", v.resolved);
        assert_eq!(v.evaluations_per_run, Some(150));
    }
}
