//! Real-vector genotypes with the operators of the thesis (§3.3.5.2) and of jgea.

use super::Representation;
use crate::error::EvolutionError;
use crate::optimizer::ensure;
use crate::rng::SeededRng;
use serde::{Deserialize, Serialize};

/// Unbounded real vectors of fixed length.
///
/// - Initialisation: each gene uniform in `[init_min, init_max)` (thesis: `[-1, 1]`).
/// - Mutation: every gene gets `+N(0, mutation_sigma²)` (thesis σ_mut = 0.35).
/// - Crossover: *extended geometric* ("hypercube") crossover: for each gene independently
///   `α ~ U[crossover_min, crossover_max)` and `child = p1 + α (p2 − p1)` (thesis `[-1, 2]`),
///   followed by Gaussian mutation with `crossover_sigma` (thesis σ′_mut = 0.1, to avoid
///   identical children of similar parents; 0 disables it, as in the GECCO'21 code).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RealVector {
    /// Number of genes.
    pub dimension: usize,
    /// Lower end of the initialisation range.
    pub init_min: f64,
    /// Upper end of the initialisation range.
    pub init_max: f64,
    /// Standard deviation of the Gaussian mutation.
    pub mutation_sigma: f64,
    /// Lower end of the per-gene crossover coefficient α.
    pub crossover_min: f64,
    /// Upper end of the per-gene crossover coefficient α.
    pub crossover_max: f64,
    /// Standard deviation of the Gaussian perturbation after crossover.
    pub crossover_sigma: f64,
}

impl RealVector {
    /// The thesis settings: init `U[-1, 1]`, σ = 0.35, α ∈ [−1, 2], σ′ = 0.1.
    pub fn thesis(dimension: usize) -> Self {
        Self {
            dimension,
            init_min: -1.0,
            init_max: 1.0,
            mutation_sigma: 0.35,
            crossover_min: -1.0,
            crossover_max: 2.0,
            crossover_sigma: 0.1,
        }
    }

    /// Sets the initialisation range.
    pub fn with_init_range(mut self, min: f64, max: f64) -> Self {
        self.init_min = min;
        self.init_max = max;
        self
    }

    /// Sets the mutation standard deviation.
    pub fn with_mutation_sigma(mut self, sigma: f64) -> Self {
        self.mutation_sigma = sigma;
        self
    }

    fn perturb(&self, genes: &mut [f64], sigma: f64, rng: &mut SeededRng) {
        if sigma > 0.0 {
            for g in genes {
                *g += sigma * rng.normal();
            }
        }
    }
}

impl Representation for RealVector {
    type Genotype = Vec<f64>;

    fn validate(&self) -> Result<(), EvolutionError> {
        ensure(self.dimension > 0, || "RealVector: dimension must be > 0".into())?;
        ensure(self.init_min <= self.init_max, || {
            format!("RealVector: init range [{}, {}] is empty", self.init_min, self.init_max)
        })?;
        ensure(self.mutation_sigma >= 0.0 && self.crossover_sigma >= 0.0, || {
            "RealVector: sigmas must be >= 0".into()
        })?;
        ensure(self.crossover_min <= self.crossover_max, || {
            "RealVector: crossover range is empty".into()
        })
    }

    fn random(&self, rng: &mut SeededRng) -> Vec<f64> {
        rng.uniform_vec(self.dimension, self.init_min, self.init_max)
    }

    fn mutate(&self, parent: &Vec<f64>, rng: &mut SeededRng) -> Vec<f64> {
        let mut child = parent.clone();
        self.perturb(&mut child, self.mutation_sigma, rng);
        child
    }

    fn crossover(&self, first: &Vec<f64>, second: &Vec<f64>, rng: &mut SeededRng) -> Vec<f64> {
        let mut child: Vec<f64> = first
            .iter()
            .zip(second)
            .map(|(&a, &b)| {
                let alpha = rng.uniform_in(self.crossover_min, self.crossover_max);
                a + alpha * (b - a)
            })
            .collect();
        self.perturb(&mut child, self.crossover_sigma, rng);
        child
    }

    /// Identical gene values (NSGA-II's optional duplicate elimination).
    fn is_duplicate(&self, a: &Vec<f64>, b: &Vec<f64>) -> bool {
        a == b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Stream;

    #[test]
    fn duplicates_are_identical_genes() {
        let rep = RealVector::thesis(2);
        assert!(rep.is_duplicate(&vec![0.5, -1.0], &vec![0.5, -1.0]));
        assert!(!rep.is_duplicate(&vec![0.5, -1.0], &vec![0.5, -1.000_000_1]));
    }

    #[test]
    fn crossover_spans_the_extended_segment_per_gene() {
        let rep = RealVector {
            crossover_sigma: 0.0,
            ..RealVector::thesis(1)
        };
        let mut rng = SeededRng::derive(3, 0, 0, Stream::Variation);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut distinct_alphas = false;
        for _ in 0..5000 {
            let c = rep.crossover(&vec![0.0], &vec![1.0], &mut rng)[0];
            lo = lo.min(c);
            hi = hi.max(c);
            let c2 = rep.crossover(&vec![0.0, 0.0], &vec![1.0, 1.0], &mut rng);
            distinct_alphas |= c2[0] != c2[1];
        }
        assert!((-1.0..-0.99).contains(&lo) && hi < 2.0 && hi > 1.99, "[{lo}, {hi}]");
        assert!(distinct_alphas, "alpha must be drawn per gene");
    }

    #[test]
    fn mutation_has_the_configured_sigma() {
        let rep = RealVector::thesis(20_000);
        let mut rng = SeededRng::derive(3, 0, 1, Stream::Variation);
        let child = rep.mutate(&vec![1.0; 20_000], &mut rng);
        let var = child.iter().map(|x| (x - 1.0).powi(2)).sum::<f64>() / 20_000.0;
        assert!((var.sqrt() - 0.35).abs() < 0.01, "sd {}", var.sqrt());
        let init = rep.random(&mut rng);
        assert!(init.iter().all(|x| (-1.0..1.0).contains(x)));
    }
}
