//! Robot kinds: what a robot can be (a 2D-VSR-Sim voxel robot, a pressure-based soft agent, …).
//!
//! Each kind lives in its own folder and has one entry in [`ROBOT_KINDS`]: its name, its
//! command-line body form, its robot-file form and the `kind` tags of its `[representation] body`
//! tables. Its robots implement [`RobotDescription`] (a [`Robot`] that can also be saved and
//! summarised), so that the command line, the benchmark and the Python package hold an
//! [`AnyRobot`] without knowing its kind.
//!
//! Adding a kind: a folder `kinds/<name>/` with the robot type (implementing [`Robot`] and
//! [`RobotDescription`]), its agent, and a `pub const KIND: RobotKind`; one line in
//! [`ROBOT_KINDS`] and one `pub mod` line here.

pub mod evogym;
pub mod psa;
pub mod voxel;
pub mod voxel3d;

use crate::agent::Robot;
use crate::files::FileError;
use crate::kinds::voxel::short_forms::{RobotArgsError, RobotPart};
use std::any::Any;
use std::fmt::Debug;
use vsrlab_brain::BrainSpec;

/// Every robot kind. The first whose [`RobotKind::claims_body`] accepts a command-line body
/// builds it, so the voxel robot, whose bodies are any shape name or text grid, comes last.
pub const ROBOT_KINDS: &[RobotKind] = &[psa::KIND, evogym::KIND, voxel3d::KIND, voxel::KIND];

/// One registered robot kind.
pub struct RobotKind {
    /// The kind's name (`voxel`, `psa`): what the Python package's `Robot.kind` says.
    pub name: &'static str,
    /// The top-level keys that mark a robot file as this kind's: the first is the key under which
    /// its own robot files hold the robot (`robot`, `psa`, `evogym`); others mark files of another
    /// program that the kind reads too (EvoGym's `objects`).
    pub file_keys: &'static [&'static str],
    /// The command-line body form, for help and error messages.
    pub body_usage: &'static str,
    /// Whether a command-line body names a robot of this kind.
    pub claims_body: fn(&str) -> bool,
    /// A robot from command-line short forms.
    pub from_short_forms: fn(&RobotArgs) -> Result<AnyRobot, RobotArgsError>,
    /// A robot from a robot file's text (validated; errors name the field); `origin` names the
    /// source.
    pub from_file: fn(&str, &str) -> Result<AnyRobot, FileError>,
    /// The `kind` tags of this kind's `[representation] body` tables.
    pub body_tables: &'static [&'static str],
    /// The world settings its published models were run with (time step, gravity, solver).
    pub physics: fn() -> vsrlab_physics::WorldSettings,
    /// Robot files of other programs this kind reads and writes (EvoGym's `.npz` and JSON
    /// robots), by name.
    pub foreign_formats: &'static [ForeignFormat],
    /// Reads one of its `[representation] body` forms (a table with one of its
    /// [`RobotKind::body_tables`] tags; the default kind also gets every form that is not a
    /// table); the error's path is relative to the body's table (empty: the form as a whole).
    pub decode_body: fn(serde_json::Value) -> Result<crate::BodyPart, vsrlab_field::FieldError>,
}

/// A robot file format of another program: how to recognise, read and write it.
pub struct ForeignFormat {
    /// Its name on the command line (`evogym-npz`).
    pub name: &'static str,
    /// The file extension that selects it when saving (`npz`).
    pub extension: &'static str,
    /// Whether a file's bytes are in this format (binary formats; text formats that a kind's
    /// [`RobotKind::file_keys`] recognise say no).
    pub claims: fn(&[u8]) -> bool,
    /// A robot from the file's bytes (validated; errors name the field); `origin` names the source.
    pub read: fn(&[u8], &str) -> Result<AnyRobot, FileError>,
    /// The robot in this format, or why it cannot be written so (another kind's robot, a brain
    /// the format has no place for is left out and said in `note`).
    pub write: fn(&AnyRobot) -> Result<Vec<u8>, vsrlab_field::FieldError>,
}

/// The command line's description of a robot: a body, and optionally a brain, sensors and a
/// preset (each kind has its defaults, and refuses what it has no use for).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotArgs<'a> {
    /// The body (`biped-4x3`, `###/#.#`, `psa:small`, …).
    pub body: &'a str,
    /// The brain's short form; `None`: the kind's default.
    pub brain: Option<&'a str>,
    /// The sensors' short form; `None`: the kind's default.
    pub sensors: Option<&'a str>,
    /// The physical preset (`2021`, `2022`); `None`: the kind's default. Kinds without presets
    /// refuse one ([`refuse_preset`]) rather than ignore it.
    pub preset: Option<&'a str>,
}

