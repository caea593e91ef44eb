//! The `[task]` table: a task of any registered kind (`kind`, default `locomotion`, and that
//! kind's settings), plus how the experiment seeds its episodes.

use serde::{Serialize, Serializer};
use vsrlab_tasks::{EpisodeError, TaskSpec};

/// The task of an experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct TaskConfig {
    /// The task and its settings (including its fitness).
    pub spec: TaskSpec,
    /// `true`: every evaluation uses its candidate's own seed (a new random terrain and sensor
    /// noise each time, a noisy fitness); `false`: every evaluation uses `episode_seed`.
    pub random_terrain_per_evaluation: bool,
    /// The episode seed when `random_terrain_per_evaluation` is false.
    pub episode_seed: u64,
}

impl TaskConfig {
    /// Decodes the table; on error, the field inside `task` and the message.
    pub fn decode(mut table: toml::Table) -> Result<Self, (String, String)> {
        let random_terrain_per_evaluation = match table.remove("random_terrain_per_evaluation") {
            None => false,
            Some(toml::Value::Boolean(b)) => b,
            Some(other) => {
                return Err((
                    "random_terrain_per_evaluation".into(),
                    format!("expected true or false, got {other}"),
                ))
            }
        };
        let episode_seed = match table.remove("episode_seed") {
            None => 0,
            Some(toml::Value::Integer(i)) if i >= 0 => i as u64,
            Some(other) => return Err(("episode_seed".into(), format!("expected an integer ≥ 0, got {other}"))),
        };
        let value = serde_json::to_value(&table).map_err(|e| (String::new(), e.to_string()))?;
        let spec = TaskSpec::from_json(value).map_err(|e| (e.path, e.message))?;
        Ok(TaskConfig {
            spec,
            random_terrain_per_evaluation,
            episode_seed,
        })
    }

    /// Checks the task's settings: the dotted field and the message on error.
    pub fn validate(&self) -> Result<(), (String, String)> {
        self.spec.task().validate().map_err(|e| {
            let text = match e {
                EpisodeError::Invalid(m) => m,
                other => other.to_string(),
            };
            match text.split_once(' ') {
                Some((field, rest)) if field.starts_with("task.") => {
                    (field.trim_end_matches(':').to_string(), rest.to_string())
                }
                _ => ("task".to_string(), text),
            }
        })
    }
}

impl Serialize for TaskConfig {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Flat<'a> {
            random_terrain_per_evaluation: bool,
            episode_seed: u64,
            #[serde(flatten)]
            spec: &'a TaskSpec,
        }
        Flat {
            random_terrain_per_evaluation: self.random_terrain_per_evaluation,
            episode_seed: self.episode_seed,
            spec: &self.spec,
        }
        .serialize(serializer)
    }
}
