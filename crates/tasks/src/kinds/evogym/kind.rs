//! The EvoGym robot's registry entry: its command-line short form (`evogym:ROWS`, or
//! `evogym:<Task>:ROWS` for another task's observation), its robot-file form
//! (`{"format", "note", "evogym": {"body", "env", "brain"}}`) and its `[representation] body`
//! table (`{ kind = "evogym", body = "33333/…", env = "Walker-v0" }`: no body genes, the genotype is
//! the brain's parameters).

use super::robot::EvoGymRobot;
use crate::body_part::BodyPart;
use crate::files::{self, FileError, ROBOT_FORMAT};
use crate::fixed_body::{brain_parameters_on, FixedBody};
use crate::kinds::voxel::short_forms::{RobotArgsError, RobotPart, RANDOM_BRAIN_SEED};
use crate::kinds::{AnyRobot, ForeignFormat, RobotArgs, RobotDescription, RobotKind};
use serde::{Deserialize, Serialize};
use vsrlab_brain::BrainSpec;
use vsrlab_field::FieldError;

/// The EvoGym robot's registry entry.
pub const KIND: RobotKind = RobotKind {
    name: "evogym",
    file_keys: &["evogym", "objects"],
    body_usage: "evogym:[<Task>:]<rows of 0-4 digits joined by />",
    claims_body: |body| body.starts_with("evogym:"),
    from_short_forms,
    from_file,
    body_tables: &["evogym"],
    physics: vsrlab_physics::WorldSettings::default,
    foreign_formats: &[
        ForeignFormat {
            name: "evogym-json",
            extension: "json",
            // recognised by its key `objects` (`file_keys`)
            claims: |_| false,
            read: |bytes, origin| from_file(&String::from_utf8_lossy(bytes), origin),
            write: |robot| Ok(super::robot_to_json(&grid_of(robot)?).into_bytes()),
        },
        ForeignFormat {
            name: "evogym-npz",
            extension: "npz",
            claims: super::is_npz,
            read: from_npz,
            write: |robot| Ok(super::robot_to_npz(&grid_of(robot)?)),
        },
    ],
    decode_body,
};

/// The body of an EvoGym robot, for EvoGym's own file formats (which hold no brain).
fn grid_of(robot: &AnyRobot) -> Result<super::MaterialGrid, FieldError> {
    let evogym = robot.downcast_ref::<EvoGymRobot>().ok_or_else(|| {
        FieldError::message(format!(
            "EvoGym's robot files hold EvoGym robots, not {} robots",
            robot.kind().name
        ))
    })?;
    evogym.grid()
}

/// An EvoGym `.npz` robot: a body only, given the default brain as EvoGym's JSON robots are.
fn from_npz(bytes: &[u8], origin: &str) -> Result<AnyRobot, FileError> {
    let grid = super::robot_from_npz(bytes).map_err(|e| FileError::Invalid {
        path: origin.to_string(),
        msg: e.to_string(),
    })?;
    body_only(grid, origin)
}

/// A robot of EvoGym's files (a body only): the default brain, for Walker-v0 until a task says
/// otherwise. vsrlab's rows connect every pair of adjacent cells, so a body that leaves some apart
/// is refused.
fn body_only(grid: super::MaterialGrid, origin: &str) -> Result<AnyRobot, FileError> {
    let invalid = |msg: String| FileError::Invalid {
        path: origin.to_string(),
        msg,
    };
    if super::MaterialGrid::from_rows(&grid.to_rows()).ok() != Some(grid.clone()) {
        return Err(invalid(
            "a robot whose adjacent cells are not all connected is not supported yet".into(),
        ));
    }
    let brain = BrainSpec::parse(DEFAULT_BRAIN).map_err(|e| invalid(e.to_string()))?;
    Ok(AnyRobot::new(EvoGymRobot {
        body: grid.to_rows(),
        env: walker(),
        brain,
    }))
}

/// The default brain: a centralized MLP over the whole observation.
const DEFAULT_BRAIN: &str = "mlp";

