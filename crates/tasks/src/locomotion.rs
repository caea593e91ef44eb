//! The locomotion task (vsr-model.md §5.1): walk as far right as possible in a given time.

use crate::outcome::{Outcome, RayInfo, Trace, TraceLevel};
use crate::robot::RobotSpec;
use crate::terrain::{add_ground, height_at, Terrain};
use serde::{Deserialize, Serialize};
use vsrlab_body::sensors::SensorSuite;
use vsrlab_body::{VoxelState, Vsr};
use vsrlab_physics::{PhysicsError, Vec2, World, WorldBuilder, WorldSettings};

/// Why an episode could not be run or completed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EpisodeError {
    /// The description is invalid; the message names the field.
    #[error("{0}")]
    Invalid(String),
    /// The simulation produced non-finite values.
    #[error("episode failed at t = {time:.4} s: {source}")]
    Physics {
        /// Simulated time when it happened.
        time: f64,
        /// The engine's report.
        source: PhysicsError,
    },
}

/// Locomotion task settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Locomotion {
    /// The ground.
    pub terrain: Terrain,
    /// Episode length (simulated seconds).
    pub duration: f64,
    /// Initial period (s) excluded from distance and velocity.
    pub transient: f64,
    /// x of the robot's left edge at the start (the original's x₁ + 1 = 11).
    pub initial_x: f64,
    /// Gap between the lowest voxel and the ground below it at the start.
    pub initial_gap: f64,
    /// Physics engine settings.
    pub physics: WorldSettings,
}

impl Default for Locomotion {
    fn default() -> Self {
        Locomotion {
            terrain: Terrain::Flat,
            duration: 30.0,
            transient: 0.0,
            initial_x: 11.0,
            initial_gap: 1.0,
            physics: WorldSettings::default(),
        }
    }
}

impl Locomotion {
    /// Checks the settings; errors name the field.
    pub fn validate(&self) -> Result<(), EpisodeError> {
        let bad = |m: String| Err(EpisodeError::Invalid(m));
        if !(self.duration.is_finite() && self.duration > 0.0 && self.duration <= 1e5) {
            return bad(format!(
                "task.duration must be in (0, 100000] seconds, got {}",
                self.duration
            ));
        }
        if !(self.transient.is_finite() && self.transient >= 0.0 && self.transient < self.duration) {
            return bad(format!(
                "task.transient must be ≥ 0 and shorter than the duration ({}), got {}",
                self.duration, self.transient
            ));
        }
        if !(self.initial_x.is_finite() && self.initial_gap.is_finite() && self.initial_gap >= 0.0) {
            return bad("task.initial_x and task.initial_gap must be finite (gap ≥ 0)".into());
        }
        self.physics
            .validate()
            .map_err(|m| EpisodeError::Invalid(format!("task.physics.{m}")))
    }
}

/// The lower-left corner of the robot's grid such that its left edge is at `initial_x` and its
/// lowest voxel is `initial_gap` above the ground beneath it (vsr-model.md §2.4).
fn placement(robot: &RobotSpec, profile: &[Vec2], task: &Locomotion) -> Vec2 {
    let l = robot.voxel_params().side_length;
    let x0 = task.initial_x;
    let y0 = robot
        .body
        .voxels()
        .map(|(x, y)| {
            let cx = x0 + (x as f64 + 0.5) * l;
            height_at(profile, cx).unwrap_or(0.0) - y as f64 * l
        })
        .fold(f64::NEG_INFINITY, f64::max)
        + task.initial_gap;
    Vec2::new(x0, y0)
}

