//! The speciated evolver of the thesis (SE-g / SE-s / SE-b, §3.3.5.2).

use super::check::{positive, probability};
use super::{
    decode_flat, single, AnyOptimizer, Extract, Operators, OptimizerConfig, OptimizerEntry, OptimizerKind,
    SpeciationFeatures,
};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, SeConfig, Sense, SpeciatedEvolver};
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

/// Parameters of the speciated evolver.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct SeParams {
    /// Speciation features: `genotype` (SE-g), `shape` (SE-s), `behaviour` (SE-b).
    pub features: SeFeatures,
    /// n_pop (thesis 100).
    pub population_size: usize,
    /// k of k-means (thesis 10).
    pub species: usize,
    /// α, species preference (thesis 0.75).
    pub alpha: f64,
    /// n_elite, minimum species size whose best survives (thesis 5).
    pub elite_min_species_size: usize,
    /// p_mut (thesis 0.2).
    pub mutation_probability: f64,
    /// Maximum Lloyd iterations of k-means.
    pub kmeans_iterations: usize,
    /// The operators' parameters (`init_range`, `mutation_sigma`, `crossover_range`,
    /// `crossover_sigma`), written flat in the table.
    #[serde(flatten)]
    pub operators: Operators,
}

impl Default for SeParams {
    fn default() -> Self {
        Self {
            features: SeFeatures::Genotype,
            population_size: 100,
            species: 10,
            alpha: 0.75,
            elite_min_species_size: 5,
            mutation_probability: 0.2,
            kmeans_iterations: 200,
            operators: Operators::default(),
        }
    }
}

impl OptimizerKind for SeParams {
    fn name(&self) -> &'static str {
        "se"
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("population_size", self.population_size)?;
        positive("species", self.species)?;
        if self.species > self.population_size {
            return Err(FieldError::new(
                "species",
                format!(
                    "{} species cannot be made of a population of {}: at most population_size",
                    self.species, self.population_size
                ),
            ));
        }
        if !(self.alpha > 0.0 && self.alpha <= 1.0) {
            return Err(FieldError::new(
                "alpha",
                format!("must be in (0, 1], got {}", self.alpha),
            ));
        }
        probability("mutation_probability", self.mutation_probability)?;
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
                population_size: self.population_size,
                species: self.species,
                rank_base: self.alpha,
                min_species_size_for_elitism: self.elite_min_species_size,
                mutation_probability: self.mutation_probability,
                kmeans_iterations: self.kmeans_iterations,
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
        3 * self.population_size as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.population_size
    }
}

/// The registry entry of `kind = "se"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "se",
    decode: |v| decode_flat::<SeParams>(v).map(OptimizerConfig::Se),
};
