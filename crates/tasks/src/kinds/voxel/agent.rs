//! The 2D-VSR-Sim voxel robot as a [`Robot`]: a [`RobotSpec`] assembles into a [`Vsr`] body, its
//! [`SensorSuite`] and its brain; at every step its [`VoxelAgent`] reads the voxel states, senses,
//! controls and actuates, in that order (vsr-model.md §2.2).

use crate::agent::{Agent, Robot};
use crate::body_summary::BodySummary;
use crate::channels::{ACTUATION, AREA_RATIO, READINGS, READINGS_PER_UNIT, TOUCH};
use crate::episode::EpisodeError;
use crate::kinds::voxel::robot::RobotSpec;
use crate::outcome::Trace;
use vsrlab_body::sensors::SensorSuite;
use vsrlab_body::{Body, Channel, Probe, VoxelState, Vsr};
use vsrlab_brain::BrainShape;
use vsrlab_brain::Controller;
use vsrlab_field::FieldError;
use vsrlab_physics::{Vec2, World, WorldBuilder};

/// Grid cell (x, y) of each voxel, grid order (fixed).
pub const CELLS: Channel = Channel::traced("cells");
/// The lidar rays: (voxel, direction relative to the voxel's angle, range) each (fixed).
pub const RAYS: Channel = Channel::traced("rays");
/// Lidar distances, one per ray, per step.
pub const LIDAR: Channel = Channel::replayed("lidar", 1e-2).single();
/// Each voxel's angle (radians), per step; replays keep it for robots with lidars, whose rays are
/// drawn from it.
pub const ANGLE: Channel = Channel::traced("angle");
const ANGLE_FOR_LIDAR: Channel = Channel::replayed("angle", 1e-3);

/// Collision group of the robot (touch sensing and self-collision).
const ROBOT_GROUP: u32 = 1;

impl Robot for RobotSpec {
    fn footprint(&self) -> Vec<Vec2> {
        let l = self.voxel_params().side_length;
        self.body
            .voxels()
            .map(|(x, y)| Vec2::new((x as f64 + 0.5) * l, y as f64 * l))
            .collect()
    }

    fn assemble(&self, builder: &mut WorldBuilder, origin: Vec2, seed: u64) -> Result<Box<dyn Agent>, EpisodeError> {
        let params = self.voxel_params();
        params.validate()?;
        let vsr = Vsr::assemble(builder, &self.body, &params, origin, ROBOT_GROUP);
        let sensors = SensorSuite::for_preset(&self.sensors, &self.body, seed, self.preset)
            .map_err(|e| FieldError::new("sensors", e.to_string()).at("robot"))?;
        let per_voxel: Vec<usize> = (0..self.body.voxel_count())
            .map(|v| sensors.readings_per_voxel(v))
            .collect();
        let mut brain = self
            .brain
            .build(&BrainShape::grid(&self.body, &per_voxel))
            .map_err(|e| FieldError::from(e).at("robot"))?;
        brain.reset();
        Ok(Box::new(VoxelAgent::new(vsr, sensors, brain)))
    }

    fn summary(&self) -> Option<BodySummary> {
        Some(BodySummary::of_grid(&self.body))
    }

    fn description(&self) -> Option<&dyn crate::kinds::RobotDescription> {
        Some(self)
    }
}

/// A voxel robot in a world: body, sensors, brain and the buffers they share each step.
pub struct VoxelAgent {
    vsr: Vsr,
    sensors: SensorSuite,
    brain: Box<dyn Controller>,
    states: Vec<VoxelState>,
    readings: Vec<f64>,
    actuations: Vec<f64>,
    /// Broken voxels: their actuation stays 0 (empty until damage happens).
    broken: Vec<bool>,
    /// Domain of every reading, for scaling recorded readings to [0, 1] (filled by `describe`).
    domains: Vec<(f64, f64)>,
    /// Whether any voxel has a lidar (filled by `describe`).
    has_lidar: bool,
}

