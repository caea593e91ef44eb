//! Sensors (vsr-model.md §3): what each voxel perceives at every step.
//!
//! - A [`SensorSpec`] describes one sensor: a raw sensor ([`SensorSpec::AreaRatio`],
//!   [`SensorSpec::Touch`], [`SensorSpec::Velocity`], [`SensorSpec::Angle`], [`SensorSpec::Lidar`],
//!   [`SensorSpec::Cpg`], [`SensorSpec::ConstantPosition`], [`SensorSpec::Malfunction`]), possibly
//!   inside wrappers ([`SensorSpec::Average`], [`SensorSpec::Trend`], [`SensorSpec::Normalization`],
//!   [`SensorSpec::SoftNormalization`], [`SensorSpec::Noisy`]). [`SensorSpec::named`] gives the
//!   named sensors of 2D-VSR-Sim (`a`, `t`, `vxy`, …), listed in [`NAMED_SENSORS`].
//! - A [`SensorConfig`] places sensors on a body: a placement string (`uniform-a+vxy+t-0.01`,
//!   `spinedTouchSighted-f-f-0.01`, `empty`, …) or a list of sensor names per voxel.
//! - A [`SensorSuite`] runs the sensors of one robot during an episode. Each step,
//!   [`SensorSuite::sense`] writes every reading, voxel by voxel in grid order (row-major from the
//!   bottom row), each voxel's sensors in list order. It never allocates: windows are ring buffers
//!   sized when the suite is built.
//!
//! Each sensor kind lives in its own file (`velocity.rs`, `average.rs`, …): the running sensor, its
//! description (e.g. [`VelocitySpec`]) and how that description gives its readings count, domains,
//! checks and running form (the crate-internal `SensorKind` trait; a sensor without parameters is a
//! `Parameterless` value, a wrapper a `Transform` of its inner readings described by a
//! `WrapperKind`, see `wrapper.rs`). To add a sensor: write its file; add a variant to
//! [`SensorSpec`] and its arm in `SensorSpec::as_kind` (`spec.rs`); add a variant to the running
//! `Node` enum and its arm in `Node::sense`, `Node::reset` and, for wrappers,
//! `Node::for_each_lidar` (`node.rs`, kept an enum so that sensing is statically dispatched); give
//! it a name in [`NAMED_SENSORS`] (`named.rs`) if placements should offer it.
//!
//! Noise differs from the original on purpose: every `Noisy` instance draws from its own ChaCha8
//! stream, keyed by (episode seed, voxel index, sensor index), instead of the original's seed-0
//! stream shared by every noisy sensor of every voxel (vsr-model.md §3.2; details in `noise.rs`).

mod angle;
mod area_ratio;
mod average;
mod constant;
mod cpg;
mod kind;
mod lidar;
mod malfunction;
mod named;
mod node;
mod noise;
mod normalization;
mod placement;
mod soft_normalization;
mod spec;
mod touch;
mod trend;
mod velocity;
mod window;
mod wrapper;

pub use average::AverageSpec;
pub use constant::{Axis, ConstantPositionSpec};
pub use lidar::{LidarSpec, RayLayout, MAX_RAYS};
pub use named::{NamedSensor, NAMED_SENSORS, SENSOR_NAMES};
pub use noise::NoisySpec;
pub use normalization::NormalizationSpec;
pub use placement::{ApparatusShape, Level, SensorConfig};
pub use soft_normalization::SoftNormalizationSpec;
pub use spec::SensorSpec;
pub use trend::TrendSpec;
pub use velocity::{Axes, VelocitySpec};
pub use window::MAX_WINDOW;

use crate::morphology::Morphology;
use crate::robot::VoxelState;
use constant::relative_position;
use node::{Frame, Node, Site};
use noise::{NoiseKey, MAX_SENSORS_PER_VOXEL};
use std::ops::Range;
use vsrlab_field::FieldError;
use vsrlab_physics::World;

/// The sampling interval the suite plans its windows for unless told otherwise: one physics step of
/// 2D-VSR-Sim (1/60 s).
pub const DEFAULT_TIME_STEP: f64 = 1.0 / 60.0;

