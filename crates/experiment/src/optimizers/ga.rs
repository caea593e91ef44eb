//! The μ + λ genetic algorithm of the thesis (§3.3.5.2).

use super::check::{positive, probability};
use super::{
    decode_flat, single, AnyOptimizer, OperatorPlan, Operators, OptimizerConfig, OptimizerEntry, OptimizerKind,
};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, GaConfig, GaSettings, GeneticAlgorithm, Sense};
use vsrlab_field::FieldError;

/// Parameters of the GA: its settings ([`GaSettings`], declared once, in the optimizer's crate)
/// and the real-vector operators', both written flat in the `[optimizer]` table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct GaParams {
    /// μ, λ, tournament size, p_mut and re-evaluation (thesis 100, 100, 5, 0.2, off).
    #[serde(flatten)]
    pub ga: GaSettings,
    /// The operators' parameters (`init_range`, `mutation_sigma`, `crossover_range`,
    /// `crossover_sigma`), written flat in the table.
    #[serde(flatten)]
    pub operators: Operators,
}

impl GaParams {
    /// The GA's settings for objectives of these senses (several: compared lexicographically).
    fn config(&self, senses: &[Sense]) -> GaConfig {
        GaConfig {
            settings: self.ga.clone(),
            sense: single(senses),
            ties: senses.iter().skip(1).copied().collect(),
        }
    }
}

impl OptimizerKind for GaParams {
    fn name(&self) -> &'static str {
        "ga"
    }

    fn lexicographic(&self) -> bool {
        true
    }

    fn validate(&self) -> Result<(), FieldError> {
        let ga = &self.ga;
        positive("population_size", ga.population_size)?;
        positive("offspring_size", ga.offspring_size)?;
        positive("tournament_size", ga.tournament_size)?;
        probability("mutation_probability", ga.mutation_probability)?;
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
        self.ga.population_size as u128 + 2 * self.ga.offspring_size as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        // re-evaluated survivors are evaluated in the same batch as the children
        self.ga.offspring_size
            + if self.ga.reevaluate_survivors {
                self.ga.population_size
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
