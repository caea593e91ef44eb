//! NSGA-II (thesis ch. 5.1), multi-objective, with the thesis' real-vector operators.
//!
//! Defaults: N = 100, 100 children per generation, Gaussian mutation (σ = 0.35) for a child with
//! probability `mutation_probability` (0.2), else extended geometric crossover then σ′ = 0.1.
//! The thesis' affordance runs used mutation only and N/2 children: `mutation_probability = 1`,
//! `offspring_size = 50`.

use super::check::{positive, probability};
use super::{check_operators, real_vector, AnyOptimizer, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, Nsga2, Nsga2Config, Sense};

/// Parameters of NSGA-II.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Nsga2Params {
    /// N, the population size (Deb et al. and thesis 100).
    pub population_size: usize,
    /// Children per generation (Deb et al.: N; thesis affordance runs: N/2).
    pub offspring_size: usize,
    /// Probability of a child by mutation alone instead of crossover.
    pub mutation_probability: f64,
    /// Initial genes uniform in [min, max).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation.
    pub mutation_sigma: f64,
    /// Per-gene α range of the extended geometric crossover.
    pub crossover_range: [f64; 2],
    /// σ′ of the Gaussian perturbation after crossover.
    pub crossover_sigma: f64,
}

impl Default for Nsga2Params {
    fn default() -> Self {
        Self {
            population_size: 100,
            offspring_size: 100,
            mutation_probability: 0.2,
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
            crossover_range: [-1.0, 2.0],
            crossover_sigma: 0.1,
        }
    }
}

impl OptimizerKind for Nsga2Params {
    fn name(&self) -> &'static str {
        "nsga2"
    }

    fn validate(&self) -> Result<(), (String, String)> {
        positive("population_size", self.population_size)?;
        positive("offspring_size", self.offspring_size)?;
        probability("mutation_probability", self.mutation_probability)?;
        check_operators(
            self.init_range,
            self.mutation_sigma,
            self.crossover_range,
            self.crossover_sigma,
        )
    }

    fn multi_objective(&self) -> bool {
        true
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Nsga2(Nsga2::new(
            Nsga2Config {
                population_size: self.population_size,
                offspring_size: self.offspring_size,
                mutation_probability: self.mutation_probability,
                senses: senses.to_vec(),
            },
            real_vector(
                dimension,
                self.init_range,
                self.mutation_sigma,
                self.crossover_range,
                self.crossover_sigma,
            ),
            seed,
        )?))
    }
}
