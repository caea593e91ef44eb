//! A robot description: body, physical preset, sensors and brain.

use serde::{Deserialize, Serialize};
use vsrlab_body::sensors::{SensorConfig, SensorSuite};
use vsrlab_body::{Morphology, Preset, VoxelParams};
use vsrlab_brain::BrainShape;
use vsrlab_brain::BrainSpec;
use vsrlab_field::FieldError;

/// Everything needed to build a robot in a world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSpec {
    /// Which cells hold voxels.
    pub body: Morphology,
    /// Named physical preset ("2021" or "2022").
    #[serde(default)]
    pub preset: Preset,
    /// Full voxel constants; when absent, the preset's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub voxel: Option<VoxelParams>,
    /// Sensors on each voxel.
    pub sensors: SensorConfig,
    /// The controller.
    pub brain: BrainSpec,
}

impl RobotSpec {
    /// The voxel constants in force: explicit ones, or the preset's.
    pub fn voxel_params(&self) -> VoxelParams {
        self.voxel.clone().unwrap_or_else(|| VoxelParams::preset(self.preset))
    }
}

/// Why a robot description does not hold together: the field and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("robot{}{message}", if field.is_empty() { ": ".to_string() } else { format!(".{field}: ") })]
pub struct RobotError {
    /// The offending field of the robot (`sensors`, `brain.weights`, `voxel.…`).
    pub field: String,
    /// What is wrong.
    pub message: String,
}

impl RobotError {
    /// An error on `field`.
    fn at(field: &str, message: impl std::fmt::Display) -> Self {
        RobotError {
            field: field.to_string(),
            message: message.to_string(),
        }
    }
}

impl RobotSpec {
    /// Readings per voxel (grid order) that this robot's sensors produce.
    pub fn readings_per_voxel(&self) -> Result<Vec<usize>, RobotError> {
        let sensors = SensorSuite::new(&self.sensors, &self.body, 0).map_err(|e| RobotError::at("sensors", e))?;
        Ok((0..self.body.voxel_count())
            .map(|v| sensors.readings_per_voxel(v))
            .collect())
    }

    /// Checks that body, constants, sensors and brain fit together; the error names the field.
    pub fn validate(&self) -> Result<(), RobotError> {
        self.voxel_params().validate()?;
        let per_voxel = self.readings_per_voxel()?;
        self.brain
            .build(&BrainShape::grid(&self.body, &per_voxel))
            .map(|_| ())
            .map_err(|e| RobotError::from(FieldError::from(e)))
    }
}

impl From<FieldError> for RobotError {
    /// An error on a field of the robot (`voxel.side_length`, `brain.hidden`), shown as
    /// `robot.<field>: <message>`.
    fn from(e: FieldError) -> Self {
        RobotError {
            field: e.path,
            message: e.message,
        }
    }
}
