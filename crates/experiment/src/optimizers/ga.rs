//! The μ + λ genetic algorithm of the thesis (§3.3.5.2).

use super::check::{positive, probability};
use super::{
    decode_flat, single, AnyOptimizer, OperatorPlan, Operators, OptimizerConfig, OptimizerEntry, OptimizerKind,
};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, GaConfig, GeneticAlgorithm, Sense};
use vsrlab_field::FieldError;

/// Parameters of the GA.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
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
    /// The operators' parameters (`init_range`, `mutation_sigma`, `crossover_range`,
    /// `crossover_sigma`), written flat in the table.
    #[serde(flatten)]
    pub operators: Operators,
}

impl Default for GaParams {
    /// The thesis settings, as the optimizer's own defaults ([`GaConfig::default`]).
    fn default() -> Self {
        let ga = GaConfig::default();
        Self {
            population_size: ga.population_size,
            offspring_size: ga.offspring_size,
            tournament_size: ga.tournament_size,
            mutation_probability: ga.mutation_probability,
            reevaluate_survivors: ga.reevaluate_survivors,
            operators: Operators::default(),
        }
    }
}

impl GaParams {
    /// The GA's settings for an objective of this sense.
    fn config(&self, senses: &[Sense]) -> GaConfig {
        GaConfig {
            population_size: self.population_size,
            offspring_size: self.offspring_size,
            tournament_size: self.tournament_size,
            mutation_probability: self.mutation_probability,
            reevaluate_survivors: self.reevaluate_survivors,
            sense: single(senses),
        }
    }
}

impl OptimizerKind for GaParams {
    fn name(&self) -> &'static str {
        "ga"
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("population_size", self.population_size)?;
        positive("offspring_size", self.offspring_size)?;
        positive("tournament_size", self.tournament_size)?;
        probability("mutation_probability", self.mutation_probability)?;
        self.operators.validate()
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Ga(GeneticAlgorithm::new(
            self.config(senses),
            self.operators.real_vector(dimension),
            seed,
        )?))
    }

    fn over_operators(&self, senses: &[Sense]) -> Option<OperatorPlan> {
        Some(OperatorPlan::Ga(self.config(senses)))
    }

    fn held_genotypes(&self, _dimension: usize, _budget: Option<u64>) -> u128 {
        self.population_size as u128 + 2 * self.offspring_size as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        // re-evaluated survivors are evaluated in the same batch as the children
        self.offspring_size
            + if self.reevaluate_survivors {
                self.population_size
            } else {
                0
            }
    }
}

/// The registry entry of `kind = "ga"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "ga",
    decode: |v| decode_flat::<GaParams>(v).map(OptimizerConfig::Ga),
};
