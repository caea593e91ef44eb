//! The ask/tell protocol shared by all optimizers, and the plain data that crosses it.
//!
//! A run is driven from outside: [`Optimizer::ask`] hands out a batch of [`Candidate`]s, the
//! caller evaluates them however it likes (serially, on threads, on other machines, in any
//! order) and hands the results back with [`Tell::tell`], each tagged with its candidate id.
//! The optimizer sorts results by id, so the order in which they arrive never matters.
//!
//! Fitness is a vector of objective values (one for single-objective optimizers). Whether
//! larger or smaller is better is the optimizer's [`Sense`] per objective; the default is
//! [`Sense::Maximize`] because robots maximise velocity. NaN is always the worst value.

use crate::error::EvolutionError;
use crate::search_state::SearchState;
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// Whether larger or smaller values of an objective are better.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Sense {
    /// Larger is better (e.g. velocity).
    #[default]
    Maximize,
    /// Smaller is better (e.g. a loss or a benchmark function).
    Minimize,
}

impl Sense {
    /// The value mapped to "larger is better"; NaN maps to −∞ so it loses every comparison.
    pub fn utility(self, value: f64) -> f64 {
        if value.is_nan() {
            f64::NEG_INFINITY
        } else {
            match self {
                Sense::Maximize => value,
                Sense::Minimize => -value,
            }
        }
    }

    /// Compares two values, `Greater` meaning `a` is better.
    pub fn compare(self, a: f64, b: f64) -> Ordering {
        self.utility(a).total_cmp(&self.utility(b))
    }

    /// Whether `value` is at least as good as `target`.
    pub fn reaches(self, value: f64, target: f64) -> bool {
        self.compare(value, target) != Ordering::Less
    }
}

/// One genotype to evaluate, as handed out by [`Optimizer::ask`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Candidate<G> {
    /// Position in the batch; the result must be told back with this id.
    pub id: usize,
    /// The genotype to evaluate.
    pub genotype: G,
    /// A seed for the evaluator's own randomness (e.g. a random terrain), derived from
    /// (run seed, generation, id) so it does not depend on evaluation order.
    pub seed: u64,
    /// `true` when this is a survivor re-evaluated for a noisy task (not a birth).
    pub reevaluation: bool,
}

impl<G> Candidate<G> {
    /// Tags an evaluation with this candidate's id.
    pub fn told<O>(&self, evaluation: Evaluation<O>) -> Told<O> {
        Told {
            id: self.id,
            evaluation,
        }
    }
}

/// What the caller measured for one candidate.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation<O = ()> {
    /// Objective values (exactly one for single-objective optimizers).
    pub objectives: Vec<f64>,
    /// Behaviour descriptor (MAP-Elites); empty when unused.
    pub descriptor: Vec<f64>,
    /// Any further outcome of the evaluation; only optimizers that need it (the speciated
    /// evolver's feature provider) look at it.
    pub outcome: O,
}

impl Evaluation<()> {
    /// A single-objective evaluation.
    pub fn single(fitness: f64) -> Self {
        Self::multi(vec![fitness])
    }

    /// A multi-objective evaluation.
    pub fn multi(objectives: Vec<f64>) -> Self {
        Self {
            objectives,
            descriptor: Vec::new(),
            outcome: (),
        }
    }
}

impl<O> Evaluation<O> {
    /// Adds a behaviour descriptor (for MAP-Elites).
    pub fn with_descriptor(mut self, descriptor: Vec<f64>) -> Self {
        self.descriptor = descriptor;
        self
    }

    /// Attaches an outcome (for feature providers).
    pub fn with_outcome<P>(self, outcome: P) -> Evaluation<P> {
        Evaluation {
            objectives: self.objectives,
            descriptor: self.descriptor,
            outcome,
        }
    }
}

/// An evaluation tagged with the id of the candidate it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct Told<O = ()> {
    /// The candidate's [`Candidate::id`].
    pub id: usize,
    /// Its evaluation.
    pub evaluation: Evaluation<O>,
}

