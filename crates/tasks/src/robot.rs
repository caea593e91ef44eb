//! A robot description: body, physical preset, sensors and brain.

use serde::{Deserialize, Serialize};
use vsrlab_body::sensors::SensorConfig;
use vsrlab_body::{Morphology, Preset, VoxelParams};
use vsrlab_brain::BrainSpec;

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
