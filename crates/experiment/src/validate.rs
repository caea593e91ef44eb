//! `vsrlab validate`: what an experiment file will do, before it runs: the resolved
//! configuration (every default written out), the genotype size, the memory estimate, and a
//! time estimate from one timed evaluation.

use crate::config::Experiment;
use crate::memory::MemoryEstimate;
use crate::optimizers::FieldError;
use std::time::Instant;

/// Initial genotypes timed for the estimate.
const TIMED_EVALUATIONS: usize = 3;
/// Steps of each timed episode, at most (10 s at the usual 60 Hz): a longer episode is timed on
/// its first steps and the time scaled up, so that validating a file of absurd length
/// (`dt = 1e-12`) takes seconds, not the episode's length.
const TIMED_STEPS: f64 = 600.0;
/// Steps of the probe that sizes the timed episodes, and the fewest steps they are cut to.
const PROBE_STEPS: f64 = 10.0;
/// Wall seconds the timed evaluations aim at in all: a body so large that 600 steps would take
/// longer (100 × 100 voxels: a minute per evaluation) is timed on fewer.
const TIMING_BUDGET: f64 = 3.0;

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
    // a probe of a few steps says how many steps the timed episodes can afford
    let seconds_per_evaluation = match shortened(experiment, PROBE_STEPS).0 {
        // an episode of a few steps, or one that cannot be cut: timed whole
        None => time_whole(experiment, kind)?,
        Some(probe) => {
            // the probe's genotypes are the timed ones, so "all failed" means the same
            kind.time_evaluations(&probe, TIMED_EVALUATIONS)?;
            let per_step = start.elapsed().as_secs_f64() / (TIMED_EVALUATIONS as f64 * PROBE_STEPS);
            let affordable = (TIMING_BUDGET / (TIMED_EVALUATIONS as f64 * per_step)).floor();
            let (timed, scale) = shortened(experiment, affordable.clamp(PROBE_STEPS, TIMED_STEPS));
            let start = Instant::now();
            kind.time_evaluations(timed.as_ref().unwrap_or(experiment), TIMED_EVALUATIONS)?;
            scale * start.elapsed().as_secs_f64() / TIMED_EVALUATIONS as f64
        }
    };
    let seconds_per_evaluation = seconds_per_evaluation * kind.timing_scale(experiment);
    let genes = kind.size(experiment)?.genes;
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

/// Mean seconds of [`TIMED_EVALUATIONS`] evaluations of the experiment as it is.
fn time_whole(experiment: &Experiment, kind: &dyn crate::genotypes::GenotypeKind) -> Result<f64, FieldError> {
    let start = Instant::now();
    kind.time_evaluations(experiment, TIMED_EVALUATIONS)?;
    Ok(start.elapsed().as_secs_f64() / TIMED_EVALUATIONS as f64)
}

/// The experiment whose episodes are timed, when it is not `experiment` itself: the same with
/// its task's `duration` cut to `steps` steps; and the factor from that episode's length to the
/// full one's. An episode of an engine without a step (or a task without a `duration`) is timed
/// whole.
fn shortened(experiment: &Experiment, steps: f64) -> (Option<Experiment>, f64) {
    let task = experiment.task.spec.task();
    let (duration, dt) = (task.duration(), task.step_seconds());
    if !(dt > 0.0 && duration / dt > steps) {
        return (None, 1.0);
    }
    let short = steps * dt;
    let Ok(mut table) = experiment.to_toml().parse::<toml::Table>() else {
        return (None, 1.0);
    };
    match table.get_mut("task").and_then(|t| t.get_mut("duration")) {
        Some(value @ toml::Value::Float(_)) => *value = toml::Value::Float(short),
        _ => return (None, 1.0),
    }
    match crate::config::parse(&table.to_string(), "timed copy") {
        Ok(copy) => (Some(copy), duration / short),
        Err(_) => (None, 1.0),
    }
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
    fn an_episode_of_absurd_length_is_timed_on_its_first_steps() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/quickstart.toml");
        let text = std::fs::read_to_string(path)
            .unwrap()
            .replace("duration = 10.0", "duration = 10.0\nphysics = { dt = 1e-9 }");
        let experiment = config::parse(&text, "tiny-dt.toml").unwrap();
        let start = Instant::now();
        let v = validate(&experiment, 2).unwrap();
        assert!(start.elapsed().as_secs_f64() < 60.0, "{:?}", start.elapsed());
        // 1e10 steps per episode, timed on 600 of them: hours per evaluation, not milliseconds
        assert!(v.seconds_per_evaluation > 1e3, "{}", v.seconds_per_evaluation);
        let (copy, scale) = shortened(&experiment, TIMED_STEPS);
        assert!((scale - 1e10 / TIMED_STEPS).abs() / scale < 1e-9, "{scale}");
        assert!((copy.unwrap().task.spec.task().duration() - 6e-7).abs() < 1e-15);
        let quickstart = config::load(path.as_ref()).unwrap();
        assert!(
            shortened(&quickstart, TIMED_STEPS).0.is_none(),
            "600 steps are timed whole"
        );
    }

    #[test]
    fn the_largest_body_is_timed_on_as_many_steps_as_fit_in_the_budget() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/quickstart.toml");
        let rows = vec!["#".repeat(100); 100].join("/");
        let text = std::fs::read_to_string(path)
            .unwrap()
            .replace("body = \"biped-4x3\"", &format!("body = \"{rows}\""));
        let experiment = config::parse(&text, "box-100.toml").unwrap();
        let start = Instant::now();
        let v = validate(&experiment, 2).unwrap();
        let took = start.elapsed().as_secs_f64();
        // a whole evaluation takes a minute or more: the timing stays near its budget (a margin
        // for the other tests that share the cores)
        assert!(took < 6.0 * TIMING_BUDGET, "{took} s");
        assert!(
            v.seconds_per_evaluation > took / TIMED_EVALUATIONS as f64,
            "{} vs {took}",
            v.seconds_per_evaluation
        );
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