/// An evaluated genotype kept by an optimizer (population member, archive elite, sample).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Individual<G> {
    /// The genotype.
    pub genotype: G,
    /// Its objective values, as told.
    #[serde(with = "crate::serde_float::vec")]
    pub objectives: Vec<f64>,
    /// Its descriptor, as told (empty unless MAP-Elites).
    #[serde(with = "crate::serde_float::vec")]
    pub descriptor: Vec<f64>,
    /// Generation in which the genotype was born (0 = initial population).
    pub birth_generation: u64,
}

impl<G> Individual<G> {
    /// The first objective: the fitness of a single-objective run.
    pub fn fitness(&self) -> f64 {
        self.objectives[0]
    }
}

/// The query-and-ask half of an optimizer: everything that does not depend on the outcome type.
///
/// Optimizers are plain serde-serialisable values (the speciated evolver when its feature
/// provider is serialisable): serialising one between `tell` and the next `ask` (or between
/// `ask` and `tell`) and deserialising it later resumes the run bit-identically.
pub trait Optimizer {
    /// The genotype searched.
    type Genotype: Clone;

    /// The batch to evaluate now. Calling it again before [`Tell::tell`] returns the same batch.
    fn ask(&mut self) -> Vec<Candidate<Self::Genotype>>;

    /// The run seed, counters, pending batch and best individual: the bookkeeping shared by all
    /// optimizers, behind [`Optimizer::counters`] and [`Optimizer::best`].
    fn search_state(&self) -> &SearchState<Self::Genotype>;

    /// Generations, evaluations and births so far.
    fn counters(&self) -> &Counters {
        self.search_state().counters()
    }

    /// Completed generations (number of successful `tell`s).
    fn generation(&self) -> u64 {
        self.counters().generation
    }

    /// Fitness evaluations told so far (births plus re-evaluations).
    fn evaluations(&self) -> u64 {
        self.counters().evaluations
    }

    /// New genotypes evaluated so far.
    fn births(&self) -> u64 {
        self.counters().births
    }

    /// Whether each objective is maximised or minimised.
    fn senses(&self) -> &[Sense];

    /// The best individual told so far (lexicographic over objectives for multi-objective
    /// optimizers). With noisy fitness this is an optimistic estimate.
    fn best(&self) -> Option<&Individual<Self::Genotype>> {
        self.search_state().best()
    }

    /// The current population: survivors (GA, SE, NSGA-II), the last evaluated batch (ES,
    /// CMA-ES) or the archive's elites (MAP-Elites).
    fn population(&self) -> Vec<&Individual<Self::Genotype>>;

    /// The last generation whole, best first: for the μ + λ GA the pool its truncation chose
    /// from (the parents it started from and this generation's children: the population of
    /// EvoGym's GA and of thesis ch. 5.2, where the best fifth survives); for every other
    /// optimizer its [`Optimizer::population`].
    fn generation_pool(&self) -> Vec<&Individual<Self::Genotype>> {
        self.population()
    }

    /// Why the optimizer has stopped by itself (a termination criterion of its own, e.g.
    /// `"cma-es:tolfun"`), or `None` while it can go on. Drivers end the run when it is `Some`;
    /// calling `ask`/`tell` afterwards is allowed but unlikely to help.
    fn stop_reason(&self) -> Option<&'static str> {
        None
    }
}

/// The tell half, generic over the outcome type `O` carried by evaluations. Optimizers that
/// ignore outcomes implement it for every `O`.
pub trait Tell<O = ()>: Optimizer {
    /// Takes the results of the batch returned by the last [`Optimizer::ask`], in any order,
    /// and advances one generation.
    fn tell(&mut self, results: Vec<Told<O>>) -> Result<(), EvolutionError>;
}