impl VoxelAgent {
    /// Wires a body, its sensors and a brain built for them.
    pub fn new(vsr: Vsr, sensors: SensorSuite, brain: Box<dyn Controller>) -> Self {
        let n = vsr.voxel_count();
        let readings = vec![0.0; sensors.total_readings()];
        VoxelAgent {
            vsr,
            sensors,
            brain,
            states: vec![VoxelState::default(); n],
            readings,
            actuations: vec![0.0; n],
            broken: Vec::new(),
            domains: Vec::new(),
            has_lidar: false,
        }
    }
}

impl VoxelAgent {
    /// Applies the actuations (broken voxels get 0) to the body.
    fn apply(&mut self, world: &mut World) {
        for (a, &broken) in self.actuations.iter_mut().zip(&self.broken) {
            if broken {
                *a = 0.0;
            }
        }
        self.vsr.actuate(world, &self.actuations);
    }
}

impl Agent for VoxelAgent {
    fn body(&self) -> &dyn Body {
        &self.vsr
    }

    fn act(&mut self, world: &mut World, t: f64) {
        self.sense(world, t);
        self.brain.control(t, &self.readings, &mut self.actuations);
        self.apply(world);
    }

    fn sense(&mut self, world: &World, t: f64) {
        for (i, s) in self.states.iter_mut().enumerate() {
            *s = self.vsr.unit_state(world, i);
        }
        self.sensors.sense(world, &self.states, t, &mut self.readings);
    }

    fn readings(&self) -> &[f64] {
        &self.readings
    }

    fn action_count(&self) -> usize {
        self.actuations.len()
    }

    fn actuate(&mut self, world: &mut World, actions: &[f64]) {
        self.actuations.copy_from_slice(actions);
        self.apply(world);
    }

    fn break_actuators(&mut self, broken: &[bool]) -> Result<(), EpisodeError> {
        if broken.len() != self.actuations.len() {
            return Err(EpisodeError::Field(FieldError::new(
                "task.damage",
                format!("{} flags for a body of {} voxels", broken.len(), self.actuations.len()),
            )));
        }
        self.broken = broken.to_vec();
        Ok(())
    }

    fn brain(&self) -> Option<&dyn Controller> {
        Some(self.brain.as_ref())
    }

    fn describe(&mut self, trace: &mut Trace) {
        trace.side_length = self.vsr.params().side_length;
        let cells: Vec<f64> = self
            .vsr
            .voxels()
            .iter()
            .flat_map(|v| [v.cell.0 as f64, v.cell.1 as f64])
            .collect();
        trace.fixed(&CELLS, 2, &cells);
        let mut per_unit = Vec::new();
        let mut rays = Vec::new();
        for v in 0..self.vsr.voxel_count() {
            per_unit.push(self.sensors.readings_per_voxel(v) as f64);
            self.domains.extend(self.sensors.domains(v));
            for ray in self.sensors.lidar_rays(v) {
                rays.extend([v as f64, ray.relative_angle, ray.range]);
            }
        }
        trace.fixed(&READINGS_PER_UNIT, 1, &per_unit);
        self.has_lidar = !rays.is_empty();
        if self.has_lidar {
            trace.fixed(&RAYS, 3, &rays);
        }
    }

    fn record(&self, trace: &mut Trace) {
        trace.step_from(&AREA_RATIO, &mut self.states.iter().map(|s| s.area_ratio));
        let angle = if self.has_lidar { &ANGLE_FOR_LIDAR } else { &ANGLE };
        trace.step_from(angle, &mut self.states.iter().map(|s| s.angle));
        trace.step_from(&TOUCH, &mut self.states.iter().map(|s| f64::from(u8::from(s.touching))));
        trace.step(&ACTUATION, &self.actuations);
        let scaled = self.readings.iter().zip(&self.domains).map(|(r, (lo, hi))| {
            let span = hi - lo;
            let v = if span > 0.0 { (r - lo) / span } else { 0.0 };
            v.clamp(0.0, 1.0)
        });
        trace.step_from(&READINGS, &mut scaled.into_iter());
        if self.has_lidar {
            let distances =
                (0..self.states.len()).flat_map(|v| self.sensors.lidar_rays(v).into_iter().map(|ray| ray.distance));
            trace.step_from(&LIDAR, &mut distances.into_iter());
        }
    }
}
