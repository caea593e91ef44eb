//! Running sensors: a tree of nodes mirroring [`SensorSpec`], each with the state it needs
//! (sample windows, noise generators). Nothing allocates once the windows have filled.

use super::lidar::ray_angles;
use super::spec::{Axes, Axis, SensorSpec};
use crate::robot::VoxelState;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::VecDeque;
use vsrlab_physics::{Vec2, World};

/// What a sensor may read at one step.
pub struct Context<'a> {
    /// The world (for ray casts).
    pub world: &'a World,
    /// The voxel's state.
    pub state: &'a VoxelState,
    /// Simulated time.
    pub t: f64,
}

/// Time-stamped samples within a window, with their running sum: `t` then `dim` values per sample.
#[derive(Debug, Clone)]
pub(crate) struct Samples {
    window: f64,
    dim: usize,
    data: VecDeque<f64>,
    sum: Vec<f64>,
}

impl Samples {
    fn new(window: f64, dim: usize) -> Self {
        // room for the window at 60 Hz plus slack; more samples only grow the buffer once
        let cap = ((window * 60.0).ceil() as usize + 4) * (dim + 1);
        Samples {
            window,
            dim,
            data: VecDeque::with_capacity(cap),
            sum: vec![0.0; dim],
        }
    }

    fn clear(&mut self) {
        self.data.clear();
        self.sum.fill(0.0);
    }

    fn push(&mut self, t: f64, values: &[f64]) {
        self.data.push_back(t);
        self.data.extend(values.iter().copied());
        for (s, v) in self.sum.iter_mut().zip(values) {
            *s += v;
        }
        // keep samples with time ≥ t − window (inclusive, with a tolerance for accumulated time)
        while self.data.front().is_some_and(|&t0| t0 < t - self.window - 1e-9) {
            self.data.pop_front();
            for s in self.sum.iter_mut() {
                *s -= self.data.pop_front().unwrap_or(0.0);
            }
        }
    }

    fn count(&self) -> usize {
        self.data.len() / (self.dim + 1)
    }

    /// Time and i-th value of sample k.
    fn at(&self, k: usize, i: usize) -> f64 {
        self.data[k * (self.dim + 1) + 1 + i]
    }

    fn time(&self, k: usize) -> f64 {
        self.data[k * (self.dim + 1)]
    }
}

/// A running sensor.
#[derive(Debug, Clone)]
pub(crate) enum Node {
    AreaRatio,
    Touch,
    Velocity { rotated: bool, axes: Axes },
    Angle,
    Lidar { range: f64, angles: Vec<f64>, last: Vec<f64> },
    Cpg,
    Position(f64),
    Malfunction,
    Average { inner: Box<Node>, samples: Samples, buf: Vec<f64> },
    Trend { inner: Box<Node>, samples: Samples, buf: Vec<f64> },
    Normalize { inner: Box<Node>, domains: Vec<(f64, f64)>, soft: bool, clip: bool },
    Noisy { inner: Box<Node>, sigmas: Vec<f64>, seed: u64, rng: ChaCha8Rng },
}

/// SplitMix64 finaliser: mixes several integers into one well-spread seed.
pub(crate) fn mix_seed(parts: &[u64]) -> u64 {
    let mut z: u64 = 0x9E37_79B9_7F4A_7C15;
    for &p in parts {
        z = z.wrapping_add(p).wrapping_add(0x9E37_79B9_7F4A_7C15);
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
    }
    z
}

impl Node {
    /// Builds the running form of `spec` for a voxel at relative grid position `rel`; `seed` seeds
    /// noise (each noisy node gets its own stream).
    pub fn build(spec: &SensorSpec, rel: (f64, f64), seed: u64) -> Node {
        let inner = |of: &SensorSpec, s| Box::new(Node::build(of, rel, s));
        match spec {
            SensorSpec::AreaRatio => Node::AreaRatio,
            SensorSpec::Touch => Node::Touch,
            SensorSpec::Velocity { rotated, axes, .. } => Node::Velocity { rotated: *rotated, axes: *axes },
            SensorSpec::Angle => Node::Angle,
            SensorSpec::Lidar { range, rays } => Node::Lidar {
                range: *range,
                angles: ray_angles(rel.0, rel.1, *rays),
                last: vec![*range; *rays],
            },
            SensorSpec::Cpg => Node::Cpg,
            SensorSpec::Position { axis } => Node::Position(match axis {
                Axis::X => rel.0,
                Axis::Y => rel.1,
            }),
            SensorSpec::Malfunction => Node::Malfunction,
            SensorSpec::Average { window, of } => Node::Average {
                inner: inner(of, seed),
                samples: Samples::new(*window, of.dimension()),
                buf: vec![0.0; of.dimension()],
            },
            SensorSpec::Trend { window, of } => Node::Trend {
                inner: inner(of, seed),
                samples: Samples::new(*window, of.dimension()),
                buf: vec![0.0; of.dimension()],
            },
            SensorSpec::Normalization { of } => Node::Normalize {
                inner: inner(of, seed),
                domains: of.domains(),
                soft: false,
                clip: true,
            },
            SensorSpec::SoftNormalization { clip, of } => Node::Normalize {
                inner: inner(of, seed),
                domains: of.domains(),
                soft: true,
                clip: *clip,
            },
            SensorSpec::Noisy { sigma, of } => {
                let own = mix_seed(&[seed, 0x4E01_5E]);
                Node::Noisy {
                    inner: inner(of, mix_seed(&[seed, 1])),
                    sigmas: of.domains().iter().map(|(lo, hi)| sigma * (hi - lo)).collect(),
                    seed: own,
                    rng: ChaCha8Rng::seed_from_u64(own),
                }
            }
        }
    }

