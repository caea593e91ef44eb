//! The task registry: [`TaskSpec`] is the serialisable value of any task kind, and [`TASKS`]
//! lists every kind with its command-line short form and its config decoder.
//!
//! Adding a task: write its module (a settings struct implementing [`Task`]), add one variant to
//! [`TaskSpec`], one arm to [`TaskSpec::task`] and one entry to
//! [`TASKS`]. Nothing else matches on task kinds.

use crate::carrier::Carrier;
use crate::escape::Escape;
use crate::jump::Jump;
use crate::locomotion::Locomotion;
use crate::task::Task;
use crate::terrain::Terrain;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

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
}

impl Default for TaskSpec {
    fn default() -> Self {
        TaskSpec::Locomotion(Locomotion::default())
    }
}

/// An error inside a task's settings: the dotted path of the field and what is wrong.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}{message}", if path.is_empty() { String::new() } else { format!("{path}: ") })]
pub struct FieldError {
    /// Dotted path of the field inside the task's table (empty: the table itself).
    pub path: String,
    /// What is wrong.
    pub message: String,
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
    #[error("{kind}: {message}")]
    Argument {
        /// The task kind.
        kind: &'static str,
        /// What is wrong with the argument.
        message: String,
    },
}

/// One registered task kind.
pub struct TaskKind {
    /// The `kind` tag.
    pub name: &'static str,
    /// Its command-line short form, for help and error messages.
    pub usage: &'static str,
    /// Builds the task from the argument after `kind:` (absent when there is none).
    pub parse: fn(Option<&str>) -> Result<TaskSpec, String>,
    /// Builds the task from its config table (without `kind`), naming the field on error.
    pub decode: fn(serde_json::Value) -> Result<TaskSpec, FieldError>,
}

/// Every task kind.
pub const TASKS: &[TaskKind] = &[
    TaskKind {
        name: "locomotion",
        usage: "locomotion:<terrain>",
        parse: parse_locomotion,
        decode: |v| decode::<Locomotion>(v).map(TaskSpec::Locomotion),
    },
    TaskKind {
        name: "jump",
        usage: "jump",
        parse: parse_jump,
        decode: |v| decode::<Jump>(v).map(TaskSpec::Jump),
    },
    TaskKind {
        name: "escape",
        usage: "escape[:<cage side>]",
        parse: parse_escape,
        decode: |v| decode::<Escape>(v).map(TaskSpec::Escape),
    },
    TaskKind {
        name: "carrier",
        usage: "carrier",
        parse: parse_carrier,
        decode: |v| decode::<Carrier>(v).map(TaskSpec::Carrier),
    },
];

fn parse_escape(arg: Option<&str>) -> Result<TaskSpec, String> {
    let mut escape = Escape::default();
    if let Some(a) = arg {
        escape.side = a
            .parse()
            .ok()
            .filter(|s: &f64| s.is_finite() && *s > 0.0)
            .ok_or_else(|| format!("expected the cage's side (a number > 0), got '{a}'"))?;
    }
    Ok(TaskSpec::Escape(escape))
}

fn parse_carrier(arg: Option<&str>) -> Result<TaskSpec, String> {
    match arg {
        None => Ok(TaskSpec::Carrier(Carrier::default())),
        Some(a) => Err(format!("the carrier task takes no argument, got '{a}'")),
    }
}

fn parse_locomotion(arg: Option<&str>) -> Result<TaskSpec, String> {
    let terrain: Terrain = arg.unwrap_or("flat").parse()?;
    Ok(TaskSpec::Locomotion(Locomotion {
        terrain,
        ..Locomotion::default()
    }))
}

fn parse_jump(arg: Option<&str>) -> Result<TaskSpec, String> {
    match arg {
        None => Ok(TaskSpec::Jump(Jump::default())),
        Some(a) => Err(format!("the jump task takes no argument, got '{a}'")),
    }
}

