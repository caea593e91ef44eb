//! Counter-based random streams: every random draw of an optimizer comes from a generator
//! derived from `(run seed, generation, index, stream)`.
//!
//! Why: a generator shared across a whole run makes the numbers depend on the order in which
//! things are drawn, so parallel evaluation, a different thread count or a resumed checkpoint
//! could change the results. Deriving a fresh generator per (generation, individual, purpose)
//! makes every draw a pure function of the run seed and its position in the run.
//!
//! The generator is ChaCha8 ([`rand_chacha::ChaCha8Rng`]) seeded with 32 bytes expanded from a
//! SplitMix64 mix of the four keys. Uniform, integer and Gaussian variates are computed here
//! from raw 64-bit words (not through `rand`/`rand_distr` samplers) so the numbers do not change
//! when those crates change their algorithms.

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// What a random stream is used for; part of the derivation key so that different purposes at
/// the same (generation, index) never share numbers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u64)]
pub enum Stream {
    /// Building one candidate: parent selection and variation (index = candidate index).
    Variation = 1,
    /// The per-candidate seed handed to the evaluator (index = candidate index).
    Evaluation = 2,
    /// Sampling an initial genotype or an initial mean (index = individual index).
    Initialisation = 3,
    /// Speciation (k-means++ seeding) of a generation (index = 0).
    Speciation = 4,
    /// Sampling the search distribution of ES / CMA-ES (index = sample index).
    Sampling = 5,
}

/// One SplitMix64 step (Steele, Lea & Flood 2014): a fast bijective 64-bit mixer.
fn splitmix64(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Mixes the four keys into one 64-bit value (each key passes through the mixer in turn).
pub fn mix_keys(seed: u64, generation: u64, index: u64, stream: Stream) -> u64 {
    let mut state = seed;
    let mut acc = splitmix64(&mut state);
    for key in [generation, index, stream as u64] {
        state = acc ^ key.wrapping_mul(0xD6E8_FEB8_6659_FD93);
        acc = splitmix64(&mut state);
    }
    acc
}

/// The evaluation seed of candidate `index` of `generation`: what an evaluator should use for
/// its own randomness (e.g. a random terrain), so that it too is independent of evaluation order.
pub fn evaluation_seed(seed: u64, generation: u64, index: u64) -> u64 {
    mix_keys(seed, generation, index, Stream::Evaluation)
}

/// A seeded random generator with the few variates the optimizers need.
///
/// It also implements [`RngCore`], so `rand`'s extension traits can be used by genotype
/// operators written elsewhere.
#[derive(Debug, Clone)]
pub struct SeededRng {
    inner: ChaCha8Rng,
    spare_normal: Option<f64>,
}

impl SeededRng {
    /// The generator for `(seed, generation, index, stream)`.
    pub fn derive(seed: u64, generation: u64, index: u64, stream: Stream) -> Self {
        let mut state = mix_keys(seed, generation, index, stream);
        let mut bytes = [0u8; 32];
        for chunk in bytes.chunks_exact_mut(8) {
            chunk.copy_from_slice(&splitmix64(&mut state).to_le_bytes());
        }
        Self {
            inner: ChaCha8Rng::from_seed(bytes),
            spare_normal: None,
        }
    }

    /// Uniform in `[0, 1)` with 53 random bits.
    pub fn uniform(&mut self) -> f64 {
        (self.inner.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in `[low, high)`.
    pub fn uniform_in(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.uniform()
    }

    /// A vector of `n` independent variates uniform in `[low, high)`.
    pub fn uniform_vec(&mut self, n: usize, low: f64, high: f64) -> Vec<f64> {
        (0..n).map(|_| self.uniform_in(low, high)).collect()
    }

    /// Uniform integer in `0..n` (Lemire's multiply-and-reject, unbiased). Panics if `n == 0`.
    pub fn below(&mut self, n: usize) -> usize {
        assert!(n > 0, "SeededRng::below(0)");
        let n = n as u64;
        let threshold = n.wrapping_neg() % n;
        loop {
            let product = u128::from(self.inner.next_u64()) * u128::from(n);
            if (product as u64) >= threshold {
                return (product >> 64) as usize;
            }
        }
    }

    /// Standard normal variate (Marsaglia's polar method; the second variate of each pair is
    /// kept for the next call).
    pub fn normal(&mut self) -> f64 {
        if let Some(z) = self.spare_normal.take() {
            return z;
        }
        loop {
            let u = 2.0 * self.uniform() - 1.0;
            let v = 2.0 * self.uniform() - 1.0;
            let s = u * u + v * v;
            if s > 0.0 && s < 1.0 {
                let factor = (-2.0 * s.ln() / s).sqrt();
                self.spare_normal = Some(v * factor);
                return u * factor;
            }
        }
    }

    /// A vector of `n` independent standard normal variates.
    pub fn normal_vec(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.normal()).collect()
    }
}

impl RngCore for SeededRng {
    fn next_u32(&mut self) -> u32 {
        self.inner.next_u32()
    }

    fn next_u64(&mut self) -> u64 {
        self.inner.next_u64()
    }

    fn fill_bytes(&mut self, dst: &mut [u8]) {
        self.inner.fill_bytes(dst)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn streams_are_reproducible_and_distinct() {
        let mut a = SeededRng::derive(7, 3, 11, Stream::Variation);
        let mut b = SeededRng::derive(7, 3, 11, Stream::Variation);
        let xs: Vec<u64> = (0..8).map(|_| a.next_u64()).collect();
        let ys: Vec<u64> = (0..8).map(|_| b.next_u64()).collect();
        assert_eq!(xs, ys);
        for (g, i, s) in [
            (3, 12, Stream::Variation),
            (4, 11, Stream::Variation),
            (3, 11, Stream::Evaluation),
        ] {
            let mut c = SeededRng::derive(7, g, i, s);
            assert_ne!(xs[0], c.next_u64());
        }
        let mut d = SeededRng::derive(8, 3, 11, Stream::Variation);
        assert_ne!(xs[0], d.next_u64());
    }

    #[test]
    fn variates_have_the_right_moments() {
        let mut rng = SeededRng::derive(1, 0, 0, Stream::Sampling);
        let n = 200_000;
        let (mut s1, mut s2, mut s4) = (0.0, 0.0, 0.0);
        for _ in 0..n {
            let z = rng.normal();
            s1 += z;
            s2 += z * z;
            s4 += z * z * z * z;
        }
        let nf = n as f64;
        assert!((s1 / nf).abs() < 0.01, "mean {}", s1 / nf);
        assert!((s2 / nf - 1.0).abs() < 0.015, "variance {}", s2 / nf);
        assert!((s4 / nf - 3.0).abs() < 0.08, "kurtosis {}", s4 / nf);
        let mut counts = [0usize; 7];
        let mut mean_u = 0.0;
        for _ in 0..70_000 {
            counts[rng.below(7)] += 1;
            mean_u += rng.uniform();
        }
        assert!(counts.iter().all(|&c| (9_400..10_600).contains(&c)), "{counts:?}");
        assert!((mean_u / 70_000.0 - 0.5).abs() < 0.005);
    }
}