    /// Clears windows and restarts noise streams.
    pub fn reset(&mut self) {
        match self {
            Node::Average { inner, samples, .. } | Node::Trend { inner, samples, .. } => {
                samples.clear();
                inner.reset();
            }
            Node::Normalize { inner, .. } => inner.reset(),
            Node::Noisy { inner, seed, rng, .. } => {
                *rng = ChaCha8Rng::seed_from_u64(*seed);
                inner.reset();
            }
            Node::Lidar { range, last, .. } => last.fill(*range),
            _ => {}
        }
    }

    /// Writes this sensor's readings into `out` (exactly its dimension).
    pub fn sense(&mut self, ctx: &Context, out: &mut [f64]) {
        let s = ctx.state;
        match self {
            Node::AreaRatio => out[0] = s.area_ratio,
            Node::Touch => out[0] = if s.touching { 1.0 } else { 0.0 },
            Node::Velocity { rotated, axes } => {
                let v = if *rotated {
                    let (sin, cos) = s.angle.sin_cos();
                    Vec2::new(s.velocity.dot(Vec2::new(cos, sin)), s.velocity.dot(Vec2::new(-sin, cos)))
                } else {
                    s.velocity
                };
                match axes {
                    Axes::X => out[0] = v.x,
                    Axes::Y => out[0] = v.y,
                    Axes::Xy => {
                        out[0] = v.x;
                        out[1] = v.y;
                    }
                }
            }
            Node::Angle => out[0] = s.angle,
            Node::Lidar { range, angles, last } => {
                for (k, a) in angles.iter().enumerate() {
                    let (sin, cos) = (s.angle + a).sin_cos();
                    let d = ctx.world.ray_cast_static(s.center, Vec2::new(cos, sin), *range).unwrap_or(*range);
                    last[k] = d;
                    out[k] = d;
                }
            }
            Node::Cpg => out[0] = (-2.0 * std::f64::consts::PI * ctx.t).sin(),
            Node::Position(p) => out[0] = *p,
            Node::Malfunction => out[0] = 0.0,
            Node::Average { inner, samples, buf } => {
                inner.sense(ctx, buf);
                samples.push(ctx.t, buf);
                let n = samples.count() as f64;
                for (o, s) in out.iter_mut().zip(&samples.sum) {
                    *o = s / n;
                }
            }
            Node::Trend { inner, samples, buf } => {
                inner.sense(ctx, buf);
                samples.push(ctx.t, buf);
                let last = samples.count() - 1;
                let (t0, t1) = (samples.time(0), samples.time(last));
                for (i, o) in out.iter_mut().enumerate() {
                    *o = if t1 > t0 { (samples.at(last, i) - samples.at(0, i)) / (t1 - t0) } else { 0.0 };
                }
            }
            Node::Normalize { inner, domains, soft, clip } => {
                inner.sense(ctx, out);
                for (o, (lo, hi)) in out.iter_mut().zip(domains.iter()) {
                    let mut v = (*o - lo) / (hi - lo);
                    if *clip {
                        v = v.clamp(0.0, 1.0);
                    }
                    *o = if *soft { (2.0 * (2.0 * v - 1.0)).tanh() / 2.0 + 0.5 } else { v };
                }
            }
            Node::Noisy { inner, sigmas, rng, .. } => {
                inner.sense(ctx, out);
                for (o, sigma) in out.iter_mut().zip(sigmas.iter()) {
                    *o += sigma * gaussian(rng);
                }
            }
        }
    }

    /// The lidar leaves of this tree: (relative angle, range, last distance) per ray.
    pub fn lidar_rays(&self, out: &mut Vec<(f64, f64, f64)>) {
        match self {
            Node::Lidar { range, angles, last } => out.extend(angles.iter().zip(last).map(|(a, d)| (*a, *range, *d))),
            Node::Average { inner, .. } | Node::Trend { inner, .. } | Node::Normalize { inner, .. } | Node::Noisy { inner, .. } => {
                inner.lidar_rays(out)
            }
            _ => {}
        }
    }
}

/// A standard normal draw (Marsaglia's polar method), written here so that values do not change
/// with the version of a distributions crate.
fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    loop {
        let u: f64 = rng.random_range(-1.0..1.0);
        let v: f64 = rng.random_range(-1.0..1.0);
        let s = u * u + v * v;
        if s > 0.0 && s < 1.0 {
            return u * (-2.0 * s.ln() / s).sqrt();
        }
    }
}
