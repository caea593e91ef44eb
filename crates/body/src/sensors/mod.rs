//! Sensors (vsr-model.md §3): what each voxel perceives at every step.
//!
//! A [`SensorConfig`] places [`SensorSpec`]s on voxels; a [`SensorSuite`] runs them and writes all
//! readings, voxel by voxel in grid order, each voxel's sensors in list order.
//!
//! Noise differs from the original on purpose: every noisy sensor instance draws from its own
//! generator, seeded from (episode seed, voxel index, sensor index), instead of the original's
//! identical seed-0 stream shared by every sensor (vsr-model.md §3.2).

mod lidar;
mod node;
mod placement;
mod spec;

pub use placement::SensorConfig;
pub use spec::{Axes, Axis, SensorSpec};

use crate::morphology::Morphology;
use crate::robot::{VoxelState, Vsr};
use node::{mix_seed, Context, Node};
use vsrlab_physics::World;

/// Why a sensor configuration was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SensorError {
    /// A sensor name is not one of the known ones.
    #[error("unknown sensor '{0}': expected one of a, t, r, vx, vy, vxy, ax, ay, axy, px, py, m, cpg, l5, l1")]
    UnknownSensor(String),
    /// A placement string is malformed.
    #[error("bad sensor placement '{placement}': {msg}")]
    BadPlacement {
        /// The placement string.
        placement: String,
        /// What is wrong.
        msg: String,
    },
    /// A per-voxel list does not have one entry per voxel.
    #[error("per-voxel sensor list has {got} entries but the body has {expected} voxels")]
    WrongVoxelCount {
        /// Voxels in the body.
        expected: usize,
        /// Lists given.
        got: usize,
    },
    /// A sensor parameter is out of range.
    #[error("sensor on voxel {voxel}: {msg}")]
    Invalid {
        /// Voxel index (grid order).
        voxel: usize,
        /// What is wrong.
        msg: String,
    },
}

/// A lidar ray of a voxel, for drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LidarRay {
    /// Direction relative to the voxel angle (radians).
    pub relative_angle: f64,
    /// Maximum distance.
    pub range: f64,
    /// Distance measured at the last step.
    pub distance: f64,
}

/// The running sensors of one robot.
#[derive(Debug, Clone)]
pub struct SensorSuite {
    /// Sensors per voxel (grid order).
    nodes: Vec<Vec<Node>>,
    specs: Vec<Vec<SensorSpec>>,
    offsets: Vec<usize>,
    total: usize,
}

impl SensorSuite {
    /// Places and builds the sensors for a body; `seed` seeds noise.
    pub fn new(config: &SensorConfig, morphology: &Morphology, seed: u64) -> Result<SensorSuite, SensorError> {
        let specs = config.specs(morphology)?;
        let (w, h) = (morphology.width(), morphology.height());
        let rel = |c: usize, n: usize| if n > 1 { c as f64 / (n - 1) as f64 } else { 0.5 };
        let mut nodes = Vec::with_capacity(specs.len());
        let mut offsets = Vec::with_capacity(specs.len() + 1);
        let mut total = 0;
        for (v, ((x, y), list)) in morphology.voxels().zip(&specs).enumerate() {
            offsets.push(total);
            let mut voxel_nodes = Vec::with_capacity(list.len());
            for (k, spec) in list.iter().enumerate() {
                spec.validate().map_err(|msg| SensorError::Invalid { voxel: v, msg })?;
                total += spec.dimension();
                voxel_nodes.push(Node::build(spec, (rel(x, w), rel(y, h)), mix_seed(&[seed, v as u64, k as u64])));
            }
            nodes.push(voxel_nodes);
        }
        offsets.push(total);
        Ok(SensorSuite { nodes, specs, offsets, total })
    }

    /// Number of readings of voxel `v`.
    pub fn readings_per_voxel(&self, v: usize) -> usize {
        self.offsets[v + 1] - self.offsets[v]
    }

    /// Total number of readings (all voxels).
    pub fn total_readings(&self) -> usize {
        self.total
    }

    /// Domain (min, max) of each reading of voxel `v`.
    pub fn domains(&self, v: usize) -> Vec<(f64, f64)> {
        self.specs[v].iter().flat_map(|s| s.domains()).collect()
    }

    /// The sensors placed on voxel `v`.
    pub fn specs(&self, v: usize) -> &[SensorSpec] {
        &self.specs[v]
    }

    /// Lidar rays of voxel `v` with their last measured distances.
    pub fn lidar_rays(&self, v: usize) -> Vec<LidarRay> {
        let mut raw = Vec::new();
        for n in &self.nodes[v] {
            n.lidar_rays(&mut raw);
        }
        raw.into_iter()
            .map(|(relative_angle, range, distance)| LidarRay {
                relative_angle,
                range,
                distance,
            })
            .collect()
    }

    /// Clears every window and restarts every noise stream.
    pub fn reset(&mut self) {
        self.nodes.iter_mut().flatten().for_each(Node::reset);
    }

    /// Senses every voxel at time `t` (states in grid order) and writes all readings into `out`.
    pub fn sense(&mut self, world: &World, _vsr: &Vsr, states: &[VoxelState], t: f64, out: &mut [f64]) {
        for (v, voxel_nodes) in self.nodes.iter_mut().enumerate() {
            let ctx = Context { world, state: &states[v], t };
            let mut at = self.offsets[v];
            for n in voxel_nodes.iter_mut() {
                let dim = n_dim(n);
                n.sense(&ctx, &mut out[at..at + dim]);
                at += dim;
            }
        }
    }
}

/// Dimension of a running node (mirrors [`SensorSpec::dimension`]).
fn n_dim(n: &Node) -> usize {
    match n {
        Node::Velocity { axes: Axes::Xy, .. } => 2,
        Node::Lidar { angles, .. } => angles.len(),
        Node::Average { buf, .. } | Node::Trend { buf, .. } => buf.len(),
        Node::Normalize { domains, .. } => domains.len(),
        Node::Noisy { sigmas, .. } => sigmas.len(),
        _ => 1,
    }
}

#[cfg(test)]
mod tests;
