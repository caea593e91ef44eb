//! The PSA's `[representation] body` form: `{ kind = "psa", size = …, … }` (no body genes; the
//! genotype is the brain's parameters).

use super::robot::PsaRobot;
use crate::body_part::BodyPart;
use crate::fixed_body::FixedBody;
use crate::kinds::{AnyRobot, RobotKind};
use serde::Serialize;
use vsrlab_body::psa::PsaBody;
use vsrlab_brain::BrainSpec;
use vsrlab_field::FieldError;

/// A PSA body in an experiment file: `{ kind = "psa", size = …, … }` (see [`PsaBody`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PsaTable {
    /// Always `psa`.
    pub kind: PsaKind,
    /// Size and constants.
    #[serde(flatten)]
    pub body: PsaBody,
}

/// The `kind` tag of a PSA body table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PsaKind {
    /// A pressure-based soft agent.
    Psa,
}

/// Reads a PSA body table; the error's path is relative to the table.
pub(crate) fn decode(value: serde_json::Value) -> Result<BodyPart, FieldError> {
    let body = PsaBody::from_table(value)?;
    Ok(BodyPart::new(PsaTable {
        kind: PsaKind::Psa,
        body,
    }))
}

impl PsaTable {
    fn robot_with(&self, brain: BrainSpec) -> PsaRobot {
        PsaRobot {
            body: self.body.clone(),
            brain,
        }
    }
}

impl FixedBody for PsaTable {
    fn robot_kind(&self) -> &'static RobotKind {
        &super::KIND
    }

    fn sensors_refused(&self) -> &'static str {
        "a PSA has its own sensors (3 per mass and 3 for the whole); remove this field"
    }

    fn brain_parameters(&self, brain: &BrainSpec) -> Result<usize, FieldError> {
        let robot = self.robot_with(brain.clone());
        robot.validate_body()?;
        robot.brain_parameters()
    }

    fn robot_of(&self, brain: BrainSpec) -> AnyRobot {
        AnyRobot::new(self.robot_with(brain))
    }

    fn body_units(&self) -> usize {
        self.body.params.masses + 1
    }

    fn extra_episode_bytes(&self, dt: f64) -> u128 {
        let params = &self.body.params;
        // the sensors' ring buffer: a window of steps, every reading, 8 bytes each
        let steps = (params.sensor_window / dt).round().max(1.0);
        (steps * params.reading_count() as f64 * 8.0) as u128
    }
}
