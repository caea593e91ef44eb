//! NSGA-II (thesis ch. 5.1), multi-objective, with the thesis' real-vector operators.
//!
//! Defaults: N = 100, 100 children per generation, Gaussian mutation (σ = 0.35) for a child with
//! probability `mutation_probability` (0.2), else extended geometric crossover then σ′ = 0.1.
//! The thesis' affordance runs used mutation only and N/2 children: `mutation_probability = 1`,
//! `offspring_size = 50`.

use super::check::{positive, probability};
use super::{decode_flat, AnyOptimizer, OperatorPlan, Operators, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, Nsga2, Nsga2Config, Nsga2Settings, Sense};
use vsrlab_field::FieldError;

/// Parameters of NSGA-II: its settings ([`Nsga2Settings`], declared once, in the optimizer's
/// crate), duplicate elimination and the real-vector operators', written flat in the table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct Nsga2Params {
    /// N, children per generation and p_mut (defaults 100, 100, 0.2).
    #[serde(flatten)]
    pub nsga2: Nsga2Settings,
    /// Redraw children whose genes equal a population member's or an earlier child's (pymoo's
    /// `eliminate_duplicates`; default false, as Deb et al.).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub eliminate_duplicates: bool,
    /// The operators' parameters (`init_range`, `mutation_sigma`, `crossover_range`,
    /// `crossover_sigma`), written flat in the table.
    #[serde(flatten)]
    pub operators: Operators,
}

impl Nsga2Params {
    /// NSGA-II's settings for objectives of these senses.
    fn config(&self, senses: &[Sense]) -> Nsga2Config {
        Nsga2Config {
            settings: self.nsga2.clone(),
            senses: senses.to_vec(),
        }
    }
}

impl OptimizerKind for Nsga2Params {
    fn name(&self) -> &'static str {
        "nsga2"
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("population_size", self.nsga2.population_size)?;
        positive("offspring_size", self.nsga2.offspring_size)?;
        probability("mutation_probability", self.nsga2.mutation_probability)?;
        self.operators.validate()
    }

    fn multi_objective(&self) -> bool {
        true
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Nsga2(
            Nsga2::new(self.config(senses), self.operators.real_vector(dimension), seed)?
                .with_duplicate_elimination(self.eliminate_duplicates),
        ))
    }

    fn over_operators(&self, senses: &[Sense]) -> Option<OperatorPlan> {
        Some(OperatorPlan::Nsga2(self.config(senses), self.eliminate_duplicates))
    }

    fn held_genotypes(&self, _dimension: usize, _budget: Option<u64>) -> u128 {
        self.nsga2.population_size as u128 + 2 * self.nsga2.offspring_size as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.nsga2.offspring_size
    }
}

/// The registry entry of `kind = "nsga2"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "nsga2",
    decode: |v| decode_flat::<Nsga2Params>(v).map(OptimizerConfig::Nsga2),
};
