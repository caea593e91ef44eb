//! The speciated evolver of the thesis (SE-g / SE-s / SE-b, §3.3.5.2).

use super::check::{positive, probability};
use super::{
    decode_flat, single, AnyOptimizer, Extract, Operators, OptimizerConfig, OptimizerEntry, OptimizerKind,
    SpeciationFeatures,
};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, SeConfig, SeSettings, Sense, SpeciatedEvolver};
use vsrlab_field::FieldError;

/// What the speciated evolver clusters on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SeFeatures {
    /// SE-g: the genotype.
    #[default]
    Genotype,
    /// SE-s: the 16×16 dynamic pose (256 values).
    Shape,
    /// SE-b: the centre-of-mass |Δy| spectrum (100 values).
    Behaviour,
}

/// Parameters of the speciated evolver: the speciation features, its settings ([`SeSettings`],
/// declared once, in the optimizer's crate) and the real-vector operators', written flat in the
/// table.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct SeParams {
    /// Speciation features: `genotype` (SE-g), `shape` (SE-s), `behaviour` (SE-b).
    pub features: SeFeatures,
    /// n_pop, k, α, n_elite, p_mut and k-means iterations (thesis 100, 10, 0.75, 5, 0.2, 200).
    #[serde(flatten)]
    pub se: SeSettings,
    /// The operators' parameters (`init_range`, `mutation_sigma`, `crossover_range`,
    /// `crossover_sigma`), written flat in the table.
    #[serde(flatten)]
    pub operators: Operators,
}

impl OptimizerKind for SeParams {
    fn name(&self) -> &'static str {
        "se"
    }

    fn validate(&self) -> Result<(), FieldError> {
        let se = &self.se;
        positive("population_size", se.population_size)?;
        positive("species", se.species)?;
        if se.species > se.population_size {
            return Err(FieldError::new(
                "species",
                format!(
                    "{} species cannot be made of a population of {}: at most population_size",
                    se.species, se.population_size
                ),
            ));
        }
        if !(se.rank_base > 0.0 && se.rank_base <= 1.0) {
            return Err(FieldError::new(
                "alpha",
                format!("must be in (0, 1], got {}", se.rank_base),
            ));
        }
        probability("mutation_probability", se.mutation_probability)?;
        self.operators.validate()
    }

    fn extract(&self) -> Extract {
        match self.features {
            SeFeatures::Genotype => Extract::Nothing,
            SeFeatures::Shape => Extract::Pose,
            SeFeatures::Behaviour => Extract::Spectrum,
        }
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Se(SpeciatedEvolver::new(
            SeConfig {
                settings: self.se.clone(),
                sense: single(senses),
            },
            self.operators.real_vector(dimension),
            match self.features {
                SeFeatures::Genotype => SpeciationFeatures::Genotype,
                SeFeatures::Shape | SeFeatures::Behaviour => SpeciationFeatures::Outcome,
            },
            seed,
        )?))
    }

    fn held_genotypes(&self, _dimension: usize, _budget: Option<u64>) -> u128 {
        3 * self.se.population_size as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.se.population_size
    }
}

/// The registry entry of `kind = "se"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "se",
    decode: |v| decode_flat::<SeParams>(v).map(OptimizerConfig::Se),
};