/// The error of a kind that has no presets when the command line gives one: `what` says where
/// its constants are instead.
pub fn refuse_preset(args: &RobotArgs, what: &str) -> Result<(), RobotArgsError> {
    match args.preset {
        None => Ok(()),
        Some(preset) => Err(RobotArgsError::Kind {
            part: RobotPart::Preset,
            message: format!("'{preset}' is a preset of voxel robots; {what}: leave the preset out"),
        }),
    }
}

/// A robot of a registered kind, as robot files and the command line describe it.
pub trait RobotDescription: Robot + Debug {
    /// The kind's registry entry.
    fn kind(&self) -> &'static RobotKind;
    /// The brain.
    fn brain(&self) -> &BrainSpec;
    /// The robot as a robot file (JSON) with an optional note.
    fn to_json(&self, note: Option<&str>) -> String;
    /// What the command line prints after `body NAME`: sizes and constants, given the
    /// number of actuators the episode reported.
    fn body_details(&self, actuators: usize) -> String;
    /// The sensors, as the command line prints them.
    fn sensors_label(&self) -> String;
    /// The physical preset, as the command line prints it.
    fn preset_label(&self) -> String;
    /// The body's size in the units of the speed benchmark (voxels; a PSA's masses).
    fn size(&self) -> usize;
    /// A one-line description (the Python package's `repr`).
    fn label(&self) -> String;
    /// The robot as `task` runs it, when that differs from the robot as described: a kind whose
    /// brain depends on the task (an EvoGym robot's brain sees its task's observation) takes the
    /// task's, for a template brain (no weights) and, when `untrained` (a robot of command-line
    /// short forms, whose weights are drawn at random), for any brain. Default: unchanged.
    fn for_task(&self, _task: &dyn crate::task::Task, _untrained: bool) -> Option<AnyRobot> {
        None
    }
    /// The thesis's morphology descriptors of the body (d_num, d_elong, d_compact: a 2D grid of
    /// cells), for the analyses' tables and figures; `None` (the default) for a kind whose body
    /// they are not defined for.
    fn morphology(&self) -> Option<vsrlab_body::MorphologyDescriptors> {
        None
    }
    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn RobotDescription>;
    /// The robot itself, for code of its own kind.
    fn as_any(&self) -> &dyn Any;
}

/// A robot of any registered kind.
#[derive(Debug)]
pub struct AnyRobot(Box<dyn RobotDescription>);

impl AnyRobot {
    /// The robot as the episode loop takes it.
    pub fn into_robot(self) -> Box<dyn Robot> {
        self.0
    }

    /// Wraps a robot of a registered kind.
    pub fn new(robot: impl RobotDescription + 'static) -> AnyRobot {
        AnyRobot(Box::new(robot))
    }

    /// The robot, for episodes.
    pub fn as_robot(&self) -> &dyn Robot {
        self.0.as_ref()
    }

    /// The robot as its kind sees it (saving, summaries).
    pub fn description(&self) -> &dyn RobotDescription {
        self.0.as_ref()
    }

    /// The kind's registry entry.
    pub fn kind(&self) -> &'static RobotKind {
        self.0.kind()
    }

    /// The brain.
    pub fn brain(&self) -> &BrainSpec {
        self.0.brain()
    }

    /// The robot file's JSON.
    pub fn to_json(&self, note: Option<&str>) -> String {
        self.0.to_json(note)
    }

    /// The robot as a `T`, when it is one.
    pub fn downcast_ref<T: 'static>(&self) -> Option<&T> {
        self.0.as_any().downcast_ref()
    }
}

impl Clone for AnyRobot {
    fn clone(&self) -> Self {
        AnyRobot(self.0.clone_box())
    }
}

impl PartialEq for AnyRobot {
    /// Two robots are equal when they are of the same kind and write the same robot file.
    fn eq(&self, other: &Self) -> bool {
        self.kind().name == other.kind().name && self.to_json(None) == other.to_json(None)
    }
}

/// The robot that command-line short forms describe, of the first kind that claims the body.
pub fn from_short_forms(args: &RobotArgs) -> Result<AnyRobot, RobotArgsError> {
    let kind = ROBOT_KINDS
        .iter()
        .find(|k| (k.claims_body)(args.body))
        .ok_or_else(|| RobotArgsError::Kind {
            part: RobotPart::Body,
            message: format!("'{}' is no robot body: expected {}", args.body, body_usages()),
        })?;
    (kind.from_short_forms)(args)
}