fn from_short_forms(args: &RobotArgs) -> Result<AnyRobot, RobotArgsError> {
    let kind = |part, message: String| RobotArgsError::Kind { part, message };
    if args.sensors.is_some() {
        return Err(kind(
            RobotPart::Sensors,
            "an EvoGym robot observes what its task gives (docs/evogym-envs.md); leave sensors out".into(),
        ));
    }
    super::super::refuse_preset(args, "an EvoGym robot's constants are EvoGym's (docs/evogym-model.md)")?;
    let rest = args.body.strip_prefix("evogym:").unwrap_or(args.body);
    let (env, rows) = match rest.split_once(':') {
        Some((env, rows)) => (env.to_string(), rows),
        None => (super::EvoGymTask::Walker.name().to_string(), rest),
    };
    let brain = BrainSpec::parse(args.brain.unwrap_or(DEFAULT_BRAIN)).map_err(RobotArgsError::Brain)?;
    let mut robot = EvoGymRobot {
        body: rows.to_string(),
        env,
        brain,
    };
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
    robot
        .validate()
        .map_err(|e| kind(RobotPart::Brain, e.at("robot").to_string()))?;
    Ok(AnyRobot::new(robot))
}

/// On-disk form of an EvoGym robot.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct EvoGymFile {
    format: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    note: Option<String>,
    evogym: EvoGymRobot,
}

/// Parses and validates an EvoGym robot file: vsrlab's (`"evogym"`), or EvoGym's own
/// (`grid_width`, `grid_height`, `objects` with one object), which holds a body only: its brain is
/// the default template, given random weights for whichever task runs it.
fn from_file(text: &str, origin: &str) -> Result<AnyRobot, FileError> {
    let value = serde_json::from_str::<serde_json::Value>(text).unwrap_or_default();
    if value.get("objects").is_some() {
        let invalid = |msg: String| FileError::Invalid {
            path: origin.to_string(),
            msg,
        };
        let grid = super::robot_from_json(text).map_err(|e| invalid(e.to_string()))?;
        return body_only(grid, origin).map_err(|e| match e {
            FileError::Invalid { path, msg } => FileError::Invalid {
                path,
                msg: format!("objects: {msg} (neighbors)"),
            },
            other => other,
        });
    }
    let file: EvoGymFile = files::parse_json(text, origin)?;
    files::check_format(&file.format, origin)?;
    file.evogym.validate().map_err(|e| FileError::Invalid {
        path: origin.to_string(),
        msg: e.at("evogym").to_string(),
    })?;
    Ok(AnyRobot::new(file.evogym))
}

impl RobotDescription for EvoGymRobot {
    fn kind(&self) -> &'static RobotKind {
        &KIND
    }

    /// The descriptors of the grid's cells of any material, as a voxel body's.
    fn morphology(&self) -> Option<vsrlab_body::MorphologyDescriptors> {
        let grid = self.grid().ok()?;
        let (w, h) = (grid.width(), grid.height());
        // a morphology's rows run from the bottom, the grid's from the top
        let cells = (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, h - 1 - y)))
            .map(|(x, y)| grid.at(x, y) != super::Material::Empty)
            .collect();
        let body = vsrlab_body::Morphology::from_cells(w, h, cells).ok()?;
        Some(vsrlab_body::MorphologyDescriptors::of(&body))
    }

    fn for_task(&self, task: &dyn crate::task::Task, untrained: bool) -> Option<AnyRobot> {
        let task = task.as_any()?.downcast_ref::<super::EvoGym>()?;
        let template = self.brain.parameters().is_empty();
        if !template && (!untrained || task.env == self.env) {
            return None;
        }
        // the weights the episode would draw for a template (and the short form for the task's
        // observation): the same seed, so the same bits as before
        let mut robot = EvoGymRobot {
            env: task.env.clone(),
            ..self.clone()
        };
        let shape = robot.brain_shape().ok()?;
        robot.brain = robot.brain.with_random_parameters(RANDOM_BRAIN_SEED, &shape).ok()?;
        robot.validate().ok()?;
        Some(AnyRobot::new(robot))
    }

    fn brain(&self) -> &BrainSpec {
        &self.brain
    }

    fn to_json(&self, note: Option<&str>) -> String {
        let file = EvoGymFile {
            format: ROBOT_FORMAT.to_string(),
            note: note.map(str::to_string),
            evogym: self.clone(),
        };
        serde_json::to_string_pretty(&file).expect("EvoGym robots always serialise")
    }

    fn body_details(&self, actuators: usize) -> String {
        format!(
            "material grid {}, {actuators} actuators, {}'s observation",
            self.body, self.env
        )
    }

    fn sensors_label(&self) -> String {
        format!("{}'s observation", self.env)
    }

    fn preset_label(&self) -> String {
        "evogym".to_string()
    }

    fn size(&self) -> usize {
        self.grid().map_or(0, |g| g.cell_count())
    }

    fn label(&self) -> String {
        format!("evogym {} for {}, brain={:?}", self.body, self.env, self.brain.kind())
    }

    fn clone_box(&self) -> Box<dyn RobotDescription> {
        Box::new(self.clone())
    }

    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

