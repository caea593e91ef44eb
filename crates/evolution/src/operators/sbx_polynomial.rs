//! Bounded real vectors with simulated binary crossover (SBX) and polynomial mutation
//! (Deb & Agrawal 1995; Deb 2001), the variation operators of NSGA-II (Deb et al. 2002).

use super::Representation;
use crate::error::EvolutionError;
use crate::optimizer::ensure;
use crate::rng::SeededRng;
use serde::{Deserialize, Serialize};

/// Real vectors in the box `[lower, upper]^dimension`.
///
/// - Initialisation: uniform in the box.
/// - Crossover: with probability `crossover_probability`, bounded SBX with distribution index
///   `eta_crossover`, each gene crossed with probability 0.5; SBX makes a pair of children and
///   this operator returns one of the two values per crossed gene at random (genes not crossed
///   are copied from the first parent). The child is then mutated as below.
/// - Mutation: each gene with probability `mutation_probability` (default `1/dimension`) gets
///   the bounded polynomial perturbation with distribution index `eta_mutation`.
///
/// Defaults (`SbxPolynomial::new`) follow Deb et al. 2002 and pymoo: p_c = 0.9, η_c = 15,
/// η_m = 20, p_m = 1/n.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SbxPolynomial {
    /// Number of genes.
    pub dimension: usize,
    /// Lower bound of every gene.
    pub lower: f64,
    /// Upper bound of every gene.
    pub upper: f64,
    /// Probability that a crossover recombines at all (else the child copies the first parent).
    pub crossover_probability: f64,
    /// SBX distribution index η_c (larger = children closer to the parents).
    pub eta_crossover: f64,
    /// Per-gene probability of polynomial mutation.
    pub mutation_probability: f64,
    /// Polynomial mutation distribution index η_m.
    pub eta_mutation: f64,
}

impl SbxPolynomial {
    /// Default operators for the box `[lower, upper]^dimension`.
    pub fn new(dimension: usize, lower: f64, upper: f64) -> Self {
        Self {
            dimension,
            lower,
            upper,
            crossover_probability: 0.9,
            eta_crossover: 15.0,
            mutation_probability: 1.0 / dimension.max(1) as f64,
            eta_mutation: 20.0,
        }
    }

    /// Bounded SBX on one gene pair; returns the two children values.
    fn sbx_gene(&self, a: f64, b: f64, u: f64) -> (f64, f64) {
        let (y1, y2) = if a < b { (a, b) } else { (b, a) };
        let span = y2 - y1;
        let exponent = 1.0 / (self.eta_crossover + 1.0);
        let spread = |beta: f64| {
            let alpha = 2.0 - beta.powf(-(self.eta_crossover + 1.0));
            if u <= 1.0 / alpha {
                (u * alpha).powf(exponent)
            } else {
                (1.0 / (2.0 - u * alpha)).powf(exponent)
            }
        };
        let beta_low = 1.0 + 2.0 * (y1 - self.lower) / span;
        let beta_high = 1.0 + 2.0 * (self.upper - y2) / span;
        let c1 = 0.5 * ((y1 + y2) - spread(beta_low) * span);
        let c2 = 0.5 * ((y1 + y2) + spread(beta_high) * span);
        (c1.clamp(self.lower, self.upper), c2.clamp(self.lower, self.upper))
    }

    fn polynomial_mutation(&self, genes: &mut [f64], rng: &mut SeededRng) {
        let range = self.upper - self.lower;
        let power = 1.0 / (self.eta_mutation + 1.0);
        for y in genes {
            if rng.uniform() >= self.mutation_probability {
                continue;
            }
            let u = rng.uniform();
            let delta_q = if u < 0.5 {
                let xy = 1.0 - (*y - self.lower) / range;
                let val = 2.0 * u + (1.0 - 2.0 * u) * xy.powf(self.eta_mutation + 1.0);
                val.powf(power) - 1.0
            } else {
                let xy = 1.0 - (self.upper - *y) / range;
                let val = 2.0 * (1.0 - u) + 2.0 * (u - 0.5) * xy.powf(self.eta_mutation + 1.0);
                1.0 - val.powf(power)
            };
            *y = (*y + delta_q * range).clamp(self.lower, self.upper);
        }
    }
}

impl Representation for SbxPolynomial {
    type Genotype = Vec<f64>;

    fn validate(&self) -> Result<(), EvolutionError> {
        ensure(self.dimension > 0, || "SbxPolynomial: dimension must be > 0".into())?;
        ensure(self.lower < self.upper, || {
            format!("SbxPolynomial: bounds [{}, {}] are empty", self.lower, self.upper)
        })?;
        ensure(
            (0.0..=1.0).contains(&self.crossover_probability) && (0.0..=1.0).contains(&self.mutation_probability),
            || "SbxPolynomial: probabilities must be in [0, 1]".into(),
        )?;
        ensure(self.eta_crossover >= 0.0 && self.eta_mutation >= 0.0, || {
            "SbxPolynomial: distribution indices must be >= 0".into()
        })
    }

    fn random(&self, rng: &mut SeededRng) -> Vec<f64> {
        rng.uniform_vec(self.dimension, self.lower, self.upper)
    }

    fn mutate(&self, parent: &Vec<f64>, rng: &mut SeededRng) -> Vec<f64> {
        let mut child = parent.clone();
        self.polynomial_mutation(&mut child, rng);
        child
    }

    fn crossover(&self, first: &Vec<f64>, second: &Vec<f64>, rng: &mut SeededRng) -> Vec<f64> {
        let mut child = first.clone();
        if rng.uniform() < self.crossover_probability {
            for (c, &b) in child.iter_mut().zip(second) {
                let a = *c;
                // Each gene is crossed with probability 0.5; nearly equal genes are left alone.
                if rng.uniform() < 0.5 && (a - b).abs() > 1e-14 {
                    let u = rng.uniform();
                    let (low, high) = self.sbx_gene(a, b, u);
                    *c = if rng.uniform() < 0.5 { low } else { high };
                }
            }
        }
        self.polynomial_mutation(&mut child, rng);
        child
    }

    /// Identical gene values.
    fn is_duplicate(&self, a: &Vec<f64>, b: &Vec<f64>) -> bool {
        a == b
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Stream;

    #[test]
    fn children_stay_in_bounds_and_near_parents() {
        let rep = SbxPolynomial::new(10, 0.0, 1.0);
        let mut rng = SeededRng::derive(5, 0, 0, Stream::Variation);
        let p1 = vec![0.2; 10];
        let p2 = vec![0.8; 10];
        let mut mean_abs_dev = 0.0;
        let n = 2000;
        for _ in 0..n {
            let c = rep.crossover(&p1, &p2, &mut rng);
            assert!(c.iter().all(|x| (0.0..=1.0).contains(x)));
            let m = rep.mutate(&p1, &mut rng);
            assert!(m.iter().all(|x| (0.0..=1.0).contains(x)));
            mean_abs_dev += m.iter().map(|x| (x - 0.2).abs()).sum::<f64>() / 10.0;
        }
        // p_m = 1/n and η_m = 20: on average one gene moves by a few hundredths.
        let mad = mean_abs_dev / n as f64;
        assert!(mad > 0.001 && mad < 0.02, "{mad}");
        // SBX is mean-preserving around the parents' midpoint when far from the bounds.
        let (a, b) = rep.sbx_gene(0.4, 0.6, 0.3);
        assert!((a + b - 1.0).abs() < 1e-12);
    }
}
