//! The μ + λ genetic algorithm of the thesis (§3.3.5.2).

use super::check::{positive, probability};
use super::{check_operators, real_vector, single, AnyOptimizer, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, GaConfig, GeneticAlgorithm, Sense};

/// Parameters of the GA.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GaParams {
    /// μ (thesis 100).
    pub population_size: usize,
    /// λ (thesis 100).
    pub offspring_size: usize,
    /// Tournament size (thesis 5).
    pub tournament_size: usize,
    /// p_mut: mutation instead of crossover (thesis 0.2).
    pub mutation_probability: f64,
    /// Re-evaluate survivors every generation (noisy tasks).
    pub reevaluate_survivors: bool,
    /// Initial genes uniform in [min, max) (thesis [−1, 1]).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation (thesis 0.35).
    pub mutation_sigma: f64,
    /// Per-gene α range of the extended geometric crossover (thesis [−1, 2]).
    pub crossover_range: [f64; 2],
    /// σ′ of the Gaussian perturbation after crossover (thesis 0.1).
    pub crossover_sigma: f64,
}

impl Default for GaParams {
    fn default() -> Self {
        Self {
            population_size: 100,
            offspring_size: 100,
            tournament_size: 5,
            mutation_probability: 0.2,
            reevaluate_survivors: false,
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
            crossover_range: [-1.0, 2.0],
            crossover_sigma: 0.1,
        }
    }
}

impl OptimizerKind for GaParams {
    fn name(&self) -> &'static str {
        "ga"
    }

    fn validate(&self) -> Result<(), (String, String)> {
        positive("population_size", self.population_size)?;
        positive("offspring_size", self.offspring_size)?;
        positive("tournament_size", self.tournament_size)?;
        probability("mutation_probability", self.mutation_probability)?;
        check_operators(
            self.init_range,
            self.mutation_sigma,
            self.crossover_range,
            self.crossover_sigma,
        )
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Ga(GeneticAlgorithm::new(
            GaConfig {
                population_size: self.population_size,
                offspring_size: self.offspring_size,
                tournament_size: self.tournament_size,
                mutation_probability: self.mutation_probability,
                reevaluate_survivors: self.reevaluate_survivors,
                sense: single(senses),
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