/// Why a sensor configuration was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SensorError {
    /// A sensor name is not one of [`SENSOR_NAMES`].
    #[error("{}unknown sensor '{name}': expected one of {}", at_voxel(.voxel), SENSOR_NAMES.join(", "))]
    UnknownSensor {
        /// Voxel (grid order) whose list holds the name, for per-voxel lists.
        voxel: Option<usize>,
        /// The unknown name.
        name: String,
    },
    /// A placement string is malformed.
    #[error("bad sensor placement '{placement}': got '{token}', expected {expected}")]
    BadPlacement {
        /// The whole placement string.
        placement: String,
        /// The offending part.
        token: String,
        /// What would have been accepted there.
        expected: String,
    },
    /// A per-voxel placement does not have one list per voxel.
    #[error("the per-voxel sensor lists are {got} but the body has {expected} voxels: give one list per voxel, in grid order (row-major from the bottom row)")]
    WrongVoxelCount {
        /// Voxels in the body.
        expected: usize,
        /// Lists given.
        got: usize,
    },
    /// A sensor parameter is out of range; shown with the error's message, which names the
    /// parameter in words (its path locates it in the sensor's description).
    #[error("voxel {voxel}, sensor {sensor}: {}", .error.message)]
    InvalidSensor {
        /// Voxel (grid order).
        voxel: usize,
        /// Position of the sensor in the voxel's list.
        sensor: usize,
        /// What is wrong, and where in the sensor's description ([`SensorSpec::validate`]).
        error: FieldError,
    },
    /// The planned sampling interval is not a positive number.
    #[error("the sensor time step must be a finite number > 0, got {0}")]
    InvalidTimeStep(f64),
}

fn at_voxel(voxel: &Option<usize>) -> String {
    voxel.map(|v| format!("voxel {v}: ")).unwrap_or_default()
}

/// One lidar ray of a voxel, for drawing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LidarRay {
    /// Direction relative to the voxel's angle (radians).
    pub relative_angle: f64,
    /// Maximum distance.
    pub range: f64,
    /// Distance measured at the last step (the range before the first).
    pub distance: f64,
}

/// One running sensor and where its readings go.
#[derive(Debug, Clone)]
struct Placed {
    node: Node,
    /// Its readings within the suite's output.
    readings: Range<usize>,
}

/// The running sensors of one robot.
#[derive(Debug, Clone)]
pub struct SensorSuite {
    /// Every sensor, voxels in grid order, each voxel's in list order.
    sensors: Vec<Placed>,
    /// Voxel v's sensors are `sensors[first_sensor[v]..first_sensor[v + 1]]`.
    first_sensor: Vec<usize>,
    /// Voxel v's readings are `first_reading[v]..first_reading[v + 1]`.
    first_reading: Vec<usize>,
    /// The specs per voxel, as placed.
    specs: Vec<Vec<SensorSpec>>,
}

impl SensorSuite {
    /// Places `config`'s sensors on `body`; `seed` (the episode seed) keys the noise streams.
    /// Windows are planned for readings every [`DEFAULT_TIME_STEP`].
    pub fn new(config: &SensorConfig, body: &Morphology, seed: u64) -> Result<SensorSuite, SensorError> {
        SensorSuite::with_time_step(config, body, seed, DEFAULT_TIME_STEP)
    }

    /// As [`SensorSuite::new`], with windows planned for readings every `dt` seconds (readings at
    /// other intervals are still windowed correctly by timestamp; faster ones cost one allocation).
    pub fn with_time_step(
        config: &SensorConfig,
        body: &Morphology,
        seed: u64,
        dt: f64,
    ) -> Result<SensorSuite, SensorError> {
        SensorSuite::from_specs(config.specs(body)?, body, seed, dt)
    }

    /// As [`SensorSuite::new`], with the named sensors built as `preset`'s simulator builds them
    /// ([`SensorSpec::named_in`]).
    pub fn for_preset(
        config: &SensorConfig,
        body: &Morphology,
        seed: u64,
        preset: crate::Preset,
    ) -> Result<SensorSuite, SensorError> {
        SensorSuite::from_specs(config.specs_in(body, preset)?, body, seed, DEFAULT_TIME_STEP)
    }

