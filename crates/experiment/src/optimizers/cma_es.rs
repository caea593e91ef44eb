//! CMA-ES (thesis ch. 6).

use super::check::range;
use super::{decode, single, AnyOptimizer, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{CmaEs, CmaEsConfig, CmaTermination, EvolutionError, RestartStrategy, Sense};
use vsrlab_field::FieldError;

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
    /// Termination criteria on (`false`: the run ends only by its `[stop]` budget).
    pub termination: bool,
    /// pycma `tolx`: σ·√C_ii and σ·|p_c,i| below this in every coordinate (default 1e-11).
    pub tolx: f64,
    /// pycma `tolfun`: current and recent best fitness ranges below this (default 1e-11).
    pub tolfun: f64,
    /// pycma `tolfunhist`: recent best fitness range below this (default 1e-12).
    pub tolfunhist: f64,
    /// pycma `tolconditioncov`: condition number of C above this (default 1e14).
    pub tolconditioncov: f64,
    /// pycma `tolfacupx`: σ·√C_ii above σ0 times this (default 1e3).
    pub tolfacupx: f64,
    /// pycma `tolupsigma`: σ/σ0 above this times √(largest eigenvalue of C) (default 1e20).
    pub tolupsigma: f64,
    /// pycma `tolstagnation` in generations (default ⌊100 + 100·n^1.5/λ⌋; 0 = off).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolstagnation: Option<u64>,
    /// pycma `tolxstagnation`: the mean moved less than this over 20 + 0.1·g generations
    /// (default 1e-9).
    pub tolxstagnation: f64,
    /// Tutorial `NoEffectAxis` (default on).
    pub noeffectaxis: bool,
    /// Tutorial `NoEffectCoord` (default on).
    pub noeffectcoord: bool,
    /// IPOP restarts after a termination criterion holds (default 0: none); needs `termination`.
    #[serde(skip_serializing_if = "is_zero")]
    pub restarts: usize,
    /// λ's factor at each restart (default 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restart_increase: Option<f64>,
    /// `"ipop"` (default) or `"bipop"` (large and small populations in turn).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restart_strategy: Option<RestartStrategy>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Default for CmaParams {
    fn default() -> Self {
        let t = CmaTermination::default();
        Self {
            population_size: None,
            sigma0: 0.5,
            init_range: [-1.0, 1.0],
            active: true,
            termination: t.enabled,
            tolx: t.tolx,
            tolfun: t.tolfun,
            tolfunhist: t.tolfunhist,
            tolconditioncov: t.tolconditioncov,
            tolfacupx: t.tolfacupx,
            tolupsigma: t.tolupsigma,
            tolstagnation: t.tolstagnation,
            tolxstagnation: t.tolxstagnation,
            noeffectaxis: t.noeffectaxis,
            noeffectcoord: t.noeffectcoord,
            restarts: 0,
            restart_increase: None,
            restart_strategy: None,
        }
    }
}

impl CmaParams {
    /// λ's factor at each restart.
    fn increase(&self) -> f64 {
        self.restart_increase.unwrap_or(2.0)
    }

    /// The largest λ of a run: after every restart.
    fn largest_lambda(&self, dimension: usize) -> usize {
        let lambda = self
            .population_size
            .unwrap_or(CmaEs::default_population_size(dimension)) as f64;
        (lambda * self.increase().powi(self.restarts.min(64) as i32)).min(1e9) as usize
    }

    /// The termination criteria these parameters describe.
    fn termination_criteria(&self) -> CmaTermination {
        CmaTermination {
            enabled: self.termination,
            tolx: self.tolx,
            tolfun: self.tolfun,
            tolfunhist: self.tolfunhist,
            tolconditioncov: self.tolconditioncov,
            tolfacupx: self.tolfacupx,
            tolupsigma: self.tolupsigma,
            tolstagnation: self.tolstagnation,
            tolxstagnation: self.tolxstagnation,
            noeffectaxis: self.noeffectaxis,
            noeffectcoord: self.noeffectcoord,
        }
    }
}

impl OptimizerKind for CmaParams {
    fn name(&self) -> &'static str {
        "cma-es"
    }

    fn validate(&self) -> Result<(), FieldError> {
        if self.population_size == Some(0) || self.population_size == Some(1) {
            return Err(FieldError::new("population_size", "must be at least 2"));
        }
        if !(self.sigma0.is_finite() && self.sigma0 > 0.0) {
            return Err(FieldError::new("sigma0", format!("must be > 0, got {}", self.sigma0)));
        }
        range("init_range", self.init_range)?;
        if !(self.increase().is_finite() && self.increase() >= 1.0) {
            return Err(FieldError::new(
                "restart_increase",
                format!("must be ≥ 1, got {}", self.increase()),
            ));
        }
        if self.restarts > 0 && !self.termination {
            return Err(FieldError::new(
                "restarts",
                "restarts follow the termination criteria: set termination = true",
            ));
        }
        self.termination_criteria()
            .validate()
            .map_err(|(field, why)| FieldError::new(field, why))
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
                termination: self.termination_criteria(),
                restarts: self.restarts,
                restart_increase: self.increase(),
                restart_strategy: self.restart_strategy.unwrap_or_default(),
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
        self.population_size
            .unwrap_or(CmaEs::default_population_size(dimension))
    }
}

/// The registry entry of `kind = "cma-es"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "cma-es",
    decode: |v| decode::<CmaParams>(v).map(OptimizerConfig::CmaEs),
};