/// Every kind's command-line body form, for messages.
pub fn body_usages() -> String {
    ROBOT_KINDS
        .iter()
        .map(|k| k.body_usage)
        .collect::<Vec<_>>()
        .join(", or ")
}

/// The kind that reads robot files and body forms that name no kind: the last one, the voxel
/// robot, whose body forms are any shape name, text grid or list of rows.
pub fn default_kind() -> &'static RobotKind {
    ROBOT_KINDS.last().expect("at least one robot kind")
}

/// The foreign format named `name`, with its kind.
pub fn foreign_format(name: &str) -> Option<(&'static RobotKind, &'static ForeignFormat)> {
    ROBOT_KINDS
        .iter()
        .flat_map(|k| k.foreign_formats.iter().map(move |f| (k, f)))
        .find(|(_, f)| f.name == name)
}

/// The foreign format whose files start like `bytes`, if any.
pub fn foreign_format_of(bytes: &[u8]) -> Option<&'static ForeignFormat> {
    ROBOT_KINDS
        .iter()
        .flat_map(|k| k.foreign_formats.iter())
        .find(|f| (f.claims)(bytes))
}

/// Every foreign format's name, for messages.
pub fn foreign_format_names() -> Vec<&'static str> {
    ROBOT_KINDS
        .iter()
        .flat_map(|k| k.foreign_formats.iter().map(|f| f.name))
        .collect()
}

/// The kind whose robots robot files hold under `key`, if any.
pub fn kind_of_file(value: &serde_json::Value) -> Option<&'static RobotKind> {
    ROBOT_KINDS
        .iter()
        .find(|k| k.file_keys.iter().any(|key| value.get(key).is_some()))
}

/// The brain itself, or for a template (parameters to fill, none given) the template with
/// seeded random parameters, as the command line gives them: what tasks on their own engines
/// run a robot file's brain with.
pub(crate) fn filled_brain(
    brain: &BrainSpec,
    shape: &vsrlab_brain::BrainShape,
) -> Result<BrainSpec, vsrlab_brain::BrainError> {
    if brain.parameters().is_empty() && brain.parameter_count(shape)? > 0 {
        brain.with_random_parameters(voxel::short_forms::RANDOM_BRAIN_SEED, shape)
    } else {
        Ok(brain.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_file_keys_and_body_tables_are_unique() {
        for (i, a) in ROBOT_KINDS.iter().enumerate() {
            for b in &ROBOT_KINDS[i + 1..] {
                assert_ne!(a.name, b.name);
                assert!(a.file_keys.iter().all(|k| !b.file_keys.contains(k)), "{}", a.name);
                assert!(a.body_tables.iter().all(|t| !b.body_tables.contains(t)), "{}", a.name);
            }
        }
    }

    #[test]
    fn each_body_form_goes_to_its_kind() {
        let cases = [
            ("psa", "psa"),
            ("psa:large", "psa"),
            ("biped-4x3", "voxel"),
            ("##/#.", "voxel"),
        ];
        for (body, kind) in cases {
            let args = RobotArgs {
                body,
                brain: None,
                sensors: None,
                preset: None,
            };
            let robot = from_short_forms(&args).unwrap_or_else(|e| panic!("{body}: {e}"));
            assert_eq!(robot.kind().name, kind, "{body}");
            let copy = robot.clone();
            assert_eq!(copy, robot);
            let again = (robot.kind().from_file)(&robot.to_json(None), "test").unwrap();
            assert_eq!(again, robot, "{body}: the robot file reads back");
        }
    }

    #[test]
    fn a_kind_refuses_what_it_has_no_use_for() {
        let args = RobotArgs {
            body: "psa:small",
            brain: None,
            sensors: Some("uniform-a-0"),
            preset: None,
        };
        let e = from_short_forms(&args).unwrap_err();
        assert_eq!(e.part(), RobotPart::Sensors);
        // a preset, which only voxel robots have, is refused by the others, not ignored
        for body in ["psa:small", "evogym:Walker:3334/3334", "3d:##"] {
            let args = RobotArgs {
                body,
                brain: None,
                sensors: None,
                preset: Some("2022"),
            };
            let e = from_short_forms(&args).unwrap_err();
            assert_eq!(e.part(), RobotPart::Preset, "{body}: {e}");
            assert!(from_short_forms(&RobotArgs { preset: None, ..args }).is_ok(), "{body}");
        }
    }
}
