//! Selection helpers shared by the population-based optimizers.

use crate::optimizer::{compare_lexicographic, Individual, Sense};
use crate::rng::SeededRng;

/// Sorts `individuals` best first by their objectives compared lexicographically under `senses`
/// (stable: equal ones keep their order, so callers choose the order that breaks ties).
pub(crate) fn sort_lexicographic<G>(individuals: &mut [Individual<G>], senses: &[Sense]) {
    individuals.sort_by(|a, b| compare_lexicographic(&b.objectives, &a.objectives, senses));
}

/// Tournament selection on a best-first sorted population: draws `size` positions uniformly
/// *with replacement* (as jgea's `Tournament`) and returns the best of them, i.e. the smallest
/// position. Ties in fitness are thereby broken by population order, deterministically.
pub(crate) fn tournament(population_len: usize, size: usize, rng: &mut SeededRng) -> usize {
    (0..size.max(1))
        .map(|_| rng.below(population_len))
        .min()
        .expect("tournament size >= 1")
}

/// Indices of `individuals` ordered best-first by their first objective (stable: among equal
/// fitnesses the smaller index comes first). The ranking of ES and CMA-ES samples.
pub(crate) fn rank_best_first<G>(individuals: &[Individual<G>], sense: Sense) -> Vec<usize> {
    let mut order: Vec<usize> = (0..individuals.len()).collect();
    order.sort_by(|&a, &b| sense.compare(individuals[b].fitness(), individuals[a].fitness()));
    order
}
