//! The task registry: [`TaskSpec`] is the serialisable value of any task kind, and [`TASKS`]
//! lists every kind with its command-line short form and its config decoder.
//!
//! Adding a task: write its module (a settings struct implementing [`Task`]), add one variant to
//! [`TaskSpec`], one arm to [`TaskSpec::task`] and one entry to
//! [`TASKS`]. Nothing else matches on task kinds.

use crate::carrier::Carrier;
use crate::escape::Escape;
use crate::jump::Jump;
use crate::kinds::evogym::{EvoGym, EvoGymTask};
use crate::kinds::voxel3d::{Affordance, Environment, Locomotion3d};
use crate::locomotion::Locomotion;
use crate::task::Task;
use crate::terrain::Terrain;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
pub use vsrlab_field::FieldError;

/// A task of any registered kind, tagged by `kind` in configs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum TaskSpec {
    /// Walk right as far as possible ([`Locomotion`]).
    Locomotion(Locomotion),
    /// Rise as high as possible ([`Jump`]).
    Jump(Jump),
    /// Get out of a cage ([`Escape`]).
    Escape(Escape),
    /// Walk with a ball on top ([`Carrier`]).
    Carrier(Carrier),
    /// One of EvoGym's tasks, on its own engine ([`EvoGym`]).
    Evogym(EvoGym),
    /// Walk in 3D, on the 3D engine ([`Locomotion3d`]).
    Locomotion3d(Locomotion3d),
    /// Detect whether an aperture is passable, on the 3D engine ([`Affordance`]).
    Affordance(Affordance),
}

impl Default for TaskSpec {
    fn default() -> Self {
        TaskSpec::Locomotion(Locomotion::default())
    }
}

/// Why a command-line task could not be parsed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TaskParseError {
    /// No task kind has this name.
    #[error("unknown task '{name}': expected {expected}")]
    Unknown {
        /// The name given.
        name: String,
        /// Every short form, for the message.
        expected: String,
    },
    /// The kind is known but its argument is not.
    #[error("{kind}: {error}")]
    Argument {
        /// The task kind.
        kind: &'static str,
        /// What is wrong with the argument.
        #[source]
        error: FieldError,
    },
}

/// One registered task kind.
pub struct TaskKind {
    /// The `kind` tag.
    pub name: &'static str,
    /// Its command-line short form, for help and error messages.
    pub usage: &'static str,
    /// Builds the task from the argument after `kind:` (absent when there is none); the error is
    /// about the argument as a whole.
    pub parse: fn(Option<&str>) -> Result<TaskSpec, FieldError>,
    /// Builds the task from its config table (without `kind`), naming the field on error.
    pub decode: fn(serde_json::Value) -> Result<TaskSpec, FieldError>,
    /// A task of this kind known by a name of its own on the command line (EvoGym's
    /// `bridge-walker` for `evogym:BridgeWalker-v0`), if `name` is one.
    pub alias: fn(&str) -> Option<TaskSpec>,
}

fn no_alias(_: &str) -> Option<TaskSpec> {
    None
}