    /// Builds explicit sensor trees: `specs[v]` lists the sensors of voxel v (grid order).
    pub fn from_specs(
        specs: Vec<Vec<SensorSpec>>,
        body: &Morphology,
        seed: u64,
        dt: f64,
    ) -> Result<SensorSuite, SensorError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(SensorError::InvalidTimeStep(dt));
        }
        if specs.len() != body.voxel_count() {
            return Err(SensorError::WrongVoxelCount {
                expected: body.voxel_count(),
                got: specs.len(),
            });
        }
        let (w, h) = (body.width(), body.height());
        let mut sensors = Vec::new();
        let mut first_sensor = vec![0];
        let mut first_reading = vec![0];
        let mut next = 0;
        for (v, ((x, y), list)) in body.voxels().zip(&specs).enumerate() {
            if list.len() > MAX_SENSORS_PER_VOXEL {
                return Err(SensorError::InvalidSensor {
                    voxel: v,
                    sensor: MAX_SENSORS_PER_VOXEL,
                    error: FieldError::message(format!(
                        "at most {MAX_SENSORS_PER_VOXEL} sensors per voxel, got {}",
                        list.len()
                    )),
                });
            }
            for (k, spec) in list.iter().enumerate() {
                spec.validate().map_err(|error| SensorError::InvalidSensor {
                    voxel: v,
                    sensor: k,
                    error,
                })?;
                let site = Site {
                    rel: (relative_position(x, w), relative_position(y, h)),
                    dt,
                    noise: NoiseKey::new(seed, v, k),
                };
                let dim = spec.dimension();
                sensors.push(Placed {
                    node: Node::build(spec, site),
                    readings: next..next + dim,
                });
                next += dim;
            }
            first_sensor.push(sensors.len());
            first_reading.push(next);
        }
        Ok(SensorSuite {
            sensors,
            first_sensor,
            first_reading,
            specs,
        })
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.specs.len()
    }

    /// Number of readings of voxel `v` (grid order).
    pub fn readings_per_voxel(&self, v: usize) -> usize {
        self.first_reading[v + 1] - self.first_reading[v]
    }

    /// Where voxel `v`'s readings lie in the output of [`SensorSuite::sense`].
    pub fn readings_range(&self, v: usize) -> Range<usize> {
        self.first_reading[v]..self.first_reading[v + 1]
    }

    /// Total number of readings, all voxels.
    pub fn total_readings(&self) -> usize {
        self.first_reading[self.specs.len()]
    }

    /// The sensors placed on voxel `v`, in list order.
    pub fn specs(&self, v: usize) -> &[SensorSpec] {
        &self.specs[v]
    }

    /// Declared domain (min, max) of each reading of voxel `v`, after wrapping.
    pub fn domains(&self, v: usize) -> Vec<(f64, f64)> {
        self.specs[v].iter().flat_map(SensorSpec::domains).collect()
    }

    /// The lidar rays of voxel `v`, in reading order, with the distances measured at the last step.
    pub fn lidar_rays(&self, v: usize) -> Vec<LidarRay> {
        let mut rays = Vec::new();
        for placed in self.voxel_sensors(v) {
            placed.node.for_each_lidar(&mut |lidar| {
                let range = lidar.range();
                rays.extend(lidar.directions().iter().zip(lidar.last_distances()).map(
                    |(&relative_angle, &distance)| LidarRay {
                        relative_angle,
                        range,
                        distance,
                    },
                ));
            });
        }
        rays
    }

    /// Back to the state right after construction: empty windows, noise streams at their start.
    pub fn reset(&mut self) {
        self.sensors.iter_mut().for_each(|p| p.node.reset());
    }

    /// Reads every sensor at simulated time `t` and writes all readings into `out`
    /// (length [`SensorSuite::total_readings`]). `states` are the states of the body's sensing
    /// units ([`crate::Body::unit_state`]) in grid order. Call once per step, with increasing `t`.
    ///
    /// # Panics
    /// If `states` does not have one entry per voxel or `out` is not exactly the readings' length.
    pub fn sense(&mut self, world: &World, states: &[VoxelState], t: f64, out: &mut [f64]) {
        assert_eq!(states.len(), self.voxel_count(), "one voxel state per voxel");
        assert_eq!(out.len(), self.total_readings(), "one slot per reading");
        for (v, state) in states.iter().enumerate() {
            let frame = Frame { world, state, t };
            for placed in &mut self.sensors[self.first_sensor[v]..self.first_sensor[v + 1]] {
                placed.node.sense(&frame, &mut out[placed.readings.clone()]);
            }
        }
    }

    fn voxel_sensors(&self, v: usize) -> &[Placed] {
        &self.sensors[self.first_sensor[v]..self.first_sensor[v + 1]]
    }
}

#[cfg(test)]
mod tests;
