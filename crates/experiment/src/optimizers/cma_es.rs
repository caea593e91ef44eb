//! CMA-ES (thesis ch. 6).

use super::check::range;
use super::{decode, single, AnyOptimizer, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{CmaEs, CmaEsConfig, EvolutionError, Sense};

/// Parameters of CMA-ES.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CmaParams {
    /// λ (default 4 + ⌊3 ln n⌋).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub population_size: Option<usize>,
    /// σ0 (thesis ch. 6: 0.5).
    pub sigma0: f64,
    /// Initial mean uniform in [min, max).
    pub init_range: [f64; 2],
    /// Active covariance update (negative weights).
    pub active: bool,
}

impl Default for CmaParams {
    fn default() -> Self {
        Self {
            population_size: None,
            sigma0: 0.5,
            init_range: [-1.0, 1.0],
            active: true,
        }
    }
}

impl OptimizerKind for CmaParams {
    fn name(&self) -> &'static str {
        "cma-es"
    }

    fn validate(&self) -> Result<(), (String, String)> {
        if self.population_size == Some(0) || self.population_size == Some(1) {
            return Err(("population_size".into(), "must be at least 2".into()));
        }
        if !(self.sigma0.is_finite() && self.sigma0 > 0.0) {
            return Err(("sigma0".into(), format!("must be > 0, got {}", self.sigma0)));
        }
        range("init_range", self.init_range)
    }

    /// λ = 4 + ⌊3 ln n⌋ written out when not given.
    fn resolved(&self, _cells: usize, genes: Option<usize>) -> Option<OptimizerConfig> {
        let genes = genes?;
        Some(OptimizerConfig::CmaEs(CmaParams {
            population_size: Some(self.population_size.unwrap_or(CmaEs::default_population_size(genes))),
            ..self.clone()
        }))
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::CmaEs(CmaEs::new(
            CmaEsConfig {
                population_size: self.population_size,
                sigma0: self.sigma0,
                init_min: self.init_range[0],
                init_max: self.init_range[1],
                active: self.active,
                sense: single(senses),
            },
            dimension,
            seed,
        )?))
    }

    fn held_genotypes(&self, dimension: usize, _budget: Option<u64>) -> u128 {
        let lambda = self
            .population_size
            .unwrap_or(CmaEs::default_population_size(dimension));
        3 * lambda as u128 + 4
    }

    /// The covariance matrix, its eigenvectors and a work copy: 3·n².
    fn held_matrix_floats(&self, dimension: usize) -> u128 {
        3 * (dimension as u128) * (dimension as u128)
    }

    fn batch_size(&self, dimension: usize) -> usize {
        self.population_size
            .unwrap_or(CmaEs::default_population_size(dimension))
    }
}

/// The registry entry of `kind = "cma-es"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "cma-es",
    decode: |v| decode::<CmaParams>(v).map(OptimizerConfig::CmaEs),
};
