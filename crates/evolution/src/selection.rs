//! Selection helpers shared by the population-based optimizers.

use crate::optimizer::{Individual, Sense};
use crate::rng::SeededRng;

/// Sorts individuals best-first by their first objective. The sort is stable, so among equal
/// fitnesses the earlier individual stays first (callers choose the order to break ties).
pub(crate) fn sort_best_first<G>(individuals: &mut [Individual<G>], sense: Sense) {
    individuals.sort_by(|a, b| sense.compare(b.fitness(), a.fitness()));
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
