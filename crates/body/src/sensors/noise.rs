//! Noisy (vsr-model.md §3.2): adds Gaussian noise N(0, (σ·extent)²) to each inner reading, where
//! extent is the width of that reading's domain (so σ is in normalised units when the inner sensor
//! is normalised). Noise is added after any normalisation inside, so readings may leave [0, 1].
//! The domain is the inner sensor's.
//!
//! **Deliberate difference from the original.** 2D-VSR-Sim (since 2021-02, so v1.9.2, v1.10 and
//! HEAD) seeds every `Noisy` with the same seed 0, so every noisy sensor on every voxel draws the
//! *identical* sequence, and a reset does not reseed it. vsrlab gives each `Noisy` instance its own
//! ChaCha8 stream: the key is the episode seed and the stream number packs (voxel index, index of
//! the sensor in the voxel's list, nesting depth of this `Noisy` among the `Noisy` wrappers of that
//! sensor). Distinct instances therefore draw independent noise, the same seed reproduces the same
//! noise, and resetting the sensor restarts the stream from its beginning.

use super::kind::SensorKind;
use super::node::{Node, Site};
use super::spec::SensorSpec;
use super::wrapper::{Transform, Wrapped};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

/// Bits of the stream number given to the voxel index.
const VOXEL_BITS: u32 = 32;
/// Bits given to the sensor's index in its voxel's list.
const SENSOR_BITS: u32 = 20;
/// Bits given to the nesting depth.
const DEPTH_BITS: u32 = 64 - VOXEL_BITS - SENSOR_BITS;

/// Most sensors one voxel may carry (so that stream numbers stay distinct).
pub(crate) const MAX_SENSORS_PER_VOXEL: usize = 1 << SENSOR_BITS;
/// Most `Noisy` wrappers nested in one sensor.
pub(crate) const MAX_NOISY_DEPTH: usize = 1 << DEPTH_BITS;

/// Identity of one noise stream: episode seed, voxel, sensor index in the voxel's list, and how many
/// `Noisy` wrappers enclose this one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NoiseKey {
    seed: u64,
    voxel: u64,
    sensor: u64,
    depth: u64,
}

impl NoiseKey {
    /// The key of the outermost `Noisy` of sensor `sensor` on voxel `voxel`.
    pub(crate) fn new(seed: u64, voxel: usize, sensor: usize) -> NoiseKey {
        NoiseKey {
            seed,
            voxel: voxel as u64,
            sensor: sensor as u64,
            depth: 0,
        }
    }

    /// The key of a `Noisy` inside this one.
    pub(crate) fn nested(self) -> NoiseKey {
        NoiseKey {
            depth: self.depth + 1,
            ..self
        }
    }

    /// ChaCha8 stream number: voxel | sensor | depth, each in its own bits (distinct for distinct
    /// keys within the limits above; the suite checks them).
    fn stream(self) -> u64 {
        let field = |v: u64, bits: u32| v & ((1u64 << bits) - 1);
        (field(self.voxel, VOXEL_BITS) << (SENSOR_BITS + DEPTH_BITS))
            | (field(self.sensor, SENSOR_BITS) << DEPTH_BITS)
            | field(self.depth, DEPTH_BITS)
    }

    /// A generator at the start of this key's stream.
    fn generator(self) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(self.seed);
        rng.set_stream(self.stream());
        rng
    }
}

/// A standard normal draw (Marsaglia's polar method), written here so that the values depend only
/// on ChaCha8, not on the version of a distributions crate.
fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    loop {
        let u = 2.0 * rng.random::<f64>() - 1.0;
        let v = 2.0 * rng.random::<f64>() - 1.0;
        let s = u * u + v * v;
        if s > 0.0 && s < 1.0 {
            return u * (-2.0 * s.ln() / s).sqrt();
        }
    }
}

/// Independent Gaussian noise added to every inner reading.
#[derive(Debug, Clone)]
pub(crate) struct Noisy {
    /// Standard deviation per reading: σ times the extent of the inner domain.
    sigmas: Vec<f64>,
    key: NoiseKey,
    /// Boxed: the generator's state is large next to the other sensors.
    rng: Box<ChaCha8Rng>,
}

