//! The canonical evolution strategy of the thesis (§3.3.5.2).

use super::check::{positive, range};
use super::{decode_flat, single, AnyOptimizer, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{CanonicalEs, CanonicalEsConfig, EsSettings, EvolutionError, Sense};
use vsrlab_field::FieldError;

/// Parameters of the canonical ES: its settings ([`EsSettings`], declared once, in the
/// optimizer's crate) and the initial mean's range, written flat in the table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct EsParams {
    /// λ, μ and σ (thesis 40, ⌊λ/4⌋, 0.35).
    #[serde(flatten)]
    pub es: EsSettings,
    /// Initial mean uniform in [min, max) (thesis [−1, 1]).
    pub init_range: [f64; 2],
}

impl Default for EsParams {
    fn default() -> Self {
        Self {
            es: EsSettings::default(),
            init_range: [-1.0, 1.0],
        }
    }
}

impl OptimizerKind for EsParams {
    fn name(&self) -> &'static str {
        "es"
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("population_size", self.es.population_size)?;
        let parents = self.es.parents.unwrap_or(1);
        if parents == 0 || parents > self.es.population_size {
            return Err(FieldError::new(
                "parents",
                format!("must be in 1..=population_size, got {parents}"),
            ));
        }
        if !(self.es.sigma.is_finite() && self.es.sigma > 0.0) {
            return Err(FieldError::new("sigma", format!("must be > 0, got {}", self.es.sigma)));
        }
        range("init_range", self.init_range)
    }

    /// μ defaults to ⌊λ/4⌋.
    fn resolved(&self, _cells: usize, _genes: Option<usize>) -> Option<OptimizerConfig> {
        let mut resolved = self.clone();
        resolved.es.parents = Some(self.es.parents());
        Some(OptimizerConfig::Es(resolved))
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::Es(CanonicalEs::new(
            CanonicalEsConfig {
                settings: EsSettings {
                    parents: Some(self.es.parents()),
                    ..self.es.clone()
                },
                init_min: self.init_range[0],
                init_max: self.init_range[1],
                sense: single(senses),
            },
            dimension,
            seed,
        )?))
    }

    fn held_genotypes(&self, _dimension: usize, _budget: Option<u64>) -> u128 {
        3 * self.es.population_size as u128 + 1
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.es.population_size
    }
}

/// The registry entry of `kind = "es"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "es",
    decode: |v| decode_flat::<EsParams>(v).map(OptimizerConfig::Es),
};
