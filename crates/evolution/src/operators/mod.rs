//! Genotype representations: how to sample, mutate and recombine a genotype.
//!
//! The population-based optimizers (GA, speciated evolver, MAP-Elites, NSGA-II) know nothing of
//! the genotype beyond this trait, so a graph genotype only needs a new [`Representation`].
//! Two are provided for flat real vectors:
//! - [`RealVector`]: the thesis operators (Gaussian mutation; extended geometric crossover
//!   followed by a small Gaussian perturbation), unbounded.
//! - [`SbxPolynomial`]: simulated binary crossover and polynomial mutation (Deb), bounded; the
//!   usual NSGA-II operators.

mod real_vector;
mod sbx_polynomial;

pub use real_vector::RealVector;
pub use sbx_polynomial::SbxPolynomial;

use crate::error::EvolutionError;
use crate::rng::{SeededRng, Stream};
use crate::search_state::SearchState;

/// Sampling and variation of one kind of genotype. All randomness comes from the `rng` passed
/// in, which the optimizer derives per candidate.
pub trait Representation {
    /// The genotype.
    type Genotype: Clone;

    /// Checks the representation's parameters; optimizers call it in their constructors.
    fn validate(&self) -> Result<(), EvolutionError> {
        Ok(())
    }

    /// A random genotype for the initial population.
    fn random(&self, rng: &mut SeededRng) -> Self::Genotype;

    /// Member `index` of the initial population: a random genotype by default; a representation
    /// seeded from a known genotype may put that genotype itself first (transfer experiments).
    fn initial(&self, _index: usize, rng: &mut SeededRng) -> Self::Genotype {
        self.random(rng)
    }

    /// The mutation operator: one child from one parent.
    fn mutate(&self, parent: &Self::Genotype, rng: &mut SeededRng) -> Self::Genotype;

    /// The crossover operator (including any mutation the representation applies after it):
    /// one child from two parents.
    fn crossover(&self, first: &Self::Genotype, second: &Self::Genotype, rng: &mut SeededRng) -> Self::Genotype;

    /// Whether two genotypes count as duplicates, for optimizers that can eliminate duplicate
    /// children (NSGA-II's `with_duplicate_elimination`). The default says never.
    fn is_duplicate(&self, _a: &Self::Genotype, _b: &Self::Genotype) -> bool {
        false
    }
}

/// The genotypes of a first batch: `count` initial ones, genotype `i` drawn from the
/// initialisation stream of index `i` in the current generation.
pub(crate) fn random_genotypes<R: Representation>(
    representation: &R,
    state: &SearchState<R::Genotype>,
    count: usize,
) -> Vec<R::Genotype> {
    (0..count)
        .map(|i| representation.initial(i, &mut state.rng(i, Stream::Initialisation)))
        .collect()
}

/// One child: with probability `mutation_probability` the mutation of one parent, otherwise
/// the crossover of two. `select` picks each parent, after the choice is drawn from `rng`.
pub(crate) fn mutate_or_crossover<'a, R: Representation>(
    representation: &R,
    mutation_probability: f64,
    rng: &mut SeededRng,
    mut select: impl FnMut(&mut SeededRng) -> &'a R::Genotype,
) -> R::Genotype
where
    R::Genotype: 'a,
{
    if rng.uniform() < mutation_probability {
        let parent = select(rng);
        representation.mutate(parent, rng)
    } else {
        let first = select(rng);
        let second = select(rng);
        representation.crossover(first, second, rng)
    }
}