impl Noisy {
    /// Noise of relative size `sigma` for readings whose domains are `domains`.
    pub(crate) fn new(domains: &[(f64, f64)], sigma: f64, key: NoiseKey) -> Noisy {
        Noisy {
            sigmas: domains.iter().map(|(lo, hi)| sigma * (hi - lo)).collect(),
            key,
            rng: Box::new(key.generator()),
        }
    }
}

impl Transform for Noisy {
    /// Adds one draw per reading.
    fn apply(&mut self, _t: f64, out: &mut [f64]) {
        for (o, sigma) in out.iter_mut().zip(&self.sigmas) {
            *o += sigma * standard_normal(&mut self.rng);
        }
    }

    /// Restarts the noise stream from its beginning.
    fn reset(&mut self) {
        *self.rng = self.key.generator();
    }
}

/// Description of a noisy wrapper (`{"kind": "noisy", "sigma": 0.01, "inner": {…}}`): adds
/// N(0, (σ·extent)²) to each inner reading, extent being the width of its domain; domain unchanged.
/// Each instance has its own noise stream (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NoisySpec {
    /// Standard deviation relative to the domain's extent (≥ 0).
    pub sigma: f64,
    /// The sensor the noise is added to.
    pub inner: Box<SensorSpec>,
}

impl SensorKind for NoisySpec {
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }

    fn domains(&self) -> Vec<(f64, f64)> {
        self.inner.domains()
    }

    fn validate(&self, noisy_depth: usize) -> Result<(), FieldError> {
        let sigma = self.sigma;
        if !(sigma.is_finite() && sigma >= 0.0) {
            return Err(FieldError::new(
                "sigma",
                format!("noise sigma must be a finite number ≥ 0, got {sigma}"),
            ));
        }
        if noisy_depth + 1 >= MAX_NOISY_DEPTH {
            return Err(FieldError::message(format!(
                "at most {} nested noisy wrappers",
                MAX_NOISY_DEPTH - 1
            )));
        }
        self.inner.validate_at(noisy_depth + 1).map_err(|e| e.at("inner"))
    }

    fn build(&self, site: Site) -> Node {
        let below = Site {
            noise: site.noise.nested(),
            ..site
        };
        let noisy = Noisy::new(&self.inner.domains(), self.sigma, site.noise);
        Node::Noisy(Wrapped::new(Box::new(Node::build(&self.inner, below)), noisy))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, frame, site, still_state};
    use crate::sensors::spec::SensorSpec;

    fn draws(key: NoiseKey, n: usize) -> Vec<f64> {
        let mut rng = key.generator();
        (0..n).map(|_| standard_normal(&mut rng)).collect()
    }

    #[test]
    fn streams_differ_by_every_part_of_the_key() {
        let base = NoiseKey::new(7, 3, 1);
        let a = draws(base, 8);
        assert_eq!(a, draws(base, 8));
        for other in [
            NoiseKey::new(8, 3, 1),
            NoiseKey::new(7, 4, 1),
            NoiseKey::new(7, 3, 2),
            base.nested(),
        ] {
            assert_ne!(a, draws(other, 8), "{other:?}");
        }
    }

    #[test]
    fn draws_are_standard_normal() {
        let x = draws(NoiseKey::new(1, 0, 0), 20_000);
        let n = x.len() as f64;
        let mean = x.iter().sum::<f64>() / n;
        let var = x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
        assert!(mean.abs() < 0.03 && (var - 1.0).abs() < 0.04, "mean {mean}, var {var}");
    }

    #[test]
    fn noise_scales_with_the_domain_and_restarts_on_reset() {
        // normalised area ratio (domain [0, 1]) at rest reads 0.5; σ = 0.1
        let spec = SensorSpec::AreaRatio.normalized().noisy(0.1);
        let mut node = Node::build(&spec, site());
        let world = empty_world();
        let state = still_state();
        let read = |node: &mut Node| {
            let mut out = [0.0];
            node.sense(&frame(&world, &state, 0.0), &mut out);
            out[0]
        };
        let first: Vec<f64> = (0..2000).map(|_| read(&mut node)).collect();
        let sd = (first.iter().map(|v| (v - 0.5) * (v - 0.5)).sum::<f64>() / first.len() as f64).sqrt();
        assert!((sd - 0.1).abs() < 0.01, "sd {sd}");
        node.reset();
        let again: Vec<f64> = (0..5).map(|_| read(&mut node)).collect();
        assert_eq!(again, first[..5]);
    }
}