/// Every task kind.
pub const TASKS: &[TaskKind] = &[
    TaskKind {
        name: "locomotion",
        usage: "locomotion:<terrain>",
        parse: parse_locomotion,
        decode: |v| decode_task::<Locomotion>(v).map(TaskSpec::Locomotion),
        alias: no_alias,
    },
    TaskKind {
        name: "jump",
        usage: "jump",
        parse: parse_jump,
        decode: |v| decode_task::<Jump>(v).map(TaskSpec::Jump),
        alias: no_alias,
    },
    TaskKind {
        name: "escape",
        usage: "escape[:<cage side>]",
        parse: parse_escape,
        decode: |v| decode_task::<Escape>(v).map(TaskSpec::Escape),
        alias: no_alias,
    },
    TaskKind {
        name: "carrier",
        usage: "carrier",
        parse: parse_carrier,
        decode: |v| decode_task::<Carrier>(v).map(TaskSpec::Carrier),
        alias: no_alias,
    },
    TaskKind {
        name: "evogym",
        usage: "evogym[:<Walker-v0|BridgeWalker-v0|BeamToppler-v0|CaveCrawler-v0>] (or walker, bridge-walker, beam-toppler, cave-crawler)",
        parse: parse_evogym,
        decode: |v| decode_task::<EvoGym>(v).map(TaskSpec::Evogym),
        alias: evogym_alias,
    },
    TaskKind {
        name: "locomotion3d",
        usage: "locomotion3d[:<seconds>]",
        parse: parse_locomotion3d,
        decode: |v| decode_task::<Locomotion3d>(v).map(TaskSpec::Locomotion3d),
        alias: no_alias,
    },
    TaskKind {
        name: "affordance",
        usage: "affordance[:<impassable|passable-left|passable-right>] (one environment; all three by default)",
        parse: parse_affordance,
        decode: |v| decode_task::<Affordance>(v).map(TaskSpec::Affordance),
        alias: no_alias,
    },
];

fn parse_escape(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    let mut escape = Escape::default();
    if let Some(a) = arg {
        escape.side = a
            .parse()
            .ok()
            .filter(|s: &f64| s.is_finite() && *s > 0.0)
            .ok_or_else(|| FieldError::message(format!("expected the cage's side (a number > 0), got '{a}'")))?;
    }
    Ok(TaskSpec::Escape(escape))
}

fn parse_carrier(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    match arg {
        None => Ok(TaskSpec::Carrier(Carrier::default())),
        Some(a) => Err(FieldError::message(format!(
            "the carrier task takes no argument, got '{a}'"
        ))),
    }
}

fn parse_locomotion(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    let terrain: Terrain = arg.unwrap_or("flat").parse()?;
    Ok(TaskSpec::Locomotion(Locomotion {
        terrain,
        ..Locomotion::default()
    }))
}

fn parse_evogym(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    let mut task = EvoGym::default();
    if let Some(name) = arg {
        let which = EvoGymTask::from_name(name).ok_or_else(|| FieldError::message(EvoGymTask::unknown(name)))?;
        task.env = which.name().to_string();
    }
    Ok(TaskSpec::Evogym(task))
}

fn evogym_alias(name: &str) -> Option<TaskSpec> {
    let which = EvoGymTask::from_name(name)?;
    Some(TaskSpec::Evogym(EvoGym {
        env: which.name().to_string(),
        ..EvoGym::default()
    }))
}

fn parse_locomotion3d(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    let mut task = Locomotion3d::default();
    if let Some(a) = arg {
        task.duration = a
            .parse::<f64>()
            .map_err(|_| FieldError::message(format!("'{a}': expected the episode's length in seconds")))?;
    }
    Ok(TaskSpec::Locomotion3d(task))
}

fn parse_affordance(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    let mut task = Affordance::default();
    if let Some(name) = arg {
        let env = Environment::ALL.into_iter().find(|e| e.name() == name).ok_or_else(|| {
            FieldError::message(format!(
                "unknown environment '{name}': expected impassable, passable-left or passable-right"
            ))
        })?;
        task.environments = vec![env];
    }
    Ok(TaskSpec::Affordance(task))
}

fn parse_jump(arg: Option<&str>) -> Result<TaskSpec, FieldError> {
    match arg {
        None => Ok(TaskSpec::Jump(Jump::default())),
        Some(a) => Err(FieldError::message(format!(
            "the jump task takes no argument, got '{a}'"
        ))),
    }
}

/// Deserializes a task's settings from its table like [`decode`], a partial `physics` table
/// being completed field by field from the task kind's own physics (a PSA task's gravity of −10,
/// not the default world's −9.8), not from the physics type's defaults.
fn decode_task<T: DeserializeOwned + Serialize + Default>(mut value: serde_json::Value) -> Result<T, FieldError> {
    if let Some(serde_json::Value::Object(given)) = value.get_mut("physics") {
        let defaults = serde_json::to_value(T::default()).ok();
        if let Some(serde_json::Value::Object(mut physics)) =
            defaults.and_then(|mut d| d.get_mut("physics").map(serde_json::Value::take))
        {
            physics.extend(std::mem::take(given));
            *given = physics;
        }
    }
    decode(value)
}

