//! The 2D-VSR-Sim voxel robot (thesis ch. 2–5): a grid of soft voxels with sensors and a brain.
//! Its robot-file form (`{"format", "note", "robot": {…}}`), its command-line short forms and its
//! registry entry.

pub mod agent;
pub mod body;
pub mod robot;
pub mod short_forms;

use super::{AnyRobot, RobotArgs, RobotDescription, RobotKind};
use crate::files::{self, FileError, ROBOT_FORMAT};
use robot::RobotSpec;
use serde::{Deserialize, Serialize};
use short_forms::{RobotArgsError, DEFAULT_SENSORS};
use std::path::Path;

/// The voxel robot's registry entry.
pub const KIND: RobotKind = RobotKind {
    name: "voxel",
    file_keys: &["robot"],
    body_usage:
        "a shape (worm-WxH, biped-WxH, comb-WxH, box-WxH, tripod-WxH, t-WxH, ball-D) or a text grid of '#' and '.'",
    claims_body: |_| true,
    from_short_forms,
    from_file: |text, origin| robot_from_json(text, origin).map(AnyRobot::new),
    body_tables: &["direct", "gmm"],
    physics: || crate::Locomotion::default().physics,
    foreign_formats: &[],
    decode_body: body::decode,
};

fn from_short_forms(args: &RobotArgs) -> Result<AnyRobot, RobotArgsError> {
    RobotSpec::from_short_forms(
        args.body,
        args.preset.unwrap_or("2021"),
        args.sensors.unwrap_or(DEFAULT_SENSORS),
        args.brain.unwrap_or("phase"),
    )
    .map(AnyRobot::new)
}

/// On-disk form of a voxel robot.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RobotFile {
    format: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    note: Option<String>,
    robot: RobotSpec,
}

/// Serialises a robot to pretty JSON (floats written in shortest round-trip form).
pub fn robot_to_json(robot: &RobotSpec, note: Option<&str>) -> String {
    let file = RobotFile {
        format: ROBOT_FORMAT.to_string(),
        note: note.map(str::to_string),
        robot: robot.clone(),
    };
    serde_json::to_string_pretty(&file).expect("robot specs always serialise")
}

/// Parses and validates a voxel robot from JSON text; `origin` names the source in errors. A
/// robot file of another kind is refused, naming its kind.
pub fn robot_from_json(text: &str, origin: &str) -> Result<RobotSpec, FileError> {
    let invalid = |msg: String| FileError::Invalid {
        path: origin.to_string(),
        msg,
    };
    let value = serde_json::from_str::<serde_json::Value>(text).unwrap_or_default();
    if let Some(other) = super::kind_of_file(&value).filter(|k| k.name != KIND.name) {
        return Err(invalid(format!(
            "this is a {} robot (field '{}'); this command reads voxel robots only",
            other.name, other.file_keys[0]
        )));
    }
    let file: RobotFile = files::parse_json(text, origin)?;
    files::check_format(&file.format, origin)?;
    file.robot.validate().map_err(|e| invalid(e.to_string()))?;
    Ok(file.robot)
}

/// Saves a voxel robot file atomically.
pub fn save_robot(path: &Path, robot: &RobotSpec, note: Option<&str>) -> Result<(), FileError> {
    files::write_text(path, &robot_to_json(robot, note))
}

/// Loads and validates a voxel robot file.
pub fn load_robot(path: &Path) -> Result<RobotSpec, FileError> {
    robot_from_json(&files::read_text(path)?, &path.display().to_string())
}

impl RobotDescription for RobotSpec {
    fn kind(&self) -> &'static RobotKind {
        &KIND
    }

    fn morphology(&self) -> Option<vsrlab_body::MorphologyDescriptors> {
        Some(vsrlab_body::MorphologyDescriptors::of(&self.body))
    }

    fn brain(&self) -> &vsrlab_brain::BrainSpec {
        &self.brain
    }

    fn to_json(&self, note: Option<&str>) -> String {
        robot_to_json(self, note)
    }

    fn body_details(&self, actuators: usize) -> String {
        format!("{actuators} voxels, preset {}", self.preset)
    }

    fn sensors_label(&self) -> String {
        self.sensors.to_string()
    }

    fn preset_label(&self) -> String {
        self.preset.to_string()
    }

    fn size(&self) -> usize {
        self.body.voxel_count()
    }

    fn label(&self) -> String {
        format!(
            "body={:?}, brain={:?}, sensors={:?}, preset={:?}",
            self.body.to_rows().join("/"),
            self.brain.kind(),
            self.sensors.to_string(),
            self.preset.to_string()
        )
    }

    fn clone_box(&self) -> Box<dyn RobotDescription> {
        Box::new(self.clone())
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}