/// Runs one locomotion episode. Pure: the same inputs give bit-identical outcomes.
pub fn run(robot: &RobotSpec, task: &Locomotion, seed: u64, trace_level: TraceLevel) -> Result<Outcome, EpisodeError> {
    task.validate()?;
    let params = robot.voxel_params();
    params.validate().map_err(EpisodeError::Invalid)?;
    let profile = task.terrain.profile(seed);
    let mut builder = WorldBuilder::new(task.physics.clone());
    add_ground(&mut builder, &profile);
    let origin = placement(robot, &profile, task);
    let vsr = Vsr::assemble(&mut builder, &robot.body, &params, origin, 1);
    let mut world = builder.build().map_err(|e| EpisodeError::Invalid(e.to_string()))?;
    let mut sensors = SensorSuite::new(&robot.sensors, &robot.body, seed)
        .map_err(|e| EpisodeError::Invalid(format!("robot.sensors: {e}")))?;
    let per_voxel: Vec<usize> = (0..robot.body.voxel_count())
        .map(|v| sensors.readings_per_voxel(v))
        .collect();
    let mut brain = robot
        .brain
        .build(&robot.body, &per_voxel)
        .map_err(|e| EpisodeError::Invalid(format!("robot.{e}")))?;
    brain.reset();

    let n = vsr.voxel_count();
    let mut states = vec![vsr.voxel_state(&world, 0); n];
    let mut readings = vec![0.0; sensors.total_readings()];
    let mut actuations = vec![0.0; n];
    let mut recorder = Recorder::new(trace_level, task, &vsr, &sensors, &profile, &world);
    let dt = task.physics.dt;
    let mut t = 0.0;
    let mut window = Window::default();
    while t < task.duration {
        t += dt;
        world
            .step()
            .map_err(|source| EpisodeError::Physics { time: t, source })?;
        for (i, s) in states.iter_mut().enumerate() {
            *s = vsr.voxel_state(&world, i);
        }
        sensors.sense(&world, &vsr, &states, t, &mut readings);
        brain.control(t, &readings, &mut actuations);
        vsr.actuate(&mut world, &actuations);
        let center = vsr.center(&world);
        if !center.is_finite() {
            return Err(EpisodeError::Physics {
                time: t,
                source: PhysicsError::NonFinite {
                    step: world.step_count(),
                    body: 0,
                },
            });
        }
        if t >= task.transient {
            window.observe(t, center.x);
        }
        recorder.record(t, center, &states, &actuations, &readings, &sensors);
    }
    let elapsed = window.last_t - window.first_t;
    let distance = window.last_x - window.first_x;
    Ok(Outcome {
        distance,
        velocity: if elapsed > 0.0 { distance / elapsed } else { 0.0 },
        elapsed,
        steps: world.step_count(),
        voxels: n,
        trace: recorder.finish(),
    })
}

/// First and last observation of the evaluated window.
#[derive(Debug, Default)]
struct Window {
    started: bool,
    first_t: f64,
    first_x: f64,
    last_t: f64,
    last_x: f64,
}

impl Window {
    fn observe(&mut self, t: f64, x: f64) {
        if !self.started {
            self.started = true;
            self.first_t = t;
            self.first_x = x;
        }
        self.last_t = t;
        self.last_x = x;
    }
}

/// Accumulates the trace at the requested level.
struct Recorder {
    level: TraceLevel,
    trace: Trace,
    domains: Vec<(f64, f64)>,
}

impl Recorder {
    fn new(
        level: TraceLevel,
        task: &Locomotion,
        vsr: &Vsr,
        sensors: &SensorSuite,
        profile: &[Vec2],
        _world: &World,
    ) -> Recorder {
        let n = vsr.voxel_count();
        let steps = (task.duration / task.physics.dt).ceil() as usize + 1;
        let mut trace = Trace {
            dt: task.physics.dt,
            side_length: vsr.params().side_length,
            ..Default::default()
        };
        let mut domains = Vec::new();
        if level != TraceLevel::None {
            trace.times.reserve(steps);
            trace.centers.reserve(steps);
        }
        if level == TraceLevel::Full {
            trace.terrain = profile.to_vec();
            trace.cells = vsr.voxels().iter().map(|v| v.cell).collect();
            trace.polygons.reserve(steps * n);
            for v in 0..n {
                trace.readings_per_voxel.push(sensors.readings_per_voxel(v));
                domains.extend(sensors.domains(v));
                for ray in sensors.lidar_rays(v) {
                    trace.rays.push(RayInfo {
                        voxel: v,
                        relative_angle: ray.relative_angle,
                        range: ray.range,
                    });
                }
            }
        }
        Recorder { level, trace, domains }
    }

    fn record(
        &mut self,
        t: f64,
        center: Vec2,
        states: &[VoxelState],
        actuations: &[f64],
        readings: &[f64],
        sensors: &SensorSuite,
    ) {
        if self.level == TraceLevel::None {
            return;
        }
        self.trace.times.push(t);
        self.trace.centers.push(center);
        if self.level != TraceLevel::Full {
            return;
        }
        for s in states {
            self.trace.polygons.push(s.polygon);
            self.trace.area_ratios.push(s.area_ratio);
            self.trace.angles.push(s.angle);
            self.trace.touching.push(s.touching);
        }
        self.trace.actuations.extend_from_slice(actuations);
        for (r, (lo, hi)) in readings.iter().zip(&self.domains) {
            let span = hi - lo;
            let v = if span > 0.0 { (r - lo) / span } else { 0.0 };
            self.trace.readings.push(v.clamp(0.0, 1.0) as f32);
        }
        for v in 0..states.len() {
            for ray in sensors.lidar_rays(v) {
                self.trace.ray_distances.push(ray.distance as f32);
            }
        }
    }

    fn finish(self) -> Option<Trace> {
        (self.level != TraceLevel::None).then_some(self.trace)
    }
}
