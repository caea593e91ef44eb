//! Canonical evolution strategy (Chrabaszcz, Loshchilov & Hutter 2018), the "ES" of the thesis
//! (§3.3.5.2, eq. 3.1–3.3).
//!
//! The search distribution is `N(m, σ² I)` with a fixed σ. Each generation λ children
//! `m + σ ε_i`, `ε_i ~ N(0, I)`, are evaluated; the μ best (μ = ⌊λ/4⌋ by default) move the mean:
//! `m ← m + σ Σ_{j=1..μ} w_j ε_(j)` with the log-rank weights
//! `w_j = (ln(μ + ½) − ln j) / Σ_{k=1..μ} (ln(μ + ½) − ln k)`.
//! No elitism: the mean is not re-evaluated and nothing survives.
//!
//! Discrepancies with the sources (implemented here: the textbook version):
//! - Thesis eq. 3.3 writes the weights with n_pop in place of μ and normalises over j = 1..n_pop.
//!   Those weights do not sum to 1 over the μ selected children; Chrabaszcz et al. use μ.
//! - The TELO code's weights are all zero (its normaliser contains ln 0 = −∞), so its mean never
//!   moved; its numerator also grows with rank (thesis-code-facts §2.5 and §8.1).
//! - The initial mean is uniform in `[init_min, init_max)` per gene (thesis: [−1, 1]).

use crate::error::EvolutionError;
use crate::optimizer::{ensure, Candidate, Individual, Optimizer, Sense, Tell, Told};
use crate::rng::{SeededRng, Stream};
use crate::search_state::SearchState;
use crate::selection::rank_best_first;
use serde::{Deserialize, Serialize};

/// The canonical ES's settings as a user writes them in an experiment's `[optimizer]` table (and
/// as checkpoints keep them). `Default` gives the thesis settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct EsSettings {
    /// λ: samples per generation (thesis text and code: 40; its Table 3.2 says 30).
    pub population_size: usize,
    /// μ: best samples that move the mean (`None`: the thesis' ⌊λ/4⌋, at least 1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parents: Option<usize>,
    /// Fixed mutation strength σ (thesis: 0.35).
    pub sigma: f64,
}

impl Default for EsSettings {
    fn default() -> Self {
        Self {
            population_size: 40,
            parents: None,
            sigma: 0.35,
        }
    }
}

impl EsSettings {
    /// μ: as given, else ⌊λ/4⌋ (at least 1).
    pub fn parents(&self) -> usize {
        self.parents.unwrap_or((self.population_size / 4).max(1))
    }
}

/// Parameters of [`CanonicalEs`]: its settings, the initial mean's range and the sense.
/// `Default` gives the thesis settings, the initial mean in [−1, 1], maximising.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CanonicalEsConfig {
    /// λ, μ and σ, written flat beside the rest.
    #[serde(flatten)]
    pub settings: EsSettings,
    /// Lower end of the uniform initial mean.
    pub init_min: f64,
    /// Upper end of the uniform initial mean.
    pub init_max: f64,
    /// Whether fitness is maximised or minimised.
    pub sense: Sense,
}

impl Default for CanonicalEsConfig {
    fn default() -> Self {
        Self {
            settings: EsSettings::default(),
            init_min: -1.0,
            init_max: 1.0,
            sense: Sense::Maximize,
        }
    }
}

/// The canonical ES over flat real vectors (see the module docs).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CanonicalEs {
    config: CanonicalEsConfig,
    #[serde(flatten)]
    state: SearchState<Vec<f64>>,
    mean: Vec<f64>,
    /// The last evaluated batch.
    last: Vec<Individual<Vec<f64>>>,
}

/// The log-rank weights of Chrabaszcz et al. for `mu` parents (they sum to 1).
pub fn log_rank_weights(mu: usize) -> Vec<f64> {
    let raw: Vec<f64> = (1..=mu).map(|j| (mu as f64 + 0.5).ln() - (j as f64).ln()).collect();
    let total: f64 = raw.iter().sum();
    raw.into_iter().map(|w| w / total).collect()
}

impl CanonicalEs {
    /// A new run in `dimension` dimensions with the given run seed.
    pub fn new(config: CanonicalEsConfig, dimension: usize, seed: u64) -> Result<Self, EvolutionError> {
        ensure(dimension > 0, || "ES: dimension must be > 0".into())?;
        ensure(
            config.settings.parents() >= 1 && config.settings.parents() <= config.settings.population_size,
            || {
                format!(
                    "ES: parents ({}) must be in 1..=population_size ({})",
                    config.settings.parents(),
                    config.settings.population_size
                )
            },
        )?;
        ensure(config.settings.sigma > 0.0, || "ES: sigma must be > 0".into())?;
        ensure(config.init_min <= config.init_max, || "ES: init range is empty".into())?;
        let mut rng = SeededRng::derive(seed, 0, 0, Stream::Initialisation);
        let mean = rng.uniform_vec(dimension, config.init_min, config.init_max);
        Ok(Self::with_mean(config, mean, seed))
    }

    /// A new run starting from a given mean (skips the random initialisation).
    pub fn with_mean(config: CanonicalEsConfig, mean: Vec<f64>, seed: u64) -> Self {
        Self {
            config,
            state: SearchState::new(seed),
            mean,
            last: Vec::new(),
        }
    }