/// Deserializes a settings struct from its table, keeping the dotted path of a failing field
/// (serde alone loses it inside tagged tables). Registries of other kinds use it too. serde
/// reports an unknown field only in its message, so that message is read here, once, to put the
/// field's name at the end of the path.
pub fn decode<T: DeserializeOwned>(value: serde_json::Value) -> Result<T, FieldError> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let mut path = e.path().to_string();
        let message = e.into_inner().to_string();
        if path == "." {
            path.clear();
        }
        if let Some(name) = message
            .strip_prefix("unknown field `")
            .and_then(|rest| rest.split('`').next())
        {
            if path.rsplit('.').next() != Some(name) {
                path = if path.is_empty() {
                    name.to_string()
                } else {
                    format!("{path}.{name}")
                };
            }
        }
        FieldError::new(path, message)
    })
}

fn kind_names() -> String {
    TASKS.iter().map(|k| k.name).collect::<Vec<_>>().join(", ")
}

impl TaskSpec {
    /// The task behind the value.
    pub fn task(&self) -> &dyn Task {
        match self {
            TaskSpec::Locomotion(t) => t,
            TaskSpec::Jump(t) => t,
            TaskSpec::Escape(t) => t,
            TaskSpec::Carrier(t) => t,
            TaskSpec::Evogym(t) => t,
            TaskSpec::Locomotion3d(t) => t,
            TaskSpec::Affordance(t) => t,
        }
    }

    /// The task's `kind` tag.
    pub fn kind(&self) -> &'static str {
        self.task().kind()
    }

    /// Parses a command-line short form: `locomotion:<terrain>` (`locomotion` alone is flat),
    /// `jump`, …, or a name a kind claims as its own (`bridge-walker`; see [`TASKS`]).
    pub fn parse(s: &str) -> Result<TaskSpec, TaskParseError> {
        let (name, arg) = s.split_once(':').map_or((s, None), |(a, b)| (a, Some(b)));
        let kind = TASKS.iter().find(|k| k.name == name);
        if let (None, None) = (kind, arg) {
            if let Some(task) = TASKS.iter().find_map(|k| (k.alias)(name)) {
                return Ok(task);
            }
        }
        let kind = kind.ok_or_else(|| TaskParseError::Unknown {
            name: name.to_string(),
            expected: TASKS.iter().map(|k| k.usage).collect::<Vec<_>>().join(" or "),
        })?;
        (kind.parse)(arg).map_err(|error| TaskParseError::Argument { kind: kind.name, error })
    }

    /// Builds a task from its config table; `kind` defaults to `locomotion`.
    pub fn from_json(value: serde_json::Value) -> Result<TaskSpec, FieldError> {
        let serde_json::Value::Object(mut table) = value else {
            return Err(FieldError::message("expected a table of task settings"));
        };
        let name = match table.remove("kind") {
            None => "locomotion".to_string(),
            Some(serde_json::Value::String(s)) => s,
            Some(other) => {
                return Err(FieldError::new(
                    "kind",
                    format!("expected a task name ({}), got {other}", kind_names()),
                ))
            }
        };
        let kind = TASKS.iter().find(|k| k.name == name).ok_or_else(|| {
            FieldError::new(
                "kind",
                format!("unknown task '{name}': expected one of {}", kind_names()),
            )
        })?;
        (kind.decode)(serde_json::Value::Object(table))
    }

    /// The same task with some settings replaced, by dotted path (`duration`,
    /// `physics.substeps`); an error names a setting this kind of task does not have.
    pub fn with_settings(&self, settings: &[(&str, serde_json::Value)]) -> Result<TaskSpec, FieldError> {
        let mut value = serde_json::to_value(self).map_err(|e| FieldError::message(e.to_string()))?;
        for (path, v) in settings {
            let (parents, last) = split_last(path);
            // an optional setting left out of the serialised form (`damage`) is added; the
            // decoder refuses names the task does not have
            let table = table_at(&mut value, parents).ok_or_else(|| self.no_such_setting(path))?;
            table.insert(last.to_string(), v.clone());
        }
        TaskSpec::from_json(value).map_err(|e| {
            let unknown = settings
                .iter()
                .find(|(path, _)| e.path == *path && !self.has_setting(path));
            match unknown {
                Some((path, _)) => self.no_such_setting(path),
                None => e,
            }
        })
    }

    /// Whether this kind of task has the setting at dotted `path`: its serialised form holds it,
    /// or (an optional setting left out while unset, such as `damage`) it decodes with the setting
    /// set to null.
    fn has_setting(&self, path: &str) -> bool {
        let Ok(mut value) = serde_json::to_value(self) else {
            return false;
        };
        let (parents, last) = split_last(path);
        match table_at(&mut value, parents) {
            None => false,
            Some(table) if table.contains_key(last) => true,
            Some(table) => {
                table.insert(last.to_string(), serde_json::Value::Null);
                TaskSpec::from_json(value).is_ok()
            }
        }
    }

    /// The error for a setting this kind of task does not have.
    fn no_such_setting(&self, path: &str) -> FieldError {
        FieldError::new(path, format!("a {} task has no such setting", self.kind()))
    }
}

