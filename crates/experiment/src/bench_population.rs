//! The population rows of `vsrlab bench --population N`: one generation's worth of work as
//! `vsrlab run` does it. N genotypes of one body (the row's robot, its brain's weights drawn at
//! random for each) go through the runner's evaluator as one batch on the thread pool
//! ([`Evaluator::evaluate_batch`]), each building its robot and running its episode. Beside the
//! per-episode rows, which repeat one ready-built robot's episode, the row shows what a batch
//! costs end to end; a population stepping mode would show here as a higher rate.

use crate::bench::{BenchError, BenchOptions, Measured, Measurement, Mode, Row, StandardCase};
use crate::config::{self, Experiment};
use crate::cpu_time::process_cpu_seconds;
use crate::evaluator::EvaluatorError;
use crate::evaluator::{Evaluator, RobotEvaluator};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;
use vsrlab_brain::BrainSpec;
use vsrlab_tasks::TaskSpec;

/// Most genotypes in one population row.
pub const MAX_POPULATION: usize = 100_000;

/// Whether a standard robot has a population row: the rigid-body robots, voxel robots (which take
/// the options' brain), PSAs (their `heads` brain), 3D voxel robots and EvoGym robots (their row's
/// brain; the batches of both step in population lanes).
pub(crate) fn has_population_row(standard: &StandardCase) -> bool {
    standard.takes_options || is_psa(standard) || standard.body.starts_with("3d:") || evogym(standard).is_some()
}

/// An EvoGym row's task and rows (`evogym:<Task>:<rows>`).
fn evogym(standard: &StandardCase) -> Option<(&'static str, &'static str)> {
    standard.body.strip_prefix("evogym:")?.split_once(':')
}

fn is_psa(standard: &StandardCase) -> bool {
    standard.body.starts_with("psa:")
}

/// The experiment whose evaluator the row times: the row's body, sensors, preset and brain
/// template, on `task` (the per-episode rows' task: terrain, duration, physics).
fn experiment(standard: &StandardCase, options: &BenchOptions, task: &TaskSpec) -> Result<Experiment, BenchError> {
    let option = |e: String| BenchError::Option(format!("population: {e}"));
    let mut representation = toml::Table::new();
    let brain = match (standard.body.strip_prefix("psa:"), standard.body.strip_prefix("3d:")) {
        _ if evogym(standard).is_some() => {
            let (env, rows) = evogym(standard).unwrap_or_default();
            let mut body = toml::Table::new();
            body.insert("kind".into(), "evogym".into());
            body.insert("body".into(), rows.into());
            body.insert("env".into(), env.into());
            representation.insert("body".into(), body.into());
            standard.brain.unwrap_or("mlp")
        }
        (_, Some(shape)) => {
            let mut body = toml::Table::new();
            body.insert("kind".into(), "voxel3d".into());
            body.insert("body".into(), shape.into());
            representation.insert("body".into(), body.into());
            standard.brain.unwrap_or(vsrlab_tasks::kinds::voxel3d::DEFAULT_BRAIN)
        }
        (Some(size), _) => {
            let mut psa = toml::Table::new();
            psa.insert("kind".into(), "psa".into());
            psa.insert("size".into(), size.into());
            representation.insert("body".into(), psa.into());
            "heads"
        }
        (None, None) => {
            representation.insert("body".into(), standard.body.into());
            representation.insert("sensors".into(), options.sensors.as_str().into());
            representation.insert("preset".into(), options.preset.as_str().into());
            options.brain.as_str()
        }
    };
    let brain = BrainSpec::parse(brain).map_err(|e| BenchError::Option(format!("brain: {e}")))?;
    representation.insert(
        "brain".into(),
        toml::Value::try_from(&brain).map_err(|e| option(e.to_string()))?,
    );
    let table = |pairs: &[(&str, toml::Value)]| {
        toml::Value::Table(pairs.iter().map(|(k, v)| (k.to_string(), v.clone())).collect())
    };
    let document = table(&[
        ("name", "bench-population".into()),
        ("representation", representation.into()),
        ("task", table(&[("terrain", "flat".into())])),
        ("optimizer", table(&[("kind", "ga".into())])),
        ("stop", table(&[("evaluations", 1.into())])),
    ]);
    let text = toml::to_string(&document).map_err(|e| option(e.to_string()))?;
    let mut experiment = config::parse(&text, "bench").map_err(|e| option(e.to_string()))?;
    experiment.task.spec = task.clone();
    Ok(experiment)
}

/// `n` genotypes of the row's representation, genes uniform in [−1, 1] (seeded: the same
/// population every time).
fn population(evaluator: &RobotEvaluator, n: usize) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let genes = evaluator.genotype_length();
    (0..n)
        .map(|_| (0..genes).map(|_| rng.random_range(-1.0..=1.0)).collect())
        .collect()
}

/// Times one batch of `n` evaluations of the row's body on `pool`; `per_episode`: the steps one
/// episode of the task runs (every locomotion episode runs the task's length) and the robot's
/// size as the per-episode rows count it.
pub(crate) fn measure_population(
    standard: &StandardCase,
    options: &BenchOptions,
    task: &TaskSpec,
    pool: &rayon::ThreadPool,
    n: usize,
    per_episode: (u64, usize),
) -> Result<Row, BenchError> {
    let (steps_per_episode, voxels) = per_episode;
    let experiment = experiment(standard, options, task)?;
    let robot = standard.name;
    let evaluator = RobotEvaluator::new(&experiment).map_err(|e| BenchError::Population {
        robot,
        source: EvaluatorError::Robot(e),
    })?;
    let genotypes = population(&evaluator, n);
    let refs: Vec<&Vec<f64>> = genotypes.iter().collect();
    let seeds: Vec<u64> = (0..n as u64).collect();
    let (c0, w0) = (process_cpu_seconds(), Instant::now());
    let evaluated = pool
        .install(|| evaluator.evaluate_batch(&refs, &seeds))
        .map_err(|source| BenchError::Population { robot, source })?;
    let (cpu_seconds, wall_seconds) = (process_cpu_seconds() - c0, w0.elapsed().as_secs_f64());
    if let Some(reason) = evaluated.iter().find_map(|e| e.record.error.clone()) {
        return Err(BenchError::FailedEvaluation { robot, reason });
    }
    let what = Measured {
        robot: standard.name,
        terrain: standard.terrain,
        step_seconds: task.task().step_seconds(),
        voxels,
        mode: Mode::Population,
        threads: pool.current_num_threads(),
    };
    let m = Measurement {
        episodes: n,
        steps: steps_per_episode * n as u64,
        cpu_seconds,
        wall_seconds,
    };
    Ok(Row::measured(what, m, None))
}
