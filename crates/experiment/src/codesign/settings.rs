//! What the co-design genotype kinds share: the EvoGym task of the experiment, the checks of a
//! grid's size and of PPO's settings, running and timing the experiment.

use super::evaluator::CodesignEvaluator;
use super::learn::Episode;
use crate::config::Experiment;
use crate::evaluator::Evaluator;
use crate::genotype::Genotype;
use crate::optimizers::{FieldError, SearchOptimizer};
use crate::runner::{run_search, Observer, Plan, RunError, RunOptions, RunSummary};
use std::path::Path;
use vsrlab_learning::{PpoConfig, PpoError};
use vsrlab_tasks::kinds::evogym::{EvoGymTask, MAX_ROBOT_SIDE, STEP_SECONDS};
use vsrlab_tasks::task::episode_steps;
use vsrlab_tasks::{Representation, TaskSpec};

/// The EvoGym task an experiment's bodies learn on, with its episode length (the task's own, or
/// fewer steps when `task.duration` says so); an error on `task.kind` (or `task.env`) for any
/// other task.
pub fn evogym_task(experiment: &Experiment) -> Result<Episode, FieldError> {
    let TaskSpec::Evogym(task) = &experiment.task.spec else {
        return Err(FieldError::new(
            "task.kind",
            format!(
                "a co-designed body learns on an EvoGym task (kind = \"evogym\"), not {}",
                experiment.task.spec.task().kind()
            ),
        ));
    };
    let which =
        EvoGymTask::from_name(&task.env).ok_or_else(|| FieldError::new("task.env", EvoGymTask::unknown(&task.env)))?;
    let own = which.episode_steps();
    let steps = task
        .duration
        .map_or(own, |d| own.min(episode_steps(d, STEP_SECONDS) as usize));
    Ok(Episode { task: which, steps })
}

/// The representation a co-design experiment writes when its file gives none: an EvoGym body
/// of the grid's size (all horizontal actuators) on the task's environment, with the EvoGym
/// robot's default brain. The loop itself makes every body from its genotype and learns its
/// brain; the table only records the kind of robot in the resolved `experiment.toml`.
pub fn implied_representation(task: &crate::config::TaskConfig, width: usize, height: usize) -> Option<Representation> {
    let env = match &task.spec {
        TaskSpec::Evogym(t) => t.env.clone(),
        _ => EvoGymTask::Walker.name().to_string(),
    };
    let rows = vec!["3".repeat(width.clamp(1, MAX_ROBOT_SIDE)); height.clamp(1, MAX_ROBOT_SIDE)].join("/");
    let table = serde_json::json!({
        "body": { "kind": "evogym", "body": rows, "env": env },
        "brain": { "kind": "mlp" },
    });
    serde_json::from_value(table).ok()
}

/// The evaluator of a co-design kind: bodies from `body`, trained with `ppo` on the
/// experiment's EvoGym task.
pub fn codesign_evaluator<G>(
    experiment: &Experiment,
    body: super::BodyOf<G>,
    ppo: PpoConfig,
    learning_curve: bool,
) -> Result<CodesignEvaluator<G>, FieldError> {
    Ok(CodesignEvaluator::new(
        body,
        evogym_task(experiment)?,
        ppo,
        learning_curve,
    ))
}

/// Checks the grid's size and PPO's settings of a co-design kind, and its task; errors name the
/// field (`genotype.width`, `genotype.ppo.clip`, `task.kind`).
pub fn validate_codesign(
    experiment: &Experiment,
    width: usize,
    height: usize,
    ppo: &PpoConfig,
) -> Result<(), FieldError> {
    for (field, side) in [("width", width), ("height", height)] {
        if !(1..=MAX_ROBOT_SIDE).contains(&side) {
            return Err(FieldError::new(
                format!("genotype.{field}"),
                format!("must be in 1..={MAX_ROBOT_SIDE}, got {side}"),
            ));
        }
    }
    ppo.validate().map_err(|e| match e {
        PpoError::Invalid { field, message } => FieldError::new(format!("genotype.ppo.{field}"), message),
        other => FieldError::new("genotype.ppo", other.to_string()),
    })?;
    evogym_task(experiment)?;
    Ok(())
}

/// Runs every run of a co-design experiment into `out`: `new_optimizer` builds a run's
/// optimizer from its seed; every evaluation trains PPO ([`CodesignEvaluator`]).
pub fn run_codesign<G: Genotype, O: SearchOptimizer<G>>(
    experiment: &Experiment,
    evaluator: &CodesignEvaluator<G>,
    new_optimizer: &crate::runner::NewOptimizer<'_, O>,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    run_search(&Plan::of(experiment), new_optimizer, evaluator, out, options, observer)
}

/// PPO iterations a time estimate runs per evaluation (then scaled to the configured number).
pub const TIMED_ITERATIONS: usize = 2;

/// PPO's settings cut to [`TIMED_ITERATIONS`] iterations, and the factor back to the full
/// training (its cost grows with the iterations; the off-line episodes of the learning curve
/// too).
pub fn timed_ppo(ppo: &PpoConfig) -> (PpoConfig, f64) {
    let iterations = ppo.iterations.min(TIMED_ITERATIONS);
    let timed = PpoConfig {
        iterations,
        ..ppo.clone()
    };
    (timed, ppo.iterations as f64 / iterations as f64)
}

/// Evaluates `genotypes` with `evaluator` (built with [`timed_ppo`]'s settings); an error when
/// every one failed, as every run would.
pub fn time_codesign<G: Sync>(evaluator: &CodesignEvaluator<G>, genotypes: &[G]) -> Result<(), FieldError> {
    let errors: Vec<Option<String>> = genotypes
        .iter()
        .enumerate()
        .map(|(i, g)| evaluator.evaluate(g, i as u64).record.error)
        .collect();
    crate::genotypes::unless_every_evaluation_failed(&errors)
}

/// What a co-design body's fitness is: the learned policy's mean reward per step, off-line, after
/// its last iteration (not the task's summed reward).
pub const FITNESS_NAME: &str = "reward per step";

/// The figure of the co-design kinds' logged body size: the share of the grid's cells present.
pub fn column_figures() -> Vec<crate::genotypes::ColumnFigure> {
    vec![crate::genotypes::ColumnFigure {
        column: "size",
        file: "body-size",
        title: "Size of the best body during evolution",
        axis: "cells present / cells of the grid",
        description: "share of the grid's cells present in the best body vs evaluations, median ± sd across runs",
    }]
}
