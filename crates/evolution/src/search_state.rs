//! [`SearchState`]: the bookkeeping every ask/tell optimizer keeps besides its own search
//! state (population, archive, mean): the run seed, the [`Counters`], the batch handed out and
//! not yet told, and the best individual so far.
//!
//! An optimizer embeds one (flattened into its serialised form, so a checkpoint stores the
//! fields `seed`, `counters`, `pending` and `best` next to the optimizer's own) and exposes it
//! through [`Optimizer::search_state`](crate::Optimizer::search_state), which gives the
//! counters and the best individual of the trait for free. Its methods are the steps shared by
//! all `ask`s and `tell`s:
//!
//! - `ask`: return [`SearchState::pending_batch`] when there is one, otherwise build the
//!   genotypes (drawing from [`SearchState::rng`]) and [`SearchState::hand_out`] them;
//! - `tell`: [`SearchState::take_told`] the results, turn births into individuals with
//!   [`SearchState::born`] / [`SearchState::born_all`] (offering them as the best so far with
//!   [`SearchState::offer`]), update the search state, then [`SearchState::advance`].

use crate::error::EvolutionError;
use crate::optimizer::{
    collect_results, compare_lexicographic, Candidate, Counters, Evaluation, Individual, Sense, Told,
};
use crate::rng::{evaluation_seed, SeededRng, Stream};
use serde::{Deserialize, Serialize};
use std::cmp::Ordering;

/// Seed, counters, pending batch and best individual of one optimizer run (see the module
/// docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SearchState<G> {
    seed: u64,
    counters: Counters,
    pending: Option<Vec<Candidate<G>>>,
    best: Option<Individual<G>>,
}

impl<G> SearchState<G> {
    /// The state of a new run with the given run seed: nothing asked, told or found yet.
    pub fn new(seed: u64) -> Self {
        Self {
            seed,
            counters: Counters::default(),
            pending: None,
            best: None,
        }
    }

    /// The run seed.
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// Generations, evaluations and births so far.
    pub fn counters(&self) -> &Counters {
        &self.counters
    }

    /// The current generation (the number of completed ones).
    pub fn generation(&self) -> u64 {
        self.counters.generation
    }

    /// The best individual told so far.
    pub fn best(&self) -> Option<&Individual<G>> {
        self.best.as_ref()
    }

    /// The generator for draw `index` of purpose `stream` in the current generation.
    pub fn rng(&self, index: usize, stream: Stream) -> SeededRng {
        SeededRng::derive(self.seed, self.counters.generation, index as u64, stream)
    }

    /// Checks `results` against the pending batch and, when they match, takes the batch: a
    /// failed check leaves the batch pending so that the caller may tell again.
    pub fn take_told<O>(
        &mut self,
        results: Vec<Told<O>>,
        n_objectives: usize,
    ) -> Result<Evaluated<G, O>, EvolutionError> {
        self.take_told_checked(results, n_objectives, |_| Ok(()))
    }

    /// [`SearchState::take_told`] with a further check of the evaluations (in candidate order)
    /// before the batch is taken.
    pub fn take_told_checked<O>(
        &mut self,
        results: Vec<Told<O>>,
        n_objectives: usize,
        check: impl FnOnce(&[Evaluation<O>]) -> Result<(), EvolutionError>,
    ) -> Result<Evaluated<G, O>, EvolutionError> {
        let batch = self.pending.as_ref().ok_or(EvolutionError::NoPendingBatch)?;
        let evaluations = collect_results(results, batch.len(), n_objectives)?;
        check(&evaluations)?;
        Ok((self.pending.take().expect("checked above"), evaluations))
    }

    /// Ends the generation of the told `batch`: counts it and moves to the next generation.
    pub fn advance(&mut self, batch: &[Candidate<G>]) {
        self.counters.advance(batch);
    }
}

impl<G: Clone> SearchState<G> {
    /// The batch handed out and not yet told, if any (what `ask` must return again).
    pub fn pending_batch(&self) -> Option<Vec<Candidate<G>>> {
        self.pending.clone()
    }

    /// Makes `genotypes` the pending batch of the current generation and returns it: ids in
    /// order, evaluation seeds from the run seed, and the genotypes at positions
    /// `first_reevaluation..` flagged as re-evaluations.
    pub fn hand_out(&mut self, genotypes: Vec<G>, first_reevaluation: usize) -> Vec<Candidate<G>> {
        let generation = self.counters.generation;
        let batch: Vec<Candidate<G>> = genotypes
            .into_iter()
            .enumerate()
            .map(|(id, genotype)| Candidate {
                id,
                genotype,
                seed: evaluation_seed(self.seed, generation, id as u64),
                reevaluation: id >= first_reevaluation,
            })
            .collect();
        self.pending = Some(batch.clone());
        batch
    }

    /// The individual born in the current generation from `candidate` and its evaluation.
    pub fn born<O>(&self, candidate: &Candidate<G>, evaluation: Evaluation<O>) -> Individual<G> {
        Individual {
            genotype: candidate.genotype.clone(),
            objectives: evaluation.objectives,
            descriptor: evaluation.descriptor,
            birth_generation: self.counters.generation,
        }
    }

    /// The individuals born from a told batch, in candidate order, each offered as the best so
    /// far.
    pub fn born_all<O>(
        &mut self,
        batch: &[Candidate<G>],
        evaluations: Vec<Evaluation<O>>,
        senses: &[Sense],
    ) -> Vec<Individual<G>> {
        batch
            .iter()
            .zip(evaluations)
            .map(|(candidate, evaluation)| {
                let individual = self.born(candidate, evaluation);
                self.offer(&individual, senses);
                individual
            })
            .collect()
    }

    /// Makes `individual` the best, whatever the best was (optimizers of noisy tasks whose best
    /// is that of the current population, evaluated afresh).
    pub fn replace_best(&mut self, individual: Option<&Individual<G>>) {
        self.best = individual.cloned();
    }

    /// Makes `candidate` the best so far when it is strictly better (lexicographically over
    /// the objectives) than the current best.
    pub fn offer(&mut self, candidate: &Individual<G>, senses: &[Sense]) {
        let better = match &self.best {
            None => true,
            Some(best) => compare_lexicographic(&candidate.objectives, &best.objectives, senses) == Ordering::Greater,
        };
        if better {
            self.best = Some(candidate.clone());
        }
    }
}

/// A told batch and its evaluations, in candidate order.
pub type Evaluated<G, O> = (Vec<Candidate<G>>, Vec<Evaluation<O>>);
