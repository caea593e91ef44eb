//! A voxel robot from its short forms, as written on the command line: a body (`biped-4x3` or a
//! text grid such as `###/#.#`), a preset (`2021`), sensors (`uniform-a+vxy+t-0`) and a brain
//! (`phase`, `mlp`, …). A parameterised brain gets seeded random parameters, so that any brain can
//! be simulated or benchmarked without evolving it first.

use crate::kinds::voxel::robot::{RobotError, RobotSpec};
use vsrlab_body::sensors::{SensorConfig, SensorError};
use vsrlab_body::{Morphology, MorphologyError, Preset};
use vsrlab_brain::BrainShape;
use vsrlab_brain::{BrainError, BrainSpec};

/// Default sensors: area ratio, velocity and touch on every voxel (thesis ch. 3), no noise.
pub const DEFAULT_SENSORS: &str = "uniform-a+vxy+t-0";

/// Seed of the random parameters given to a parameterised brain named by its short form.
pub const RANDOM_BRAIN_SEED: u64 = 0;

/// One of the four short forms that describe a robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RobotPart {
    /// The body: a named shape or a text grid.
    Body,
    /// The physical preset.
    Preset,
    /// The sensors on each voxel.
    Sensors,
    /// The brain.
    Brain,
}

impl RobotPart {
    /// The part's name: `body`, `preset`, `sensors` or `brain`.
    pub fn name(self) -> &'static str {
        match self {
            RobotPart::Body => "body",
            RobotPart::Preset => "preset",
            RobotPart::Sensors => "sensors",
            RobotPart::Brain => "brain",
        }
    }
}

impl std::fmt::Display for RobotPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Why short forms do not make a robot; [`RobotArgsError::part`] names the short form at fault.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RobotArgsError {
    /// The body is neither a named shape nor a valid grid.
    #[error("body: {0}")]
    Body(#[source] MorphologyError),
    /// The preset is unknown.
    #[error("preset: {0}")]
    Preset(#[source] vsrlab_field::FieldError),
    /// The sensors' short form is not understood.
    #[error("sensors: {0}")]
    Sensors(#[source] SensorError),
    /// The sensors cannot be placed on this body.
    #[error("sensors: {0}")]
    SensorsOnBody(#[source] RobotError),
    /// The brain's short form is not understood, or it does not fit the body and sensors.
    #[error("brain: {0}")]
    Brain(#[source] BrainError),
    /// A robot kind refused a part (a PSA given sensors, an unknown PSA size).
    #[error("{part}: {message}")]
    Kind {
        /// The short form at fault.
        part: RobotPart,
        /// What is wrong.
        message: String,
    },
}

impl RobotArgsError {
    /// The short form at fault.
    pub fn part(&self) -> RobotPart {
        match self {
            RobotArgsError::Body(_) => RobotPart::Body,
            RobotArgsError::Preset(_) => RobotPart::Preset,
            RobotArgsError::Sensors(_) | RobotArgsError::SensorsOnBody(_) => RobotPart::Sensors,
            RobotArgsError::Brain(_) => RobotPart::Brain,
            RobotArgsError::Kind { part, .. } => *part,
        }
    }

    /// What is wrong, without the name of the part.
    pub fn message(&self) -> String {
        match self {
            RobotArgsError::Body(e) => e.to_string(),
            RobotArgsError::Preset(e) => e.to_string(),
            RobotArgsError::Sensors(e) => e.to_string(),
            RobotArgsError::SensorsOnBody(e) => e.to_string(),
            RobotArgsError::Brain(e) => e.to_string(),
            RobotArgsError::Kind { message, .. } => message.clone(),
        }
    }
}

impl RobotSpec {
    /// The voxel robot described by four short forms (body, preset, sensors, brain), with the
    /// preset's voxel constants. A brain with parameters and none given gets
    /// [`BrainSpec::with_random_parameters`] drawn with seed [`RANDOM_BRAIN_SEED`].
    pub fn from_short_forms(body: &str, preset: &str, sensors: &str, brain: &str) -> Result<RobotSpec, RobotArgsError> {
        let robot = RobotSpec {
            body: Morphology::parse(body).map_err(RobotArgsError::Body)?,
            preset: preset.parse::<Preset>().map_err(RobotArgsError::Preset)?,
            voxel: None,
            sensors: SensorConfig::parse(sensors).map_err(RobotArgsError::Sensors)?,
            brain: BrainSpec::parse(brain).map_err(RobotArgsError::Brain)?,
        };
        robot.with_random_brain_parameters()
    }

    /// The same robot, its brain filled with seeded random parameters if it needs some and has
    /// none.
    fn with_random_brain_parameters(mut self) -> Result<RobotSpec, RobotArgsError> {
        let per_voxel = self.readings_per_voxel().map_err(RobotArgsError::SensorsOnBody)?;
        let count = self
            .brain
            .parameter_count(&BrainShape::grid(&self.body, &per_voxel))
            .map_err(RobotArgsError::Brain)?;
        if count > 0 && self.brain.parameters().is_empty() {
            self.brain = self
                .brain
                .with_random_parameters(RANDOM_BRAIN_SEED, &BrainShape::grid(&self.body, &per_voxel))
                .map_err(RobotArgsError::Brain)?;
        }
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parameterised_brain_gets_seeded_random_parameters() {
        let a = RobotSpec::from_short_forms("biped-4x3", "2021", DEFAULT_SENSORS, "mlp").unwrap();
        let b = RobotSpec::from_short_forms("biped-4x3", "2021", DEFAULT_SENSORS, "mlp").unwrap();
        assert!(!a.brain.parameters().is_empty());
        assert_eq!(a, b);
        assert!(a.validate().is_ok());
    }

    #[test]
    fn a_parameterless_brain_stays_as_it_is() {
        let robot = RobotSpec::from_short_forms("worm-10x4", "2022", "empty", "phase").unwrap();
        assert!(robot.brain.parameters().is_empty());
        assert_eq!(robot.preset, Preset::Y2022);
    }

    #[test]
    fn errors_name_the_part_at_fault() {
        let cases = [
            (("#.#", "2021", DEFAULT_SENSORS, "phase"), RobotPart::Body),
            (("biped-4x3", "1999", DEFAULT_SENSORS, "phase"), RobotPart::Preset),
            (("biped-4x3", "2021", "x", "phase"), RobotPart::Sensors),
            (("biped-4x3", "2021", DEFAULT_SENSORS, "nope"), RobotPart::Brain),
        ];
        for ((body, preset, sensors, brain), part) in cases {
            let error = RobotSpec::from_short_forms(body, preset, sensors, brain).unwrap_err();
            assert_eq!(error.part(), part);
            assert_eq!(error.to_string(), format!("{part}: {}", error.message()));
        }
    }
}