/// Deserializes a settings struct from its table, keeping the dotted path of a failing field
/// (serde alone loses it inside tagged tables). Registries of other kinds use it too.
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
        FieldError { path, message }
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
        }
    }

    /// The task's `kind` tag.
    pub fn kind(&self) -> &'static str {
        self.task().kind()
    }

    /// Parses a command-line short form: `locomotion:<terrain>` (`locomotion` alone is flat),
    /// `jump`, … (see [`TASKS`]).
    pub fn parse(s: &str) -> Result<TaskSpec, TaskParseError> {
        let (name, arg) = s.split_once(':').map_or((s, None), |(a, b)| (a, Some(b)));
        let kind = TASKS
            .iter()
            .find(|k| k.name == name)
            .ok_or_else(|| TaskParseError::Unknown {
                name: name.to_string(),
                expected: TASKS.iter().map(|k| k.usage).collect::<Vec<_>>().join(" or "),
            })?;
        (kind.parse)(arg).map_err(|message| TaskParseError::Argument {
            kind: kind.name,
            message,
        })
    }

    /// Builds a task from its config table; `kind` defaults to `locomotion`.
    pub fn from_json(value: serde_json::Value) -> Result<TaskSpec, FieldError> {
        let serde_json::Value::Object(mut table) = value else {
            return Err(FieldError {
                path: String::new(),
                message: "expected a table of task settings".into(),
            });
        };
        let name = match table.remove("kind") {
            None => "locomotion".to_string(),
            Some(serde_json::Value::String(s)) => s,
            Some(other) => {
                return Err(FieldError {
                    path: "kind".into(),
                    message: format!("expected a task name ({}), got {other}", kind_names()),
                })
            }
        };
        let kind = TASKS.iter().find(|k| k.name == name).ok_or_else(|| FieldError {
            path: "kind".into(),
            message: format!("unknown task '{name}': expected one of {}", kind_names()),
        })?;
        (kind.decode)(serde_json::Value::Object(table))
    }

    /// The same task with some settings replaced, by dotted path (`duration`,
    /// `physics.substeps`); an error names a setting this kind of task does not have.
    pub fn with_settings(&self, settings: &[(&str, serde_json::Value)]) -> Result<TaskSpec, FieldError> {
        let mut value = serde_json::to_value(self).map_err(|e| FieldError {
            path: String::new(),
            message: e.to_string(),
        })?;
        for (path, v) in settings {
            let no_such = || FieldError {
                path: path.to_string(),
                message: format!("a {} task has no such setting", self.kind()),
            };
            let (parents, last) = path.rsplit_once('.').map_or(("", *path), |(p, l)| (p, l));
            let mut table = &mut value;
            for key in parents.split('.').filter(|k| !k.is_empty()) {
                table = table.as_object_mut().and_then(|t| t.get_mut(key)).ok_or_else(no_such)?;
            }
            // an optional setting left out of the serialised form (`damage`) is added; the
            // decoder refuses names the task does not have
            let table = table.as_object_mut().ok_or_else(no_such)?;
            table.insert(last.to_string(), v.clone());
        }
        TaskSpec::from_json(value).map_err(|e| {
            let unknown = settings.iter().find(|(p, _)| {
                let last = p.rsplit('.').next().unwrap_or(p);
                e.message.contains(&format!("unknown field `{last}`"))
            });
            match unknown {
                Some((path, _)) => FieldError {
                    path: path.to_string(),
                    message: format!("a {} task has no such setting", self.kind()),
                },
                None => e,
            }
        })
    }
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

    #[test]
    fn settings_are_replaced_by_path_and_unknown_ones_named() {
        let t = TaskSpec::default()
            .with_settings(&[("duration", json!(7.0)), ("physics.substeps", json!(3))])
            .unwrap();
        assert_eq!(t.task().duration(), 7.0);
        assert_eq!(t.task().physics().substeps, 3);
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
