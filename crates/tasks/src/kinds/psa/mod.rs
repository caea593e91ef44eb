//! The pressure-based soft agent (thesis ch. 6): a membrane of masses and springs around a
//! pressurised gas. Its robot-file form (`{"format", "note", "psa": {…}}`), its command-line
//! short form (`psa[:small|medium|large]`) and its registry entry.

pub mod body;
pub mod inflation;
pub mod robot;

use super::{AnyRobot, RobotArgs, RobotDescription, RobotKind};
use crate::files::{self, FileError, ROBOT_FORMAT};
use crate::kinds::voxel::short_forms::{RobotArgsError, RobotPart};
use robot::PsaRobot;
use serde::{Deserialize, Serialize};

/// The PSA's registry entry.
pub const KIND: RobotKind = RobotKind {
    name: "psa",
    file_keys: &["psa"],
    body_usage: "psa[:small|medium|large]",
    claims_body: |body| body == "psa" || body.starts_with("psa:"),
    from_short_forms,
    from_file,
    body_tables: &["psa"],
    physics: inflation::psa_physics,
    foreign_formats: &[],
    decode_body: body::decode,
};

fn from_short_forms(args: &RobotArgs) -> Result<AnyRobot, RobotArgsError> {
    if args.sensors.is_some() {
        return Err(RobotArgsError::Kind {
            part: RobotPart::Sensors,
            message: "a PSA's sensors are fixed (docs/psa.md); leave sensors out".into(),
        });
    }
    super::refuse_preset(args, "a PSA's constants are in its body table (docs/psa.md)")?;
    PsaRobot::from_short_forms(args.body, args.brain.unwrap_or("heads")).map(AnyRobot::new)
}

/// On-disk form of a pressure-based soft agent.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct PsaFile {
    format: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    note: Option<String>,
    psa: PsaRobot,
}

/// Serialises a PSA to pretty JSON: like a voxel robot file, with the robot under `psa`.
pub fn psa_to_json(robot: &PsaRobot, note: Option<&str>) -> String {
    let file = PsaFile {
        format: ROBOT_FORMAT.to_string(),
        note: note.map(str::to_string),
        psa: robot.clone(),
    };
    serde_json::to_string_pretty(&file).expect("PSA descriptions always serialise")
}

/// Parses and validates a PSA robot file.
fn from_file(text: &str, origin: &str) -> Result<AnyRobot, FileError> {
    let file: PsaFile = files::parse_json(text, origin)?;
    files::check_format(&file.format, origin)?;
    file.psa.validate().map_err(|e| FileError::Invalid {
        path: origin.to_string(),
        msg: e.at("robot").to_string(),
    })?;
    Ok(AnyRobot::new(file.psa))
}

impl RobotDescription for PsaRobot {
    fn kind(&self) -> &'static RobotKind {
        &KIND
    }

    fn brain(&self) -> &vsrlab_brain::BrainSpec {
        &self.brain
    }

    fn to_json(&self, note: Option<&str>) -> String {
        psa_to_json(self, note)
    }

    fn body_details(&self, actuators: usize) -> String {
        let p = &self.body.params;
        format!("{} masses, radius {}, {actuators} actuators", p.masses, p.radius)
    }

    fn sensors_label(&self) -> String {
        format!("psa ({} readings)", self.body.params.reading_count())
    }

    fn preset_label(&self) -> String {
        "psa".to_string()
    }

    fn size(&self) -> usize {
        self.body.params.masses
    }

    fn label(&self) -> String {
        format!(
            "psa with {} masses, brain={:?}",
            self.body.params.masses,
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