/// An EvoGym body in an experiment file: `{ kind = "evogym", body = "…", env = "Walker-v0" }`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EvoGymTable {
    /// Always `evogym`.
    pub kind: String,
    /// The material grid (rows of digits 0-4 joined by `/`).
    pub body: String,
    /// The task whose observation the brain sees (default `Walker-v0`).
    #[serde(default = "walker")]
    pub env: String,
}

fn walker() -> String {
    super::EvoGymTask::Walker.name().to_string()
}

/// Reads an EvoGym body table; the error's path is relative to the table.
fn decode_body(value: serde_json::Value) -> Result<BodyPart, FieldError> {
    let table: EvoGymTable = crate::registry::decode(value)?;
    let robot = table.robot_with(BrainSpec::parse(DEFAULT_BRAIN).map_err(FieldError::from)?);
    robot.grid()?;
    robot.task()?;
    Ok(BodyPart::new(table))
}

impl EvoGymTable {
    fn robot_with(&self, brain: BrainSpec) -> EvoGymRobot {
        EvoGymRobot {
            body: self.body.clone(),
            env: self.env.clone(),
            brain,
        }
    }
}

impl FixedBody for EvoGymTable {
    fn robot_kind(&self) -> &'static RobotKind {
        &KIND
    }

    fn sensors_refused(&self) -> &'static str {
        "an EvoGym robot observes what its task gives; remove this field"
    }

    fn brain_parameters(&self, brain: &BrainSpec) -> Result<usize, FieldError> {
        brain_parameters_on(self.robot_with(brain.clone()).brain_shape(), brain)
    }

    fn robot_of(&self, brain: BrainSpec) -> AnyRobot {
        AnyRobot::new(self.robot_with(brain))
    }

    fn body_units(&self) -> usize {
        super::MaterialGrid::from_rows(&self.body).map_or(0, |g| g.cell_count())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn robot(body: &str) -> EvoGymRobot {
        EvoGymRobot {
            body: body.into(),
            env: "Walker-v0".into(),
            brain: BrainSpec::parse("mlp").unwrap(),
        }
    }

    /// An EvoGym body's descriptors are those of the voxel body with a cell wherever the grid
    /// has a material (any material, its rows read from the top), not of its actuators.
    #[test]
    fn morphology_descriptors_read_every_cell_of_any_material() {
        let voxel =
            |rows: &[&str]| vsrlab_body::MorphologyDescriptors::of(&vsrlab_body::Morphology::from_rows(rows).unwrap());
        let l_shape = robot("3.../1.../4.../2222").morphology().unwrap();
        assert_eq!(l_shape, voxel(&["#...", "#...", "#...", "####"]));
        assert_eq!(l_shape.voxels, 7);
        assert!(l_shape.elongation > 0.0 && l_shape.compactness < 1.0);
        let full = robot("33333/33333/33333").morphology().unwrap();
        assert_eq!((full.voxels, full.compactness), (15, 1.0));
        assert!(robot("3x3").morphology().is_none(), "not a grid");
    }
}
