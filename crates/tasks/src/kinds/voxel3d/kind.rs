//! The 3D voxel robot's registry entry: its command-line short form (`3d:BODY`, with `--sensors`
//! and `--brain`), its robot-file form (`{"format", "note", "voxel3d": {"body", "sensors",
//! "brain"}}`) and its `[representation] body` table (`{ kind = "voxel3d", body = "quadruped" }`:
//! a fixed body, the genotype is the brain's parameters).

use super::robot::Voxel3dRobot;
use super::sensors::DEFAULT_SENSORS;
use crate::body_part::BodyPart;
use crate::files::{self, FileError, ROBOT_FORMAT};
use crate::fixed_body::{brain_parameters_on, FixedBody};
use crate::kinds::voxel::short_forms::{RobotArgsError, RobotPart, RANDOM_BRAIN_SEED};
use crate::kinds::{AnyRobot, RobotArgs, RobotDescription, RobotKind};
use serde::{Deserialize, Serialize};
use vsrlab_brain::BrainSpec;
use vsrlab_field::FieldError;

/// The 3D voxel robot's registry entry.
pub const KIND: RobotKind = RobotKind {
    name: "voxel3d",
    file_keys: &["voxel3d"],
    body_usage: "3d:<shape (quadruped, cube-2, worm, box-WxHxD) or layers bottom first joined by |, rows by />",
    claims_body: |body| body.starts_with("3d:"),
    from_short_forms,
    from_file,
    body_tables: &["voxel3d"],
    physics: vsrlab_physics::WorldSettings::default,
    foreign_formats: &[],
    decode_body,
};

/// The default brain: every voxel on the same sine, its phase travelling along x (an open-loop
/// gait with no parameters).
pub const DEFAULT_BRAIN: &str = "phase";

fn from_short_forms(args: &RobotArgs) -> Result<AnyRobot, RobotArgsError> {
    let kind = |part, message: String| RobotArgsError::Kind { part, message };
    super::super::refuse_preset(args, "a 3D voxel's constants are Voxelyze's (docs/voxels3d.md)")?;
    let mut robot = Voxel3dRobot {
        body: args.body.strip_prefix("3d:").unwrap_or(args.body).to_string(),
        sensors: args.sensors.unwrap_or(DEFAULT_SENSORS).to_string(),
        brain: BrainSpec::parse(args.brain.unwrap_or(DEFAULT_BRAIN)).map_err(RobotArgsError::Brain)?,
    };
    robot
        .grid()
        .map_err(|e| kind(RobotPart::Body, e.at("robot").to_string()))?;
    robot
        .sensor_list()
        .map_err(|e| kind(RobotPart::Sensors, e.at("robot").to_string()))?;
    let shape = robot
        .brain_shape()
        .map_err(|e| kind(RobotPart::Body, e.at("robot").to_string()))?;
    let count = robot.brain.parameter_count(&shape).map_err(RobotArgsError::Brain)?;
    if count > 0 && robot.brain.parameters().is_empty() {
        robot.brain = robot
            .brain
            .with_random_parameters(RANDOM_BRAIN_SEED, &shape)
            .map_err(RobotArgsError::Brain)?;
    }
    Ok(AnyRobot::new(robot))
}

/// On-disk form of a 3D voxel robot.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Voxel3dFile {
    format: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    note: Option<String>,
    voxel3d: Voxel3dRobot,
}

/// Parses and validates a 3D robot file; errors name the file and the field.
fn from_file(text: &str, origin: &str) -> Result<AnyRobot, FileError> {
    let file: Voxel3dFile = files::parse_json(text, origin)?;
    files::check_format(&file.format, origin)?;
    file.voxel3d.validate().map_err(|e| FileError::Invalid {
        path: origin.to_string(),
        msg: e.at("voxel3d").to_string(),
    })?;
    Ok(AnyRobot::new(file.voxel3d))
}

impl RobotDescription for Voxel3dRobot {
    fn kind(&self) -> &'static RobotKind {
        &KIND
    }

    fn brain(&self) -> &BrainSpec {
        &self.brain
    }

    fn to_json(&self, note: Option<&str>) -> String {
        let file = Voxel3dFile {
            format: ROBOT_FORMAT.to_string(),
            note: note.map(str::to_string),
            voxel3d: self.clone(),
        };
        serde_json::to_string_pretty(&file).expect("3D robots always serialise")
    }

    fn body_details(&self, actuators: usize) -> String {
        match self.grid() {
            Ok(g) => {
                let [w, h, d] = g.extent();
                format!("3D grid {w}×{h}×{d}, {} voxels, {actuators} actuated", g.voxel_count())
            }
            Err(e) => e.to_string(),
        }
    }

    fn sensors_label(&self) -> String {
        self.sensors.clone()
    }

    fn preset_label(&self) -> String {
        "voxcraft".to_string()
    }

    fn size(&self) -> usize {
        self.grid().map_or(0, |g| g.voxel_count())
    }

    fn label(&self) -> String {
        format!(
            "voxel3d {} sensors={} brain={:?}",
            self.body,
            self.sensors,
            self.brain.kind()
        )
    }

    fn clone_box(&self) -> Box<dyn RobotDescription> {
        Box::new(self.clone())
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

/// A 3D body in an experiment file: `{ kind = "voxel3d", body = "…", sensors = "…" }`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Voxel3dTable {
    /// Always `voxel3d`.
    pub kind: String,
    /// The body (shape name or layers).
    pub body: String,
    /// The sensors on every voxel (default `cpg,touch,floor,vy,vx`).
    #[serde(default = "default_sensors")]
    pub sensors: String,
}

fn default_sensors() -> String {
    DEFAULT_SENSORS.to_string()
}

/// Reads a 3D body table; the error's path is relative to the table.
fn decode_body(value: serde_json::Value) -> Result<BodyPart, FieldError> {
    let table: Voxel3dTable = crate::registry::decode(value)?;
    let robot = table.robot_with(BrainSpec::parse(DEFAULT_BRAIN).map_err(FieldError::from)?);
    robot.grid()?;
    robot.sensor_list()?;
    Ok(BodyPart::new(table))
}

impl Voxel3dTable {
    fn robot_with(&self, brain: BrainSpec) -> Voxel3dRobot {
        Voxel3dRobot {
            body: self.body.clone(),
            sensors: self.sensors.clone(),
            brain,
        }
    }
}

impl FixedBody for Voxel3dTable {
    fn robot_kind(&self) -> &'static RobotKind {
        &KIND
    }

    fn sensors_refused(&self) -> &'static str {
        "a 3D body's sensors go in its body table (`sensors = \"cpg,touch\"`); remove this field"
    }

    fn brain_parameters(&self, brain: &BrainSpec) -> Result<usize, FieldError> {
        brain_parameters_on(self.robot_with(brain.clone()).brain_shape(), brain)
    }

    fn robot_of(&self, brain: BrainSpec) -> AnyRobot {
        AnyRobot::new(self.robot_with(brain))
    }

    fn body_units(&self) -> usize {
        super::BodyGrid3::parse(&self.body).map_or(0, |g| g.voxel_count())
    }
}
