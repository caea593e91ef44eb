//! [`Voxel3dRobot`]: a 3D voxel body with sensors on every voxel and a brain over the 3D grid
//! layout (each voxel's unit has six face neighbours), as the robot kinds' registry sees it.

use super::grid::BodyGrid3;
use super::sensors::{Sensor3, DEFAULT_SENSORS};
use crate::agent::{Agent, Robot};
use crate::body_summary::BodySummary;
use crate::episode::EpisodeError;
use crate::kinds::RobotDescription;
use serde::{Deserialize, Serialize};
use vsrlab_brain::{BrainShape, BrainSpec};
use vsrlab_field::FieldError;
use vsrlab_physics::{Vec2, WorldBuilder};

/// A 3D voxel robot: its body grid (text form or shape name), its sensors and its brain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Voxel3dRobot {
    /// The body: layers bottom first joined by `|`, rows by `/` (`#` voxel, `.` empty), or a
    /// shape (`quadruped`, `box-4x3x2`, …).
    pub body: String,
    /// The sensors on every voxel (default: the affordance study's `cpg,touch,floor,vy,vx`).
    #[serde(default = "default_sensors")]
    pub sensors: String,
    /// The brain: every voxel's readings in, one actuation in [-1, 1] per voxel out.
    pub brain: BrainSpec,
}

fn default_sensors() -> String {
    DEFAULT_SENSORS.to_string()
}

impl Voxel3dRobot {
    /// The body grid; the error names the field relative to the robot (`body`).
    pub fn grid(&self) -> Result<BodyGrid3, FieldError> {
        BodyGrid3::parse(&self.body).map_err(|e| e.at("body"))
    }

    /// The sensors; the error names the field relative to the robot (`sensors…`).
    pub fn sensor_list(&self) -> Result<Vec<Sensor3>, FieldError> {
        Sensor3::parse_list(&self.sensors).map_err(|e| e.at("sensors"))
    }

    /// The brain's view: one unit per voxel on the 3D grid layout, every voxel with all the sensors.
    pub fn brain_shape(&self) -> Result<BrainShape, FieldError> {
        let grid = self.grid()?;
        let per_voxel = self.sensor_list()?.len();
        Ok(BrainShape::new(grid.layout(), vec![per_voxel; grid.voxel_count()]))
    }

    /// Checks body, sensors and that the brain fits them; paths are relative to the robot.
    pub fn validate(&self) -> Result<(), FieldError> {
        let shape = self.brain_shape()?;
        self.brain
            .parameter_count(&shape)
            .map_err(|e| FieldError::from(e).at("brain"))?;
        Ok(())
    }
}

impl Robot for Voxel3dRobot {
    fn footprint(&self) -> Vec<Vec2> {
        Vec::new()
    }

    /// 3D robots live on the 3D engine: only 3D tasks run them.
    fn assemble(&self, _builder: &mut WorldBuilder, _origin: Vec2, _seed: u64) -> Result<Box<dyn Agent>, EpisodeError> {
        Err(EpisodeError::Field(FieldError::new(
            "task.kind",
            "a 3D voxel robot runs in a 3D task (locomotion3d), not on the 2D engine",
        )))
    }

    fn summary(&self) -> Option<BodySummary> {
        let grid = self.grid().ok()?;
        let [w, h, d] = grid.extent();
        Some(BodySummary {
            units: grid.voxel_count(),
            text: grid.to_string(),
            descriptors: vec![
                ("voxels", grid.voxel_count() as f64),
                ("width", w as f64),
                ("depth", h as f64),
                ("height", d as f64),
            ],
        })
    }

    fn description(&self) -> Option<&dyn RobotDescription> {
        Some(self)
    }
}

/// Copies of `base`, each with its brain's parameters drawn from one of `seeds` (tests of batches
/// of same-shape robots).
#[cfg(test)]
pub(crate) fn with_random_brains(base: &Voxel3dRobot, seeds: std::ops::Range<u64>) -> Vec<Voxel3dRobot> {
    let shape = base.brain_shape().unwrap();
    seeds
        .map(|seed| Voxel3dRobot {
            brain: base.brain.with_random_parameters(seed, &shape).unwrap(),
            ..base.clone()
        })
        .collect()
}
