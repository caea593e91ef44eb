//! CMA-ES (thesis ch. 6).

use super::check::range;
use super::{decode_flat, single, AnyOptimizer, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{CmaEs, CmaEsConfig, CmaSettings, CmaTermination, EvolutionError, Sense};
use vsrlab_field::FieldError;

/// Parameters of CMA-ES: its settings ([`CmaSettings`]) and termination criteria
/// ([`CmaTermination`]: the switch `termination` and pycma's `tol*` thresholds), both declared
/// once, in the optimizer's crate, and the initial mean's range, written flat in the table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct CmaParams {
    /// λ (default 4 + ⌊3 ln n⌋), σ0 (thesis ch. 6: 0.5), the active update (default on) and IPOP
    /// or BIPOP restarts (default none; they need `termination`).
    #[serde(flatten)]
    pub cma: CmaSettings,
    /// Initial mean uniform in [min, max).
    pub init_range: [f64; 2],
    /// The termination criteria (default on, pycma's thresholds; `termination = false`: the run
    /// ends only by its `[stop]` budget).
    #[serde(flatten)]
    pub termination: CmaTermination,
}

impl Default for CmaParams {
    fn default() -> Self {
        Self {
            cma: CmaSettings::default(),
            init_range: [-1.0, 1.0],
            termination: CmaTermination::default(),
        }
    }
}

impl CmaParams {
    /// The largest λ of a run: after every restart.
    fn largest_lambda(&self, dimension: usize) -> usize {
        let lambda = self
            .cma
            .population_size
            .unwrap_or(CmaEs::default_population_size(dimension)) as f64;
        (lambda * self.cma.restart_increase.powi(self.cma.restarts.min(64) as i32)).min(1e9) as usize
    }
}

impl OptimizerKind for CmaParams {
    fn name(&self) -> &'static str {
        "cma-es"
    }

    fn validate(&self) -> Result<(), FieldError> {
        let cma = &self.cma;
        if cma.population_size == Some(0) || cma.population_size == Some(1) {
            return Err(FieldError::new("population_size", "must be at least 2"));
        }
        if !(cma.sigma0.is_finite() && cma.sigma0 > 0.0) {
            return Err(FieldError::new("sigma0", format!("must be > 0, got {}", cma.sigma0)));
        }
        range("init_range", self.init_range)?;
        if !(cma.restart_increase.is_finite() && cma.restart_increase >= 1.0) {
            return Err(FieldError::new(
                "restart_increase",
                format!("must be ≥ 1, got {}", cma.restart_increase),
            ));
        }
        if let Some(gap) = cma.updatecovwait.filter(|g| !(g.is_finite() && *g >= 0.0)) {
            return Err(FieldError::new(
                "updatecovwait",
                format!("must be a number of generations ≥ 0, got {gap}"),
            ));
        }
        if cma.restarts > 0 && !self.termination.enabled {
            return Err(FieldError::new(
                "restarts",
                "restarts follow the termination criteria: set termination = true",
            ));
        }
        self.termination
            .validate()
            .map_err(|(field, why)| FieldError::new(field, why))
    }

    /// λ = 4 + ⌊3 ln n⌋ written out when not given.
    fn resolved(&self, _cells: usize, genes: Option<usize>) -> Option<OptimizerConfig> {
        let genes = genes?;
        let mut resolved = self.clone();
        resolved.cma.population_size = Some(
            self.cma
                .population_size
                .unwrap_or(CmaEs::default_population_size(genes)),
        );
        Some(OptimizerConfig::CmaEs(resolved))
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::CmaEs(CmaEs::new(
            CmaEsConfig {
                settings: self.cma.clone(),
                init_min: self.init_range[0],
                init_max: self.init_range[1],
                sense: single(senses),
                termination: self.termination.clone(),
            },
            dimension,
            seed,
        )?))
    }

    fn held_genotypes(&self, dimension: usize, _budget: Option<u64>) -> u128 {
        3 * self.largest_lambda(dimension) as u128 + 4
    }

    /// The covariance matrix, its eigenvectors and a work copy: 3·n².
    fn held_matrix_floats(&self, dimension: usize) -> u128 {
        3 * (dimension as u128) * (dimension as u128)
    }

    fn batch_size(&self, dimension: usize) -> usize {
        self.cma
            .population_size
            .unwrap_or(CmaEs::default_population_size(dimension))
    }
}

/// The registry entry of `kind = "cma-es"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "cma-es",
    decode: |v| decode_flat::<CmaParams>(v).map(OptimizerConfig::CmaEs),
};