/// A dotted path as its parents and its last key (`physics.substeps` → `physics`, `substeps`).
fn split_last(path: &str) -> (&str, &str) {
    path.rsplit_once('.').unwrap_or(("", path))
}

/// The table at dotted path `parents` inside `value` (`value` itself for an empty path).
fn table_at<'a>(
    value: &'a mut serde_json::Value,
    parents: &str,
) -> Option<&'a mut serde_json::Map<String, serde_json::Value>> {
    let mut table = value;
    for key in parents.split('.').filter(|k| !k.is_empty()) {
        table = table.as_object_mut()?.get_mut(key)?;
    }
    table.as_object_mut()
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn short_forms_and_tables_resolve_through_the_registry() {
        assert_eq!(TaskSpec::parse("locomotion:flat"), Ok(TaskSpec::default()));
        assert_eq!(TaskSpec::parse("locomotion").unwrap().kind(), "locomotion");
        assert_eq!(TaskSpec::parse("jump").unwrap().kind(), "jump");
        let err = TaskSpec::parse("swim:deep").unwrap_err().to_string();
        assert!(err.contains("locomotion:<terrain> or jump or escape"), "{err}");
        assert!(TaskSpec::parse("locomotion:bumpy").is_err());

        let t = TaskSpec::from_json(json!({"terrain": "hilly-1-10", "duration": 5.0})).unwrap();
        assert_eq!(t.task().duration(), 5.0);
        let t = TaskSpec::from_json(json!({"kind": "jump", "duration": 3.0})).unwrap();
        assert_eq!(t.kind(), "jump");
        let e = TaskSpec::from_json(json!({"kind": "jump", "terrain": "flat"})).unwrap_err();
        assert_eq!(e.path, "terrain");
        let e = TaskSpec::from_json(json!({"duration": "long"})).unwrap_err();
        assert_eq!(e.path, "duration");
        let e = TaskSpec::from_json(json!({"physics": {"dt": "x"}})).unwrap_err();
        assert_eq!(e.path, "physics.dt");
        let e = TaskSpec::from_json(json!({"kind": "fly"})).unwrap_err();
        assert_eq!(e.path, "kind");
        assert!(e.message.contains("locomotion, jump, escape, carrier"), "{e}");
    }

    /// EvoGym's tasks answer to their own names, the kind's full form being the same task.
    #[test]
    fn a_kind_can_claim_task_names_of_its_own() {
        let full = TaskSpec::parse("evogym:BridgeWalker-v0").unwrap();
        for name in [
            "bridge-walker",
            "bridge-walker-v0",
            "BridgeWalker-v0",
            "bridgewalker-v0",
        ] {
            assert_eq!(TaskSpec::parse(name).as_ref(), Ok(&full), "{name}");
        }
        assert_eq!(
            TaskSpec::parse("cave-crawler"),
            TaskSpec::parse("evogym:CaveCrawler-v0")
        );
        assert_ne!(TaskSpec::parse("walker"), TaskSpec::parse("evogym:BeamToppler-v0"));
        let err = TaskSpec::parse("bridge-walker:x").unwrap_err().to_string();
        assert!(err.contains("unknown task 'bridge-walker'"), "{err}");
        assert!(TaskSpec::parse("bridge-runner").is_err());
    }

    /// A partial `[task.physics]` table keeps the task kind's other physics settings: a PSA
    /// task's gravity and time step, not the default world's.
    #[test]
    fn a_partial_physics_table_keeps_the_task_kind_s_physics() {
        let psa = crate::kinds::psa::inflation::psa_physics();
        assert_ne!(psa.gravity, vsrlab_physics::WorldSettings::default().gravity);
        for kind in ["carrier", "escape"] {
            let table = json!({"kind": kind, "physics": {"solver": "sequential-impulses"}});
            let task = TaskSpec::from_json(table).unwrap();
            let physics = task.task().rigid().unwrap().physics();
            assert_eq!(physics.gravity, psa.gravity, "{kind}");
            assert_eq!(physics.solver, vsrlab_physics::Solver::SequentialImpulses, "{kind}");
        }
        let e = TaskSpec::from_json(json!({"kind": "carrier", "physics": {"substeps": "x"}})).unwrap_err();
        assert_eq!(e.path, "physics.substeps");
    }

    #[test]
    fn settings_are_replaced_by_path_and_unknown_ones_named() {
        let t = TaskSpec::default()
            .with_settings(&[("duration", json!(7.0)), ("physics.substeps", json!(3))])
            .unwrap();
        assert_eq!(t.task().duration(), 7.0);
        assert_eq!(t.task().rigid().unwrap().physics().substeps, 3);
        let e = TaskSpec::parse("jump")
            .unwrap()
            .with_settings(&[("transient", json!(1.0))])
            .unwrap_err();
        assert_eq!(e.to_string(), "transient: a jump task has no such setting");
        // an optional setting absent from the serialised form can be added and removed
        let damaged = TaskSpec::default()
            .with_settings(&[("damage", json!({"at": 30.0, "probability": 0.5}))])
            .unwrap();
        assert_eq!(damaged.task().damage().map(|d| d.probability), Some(0.5));
        let healed = damaged.with_settings(&[("damage", json!(null))]).unwrap();
        assert_eq!(healed, TaskSpec::default());
        let e = TaskSpec::parse("jump")
            .unwrap()
            .with_settings(&[("damage", json!({"at": 1.0, "probability": 0.5}))])
            .unwrap_err();
        assert_eq!(e.to_string(), "damage: a jump task has no such setting");
        let e = TaskSpec::default()
            .with_settings(&[("damage", json!({"at": 1.0}))])
            .unwrap_err();
        assert!(e.to_string().contains("probability"), "{e}");
    }

    #[test]
    fn specs_round_trip_through_json_with_their_kind() {
        for s in [
            "locomotion:hilly-1-10-3",
            "jump",
            "escape:15",
            "carrier",
            "locomotion:psa-hilly-3-10",
        ] {
            let t = TaskSpec::parse(s).unwrap();
            let v = serde_json::to_value(&t).unwrap();
            assert_eq!(v["kind"], json!(t.kind()));
            assert_eq!(TaskSpec::from_json(v).unwrap(), t);
        }
    }
}