    /// The current mean of the search distribution.
    pub fn mean(&self) -> &[f64] {
        &self.mean
    }

    /// The noise vector ε_i of sample `index` of the current generation.
    fn noise(&self, index: usize) -> Vec<f64> {
        self.state.rng(index, Stream::Sampling).normal_vec(self.mean.len())
    }
}

impl Optimizer for CanonicalEs {
    type Genotype = Vec<f64>;

    fn ask(&mut self) -> Vec<Candidate<Vec<f64>>> {
        if let Some(pending) = self.state.pending_batch() {
            return pending;
        }
        let sigma = self.config.settings.sigma;
        let genotypes: Vec<Vec<f64>> = (0..self.config.settings.population_size)
            .map(|i| {
                let eps = self.noise(i);
                self.mean.iter().zip(eps).map(|(m, e)| m + sigma * e).collect()
            })
            .collect();
        let n = genotypes.len();
        self.state.hand_out(genotypes, n)
    }

    fn search_state(&self) -> &SearchState<Vec<f64>> {
        &self.state
    }

    fn senses(&self) -> &[Sense] {
        std::slice::from_ref(&self.config.sense)
    }

    fn population(&self) -> Vec<&Individual<Vec<f64>>> {
        self.last.iter().collect()
    }
}

impl<O> Tell<O> for CanonicalEs {
    fn tell(&mut self, results: Vec<Told<O>>) -> Result<(), EvolutionError> {
        let (batch, evaluations) = self.state.take_told(results, 1)?;
        self.last = self
            .state
            .born_all(&batch, evaluations, std::slice::from_ref(&self.config.sense));
        let order = rank_best_first(&self.last, self.config.sense);
        let weights = log_rank_weights(self.config.settings.parents());
        let mut step = vec![0.0; self.mean.len()];
        for (&index, w) in order.iter().zip(&weights) {
            for (s, e) in step.iter_mut().zip(self.noise(index)) {
                *s += w * e;
            }
        }
        for (m, s) in self.mean.iter_mut().zip(step) {
            *m += self.config.settings.sigma * s;
        }
        self.state.advance(&batch);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::run::{run_to_budget, Stop};
    use crate::test_functions::{rastrigin, rosenbrock, sphere};
    use crate::Evaluation;

    fn run(f: fn(&[f64]) -> f64, sigma: f64, init: f64, seed: u64, evaluations: u64) -> (f64, f64) {
        let config = CanonicalEsConfig {
            settings: EsSettings {
                sigma,
                ..EsSettings::default()
            },
            init_min: -init,
            init_max: init,
            sense: Sense::Minimize,
        };
        let mut es = CanonicalEs::new(config, 10, seed).unwrap();
        run_to_budget(
            &mut es,
            |c| Evaluation::single(f(&c.genotype)),
            &Stop::evaluations(evaluations),
        )
        .unwrap();
        (f(es.mean()), es.best().unwrap().fitness())
    }

    #[test]
    fn weights_are_chrabaszcz_log_rank() {
        let w = log_rank_weights(10);
        assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        assert!(w.windows(2).all(|p| p[0] > p[1] && p[1] > 0.0));
        let expected_first = 10.5f64.ln() / (1..=10).map(|k| 10.5f64.ln() - (k as f64).ln()).sum::<f64>();
        assert!((w[0] - expected_first).abs() < 1e-15);
    }

    /// With a fixed σ the mean converges to a noise floor around the optimum. On the sphere,
    /// progress-rate theory (Beyer 2001) puts the stationary distance at R ≈ σ n / σ*₀ with
    /// σ*₀ ≈ 2 μ_eff c_{μ/μ,λ} ≈ 14 for λ = 40, μ = 10, i.e. f(mean) ≈ 0.06 for σ = 0.35 and
    /// ≈ 5e-5 for σ = 0.01 in 10-D; measured over 5 seeds: 0.07–0.27 and 5e-5–1.2e-4.
    /// Thresholds: 0.5 and 5e-4 (the floor must be reached; it scales with σ²). Rastrigin
    /// (σ = 0.35, 20 000 evaluations): the best sample must beat the best of 20 000 random
    /// points (≈ 63–72) by far: < 35 (measured 17–25). Rosenbrock (σ = 0.1, 40 000 evaluations,
    /// from [−2, 2]^10 where random search's best of 20 000 is ≈ 124–207): f(mean) < 12
    /// (measured 5.4–7.9).
    #[test]
    fn converges_on_benchmarks() {
        for seed in 0..3 {
            let (m, _) = run(sphere, 0.35, 5.12, seed, 8_000);
            assert!(m < 0.5, "sphere sigma 0.35 seed {seed}: {m}");
            let (m, _) = run(sphere, 0.01, 1.0, seed, 20_000);
            assert!(m < 5e-4, "sphere sigma 0.01 seed {seed}: {m}");
            let (m, b) = run(rastrigin, 0.35, 5.12, seed, 20_000);
            assert!(b < 35.0, "rastrigin seed {seed}: mean {m}, best {b}");
            let (m, _) = run(rosenbrock, 0.1, 2.0, seed, 40_000);
            assert!(m < 12.0, "rosenbrock seed {seed}: {m}");
        }
    }
}
