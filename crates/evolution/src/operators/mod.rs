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
use crate::rng::SeededRng;

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

    /// The mutation operator: one child from one parent.
    fn mutate(&self, parent: &Self::Genotype, rng: &mut SeededRng) -> Self::Genotype;

    /// The crossover operator (including any mutation the representation applies after it):
    /// one child from two parents.
    fn crossover(&self, first: &Self::Genotype, second: &Self::Genotype, rng: &mut SeededRng) -> Self::Genotype;
}