/// How far an optimizer has gone (the same three counters for every optimizer).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Counters {
    /// Completed generations.
    pub generation: u64,
    /// Evaluations told (births plus re-evaluations).
    pub evaluations: u64,
    /// New genotypes evaluated.
    pub births: u64,
}

impl Counters {
    pub(crate) fn advance<G>(&mut self, batch: &[Candidate<G>]) {
        self.generation += 1;
        self.evaluations += batch.len() as u64;
        self.births += batch.iter().filter(|c| !c.reevaluation).count() as u64;
    }
}

/// Sorts results by candidate id and checks that they match the pending batch exactly and have
/// `n_objectives` objectives each.
pub(crate) fn collect_results<O>(
    results: Vec<Told<O>>,
    expected: usize,
    n_objectives: usize,
) -> Result<Vec<Evaluation<O>>, EvolutionError> {
    let mismatch = |detail: String| EvolutionError::BatchMismatch { expected, detail };
    if results.len() != expected {
        return Err(mismatch(format!("got {} results", results.len())));
    }
    let mut slots: Vec<Option<Evaluation<O>>> = (0..expected).map(|_| None).collect();
    for told in results {
        let slot = slots
            .get_mut(told.id)
            .ok_or_else(|| mismatch(format!("unknown candidate id {}", told.id)))?;
        if slot.is_some() {
            return Err(mismatch(format!("candidate id {} told twice", told.id)));
        }
        let got = told.evaluation.objectives.len();
        if got != n_objectives {
            return Err(EvolutionError::ObjectiveCount {
                id: told.id,
                expected: n_objectives,
                got,
            });
        }
        *slot = Some(told.evaluation);
    }
    Ok(slots.into_iter().map(|s| s.expect("all ids present")).collect())
}

/// Lexicographic comparison of two objective vectors, `Greater` meaning `a` is better.
pub(crate) fn compare_lexicographic(a: &[f64], b: &[f64], senses: &[Sense]) -> Ordering {
    for ((&x, &y), sense) in a.iter().zip(b).zip(senses) {
        match sense.compare(x, y) {
            Ordering::Equal => continue,
            other => return other,
        }
    }
    Ordering::Equal
}

/// Validates a configuration value, producing an [`EvolutionError::InvalidConfig`].
pub(crate) fn ensure(condition: bool, message: impl FnOnce() -> String) -> Result<(), EvolutionError> {
    if condition {
        Ok(())
    } else {
        Err(EvolutionError::InvalidConfig(message()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn senses_order_values_and_nan_is_worst() {
        assert_eq!(Sense::Maximize.compare(2.0, 1.0), Ordering::Greater);
        assert_eq!(Sense::Minimize.compare(2.0, 1.0), Ordering::Less);
        assert_eq!(Sense::Minimize.compare(f64::NAN, 1e300), Ordering::Less);
        assert_eq!(Sense::Maximize.compare(f64::NAN, -1e300), Ordering::Less);
        assert!(Sense::Minimize.reaches(1e-9, 1e-8));
        assert!(!Sense::Maximize.reaches(1e-9, 1e-8));
    }

    #[test]
    fn results_are_sorted_by_id_and_validated() {
        let told = |id, f| Told {
            id,
            evaluation: Evaluation::single(f),
        };
        let sorted = collect_results(vec![told(2, 2.0), told(0, 0.0), told(1, 1.0)], 3, 1).unwrap();
        assert_eq!(
            sorted.iter().map(|e| e.objectives[0]).collect::<Vec<_>>(),
            [0.0, 1.0, 2.0]
        );
        assert!(collect_results(vec![told(0, 0.0), told(0, 1.0)], 2, 1).is_err());
        assert!(collect_results(vec![told(0, 0.0), told(5, 1.0)], 2, 1).is_err());
        assert!(collect_results(vec![told(0, 0.0)], 2, 1).is_err());
        assert!(matches!(
            collect_results(vec![told(0, 0.0)], 1, 2),
            Err(EvolutionError::ObjectiveCount { .. })
        ));
    }
}
