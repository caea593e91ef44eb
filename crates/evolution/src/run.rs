//! A minimal serial driver: ask, evaluate each candidate, tell, until a stop criterion holds.
//! Meant for tests and benchmarks; the experiment runner adds parallel evaluation, wall-time
//! limits, logging and checkpoints on top of the same ask/tell calls.

use crate::error::EvolutionError;
use crate::optimizer::{Candidate, Evaluation, Tell};
use serde::{Deserialize, Serialize};

/// When to stop a run. Criteria are checked after every generation, so the last generation
/// may overshoot an evaluation budget (as in jgea). At least one of `max_evaluations` and
/// `max_generations` must be set. The run also ends when the optimizer stops by itself
/// ([`StopReason::Optimizer`]); a budget or target reached in the same generation wins.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Stop {
    /// Stop once at least this many fitness evaluations were told.
    pub max_evaluations: Option<u64>,
    /// Stop after this many generations.
    pub max_generations: Option<u64>,
    /// Stop once the best first-objective value reaches this target (under the optimizer's
    /// sense: `≥` when maximising, `≤` when minimising).
    pub target: Option<f64>,
}

impl Stop {
    /// Stop after `n` evaluations.
    pub fn evaluations(n: u64) -> Self {
        Self {
            max_evaluations: Some(n),
            ..Self::default()
        }
    }

    /// Stop after `n` generations.
    pub fn generations(n: u64) -> Self {
        Self {
            max_generations: Some(n),
            ..Self::default()
        }
    }

    /// Also stop when the best fitness reaches `target`.
    pub fn or_target(mut self, target: f64) -> Self {
        self.target = Some(target);
        self
    }
}

/// Why a run stopped.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum StopReason {
    /// The evaluation budget was used up.
    Evaluations,
    /// The generation budget was used up.
    Generations,
    /// The target fitness was reached.
    Target,
    /// The optimizer stopped by itself ([`Optimizer::stop_reason`](crate::Optimizer::stop_reason),
    /// e.g. `"cma-es:tolfun"`).
    Optimizer(String),
}

/// What [`run_to_budget`] did.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunSummary {
    /// Generations completed by the optimizer (in total, including earlier calls).
    pub generations: u64,
    /// Evaluations told (in total).
    pub evaluations: u64,
    /// Why it stopped.
    pub reason: StopReason,
}

/// Runs `optimizer` serially until `stop` holds, evaluating each candidate with `evaluate`.
/// Counts include whatever the optimizer had done before the call, so a resumed optimizer
/// continues towards the same budget.
pub fn run_to_budget<T, O, F>(optimizer: &mut T, mut evaluate: F, stop: &Stop) -> Result<RunSummary, EvolutionError>
where
    T: Tell<O> + ?Sized,
    F: FnMut(&Candidate<T::Genotype>) -> Evaluation<O>,
{
    if stop.max_evaluations.is_none() && stop.max_generations.is_none() {
        return Err(EvolutionError::Unbounded);
    }
    loop {
        let reason = if target_reached(optimizer, stop.target) {
            Some(StopReason::Target)
        } else if stop.max_evaluations.is_some_and(|n| optimizer.evaluations() >= n) {
            Some(StopReason::Evaluations)
        } else if stop.max_generations.is_some_and(|n| optimizer.generation() >= n) {
            Some(StopReason::Generations)
        } else {
            optimizer.stop_reason().map(|r| StopReason::Optimizer(r.to_string()))
        };
        if let Some(reason) = reason {
            return Ok(RunSummary {
                generations: optimizer.generation(),
                evaluations: optimizer.evaluations(),
                reason,
            });
        }
        let batch = optimizer.ask();
        let results = batch.iter().map(|c| c.told(evaluate(c))).collect();
        optimizer.tell(results)?;
    }
}

fn target_reached<T: Tell<O> + ?Sized, O>(optimizer: &T, target: Option<f64>) -> bool {
    match (target, optimizer.best()) {
        (Some(target), Some(best)) => optimizer.senses()[0].reaches(best.objectives[0], target),
        _ => false,
    }
}
