//! The canonical evolution strategy of the thesis (§3.3.5.2).

use super::check::{positive, range};
use super::{decode, single, AnyOptimizer, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{CanonicalEs, CanonicalEsConfig, EvolutionError, Sense};
use vsrlab_field::FieldError;

/// Parameters of the canonical ES.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EsParams {
    /// λ, samples per generation (thesis text and code 40; Table 3.2 says 30).
    pub population_size: usize,
    /// μ, best samples moving the mean (default ⌊λ/4⌋).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parents: Option<usize>,
    /// Fixed σ (thesis 0.35).
    pub sigma: f64,
    /// Initial mean uniform in [min, max) (thesis [−1, 1]).
    pub init_range: [f64; 2],
}

impl Default for EsParams {
    fn default() -> Self {
        Self {
            population_size: 40,
            parents: None,
            sigma: 0.35,
            init_range: [-1.0, 1.0],
        }
    }
}

impl OptimizerKind for EsParams {
    fn name(&self) -> &'static str {
        "es"
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("population_size", self.population_size)?;
        let parents = self.parents.unwrap_or(1);
        if parents == 0 || parents > self.population_size {
            return Err(FieldError::new(
                "parents",
                format!("must be in 1..=population_size, got {parents}"),
            ));
        }
        if !(self.sigma.is_finite() && self.sigma > 0.0) {
            return Err(FieldError::new("sigma", format!("must be > 0, got {}", self.sigma)));
        }
        range("init_range", self.init_range)
    }

    /// μ defaults to ⌊λ/4⌋.
    fn resolved(&self, _cells: usize, _genes: Option<usize>) -> Option<OptimizerConfig> {
        let parents = Some(self.parents.unwrap_or((self.population_size / 4).max(1)));
        Some(OptimizerConfig::Es(EsParams {
            parents,
            ..self.clone()
        }))
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Es(CanonicalEs::new(
            CanonicalEsConfig {
                population_size: self.population_size,
                parents: self.parents.unwrap_or((self.population_size / 4).max(1)),
                sigma: self.sigma,
                init_min: self.init_range[0],
                init_max: self.init_range[1],
                sense: single(senses),
            },
            dimension,
            seed,
        )?))
    }

    fn held_genotypes(&self, _dimension: usize, _budget: Option<u64>) -> u128 {
        3 * self.population_size as u128 + 1
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.population_size
    }
}

/// The registry entry of `kind = "es"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "es",
    decode: |v| decode::<EsParams>(v).map(OptimizerConfig::Es),
};
