//! The `[task]` table: a task of any registered kind (`kind`, default `locomotion`, and that
//! kind's settings), plus how the experiment seeds its episodes.

use serde::{Serialize, Serializer};
use vsrlab_field::FieldError;
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
    pub fn decode(mut table: toml::Table) -> Result<Self, FieldError> {
        let random_terrain_per_evaluation = match table.remove("random_terrain_per_evaluation") {
            None => false,
            Some(toml::Value::Boolean(b)) => b,
            Some(other) => {
                return Err(FieldError::new(
                    "random_terrain_per_evaluation",
                    format!("expected true or false, got {other}"),
                ))
            }
        };
        let episode_seed = match table.remove("episode_seed") {
            None => 0,
            Some(toml::Value::Integer(i)) if i >= 0 => i as u64,
            Some(other) => {
                return Err(FieldError::new(
                    "episode_seed",
                    format!("expected an integer ≥ 0, got {other}"),
                ))
            }
        };
        let value = serde_json::to_value(&table).map_err(|e| FieldError::message(e.to_string()))?;
        let spec = TaskSpec::from_json(value)?;
        Ok(TaskConfig {
            spec,
            random_terrain_per_evaluation,
            episode_seed,
        })
    }

    /// Checks the task's settings: the dotted field and the message on error.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.spec.task().validate().map_err(|e| match e {
            EpisodeError::Field(e) => e,
            EpisodeError::Invalid(m) => FieldError::new("task", m),
            other => FieldError::new("task", other.to_string()),
        })
    }

    /// The same task under another 2D physics solver (`vsrlab run --solver`, Python's
    /// `solver=`): its `physics.solver` replaced. The error (no path: the caller names its
    /// option) says when the name is not a solver or the task has no 2D solver to choose.
    pub fn set_solver(&mut self, solver: &str) -> Result<(), FieldError> {
        solver
            .parse::<vsrlab_physics::Solver>()
            .map_err(|e| FieldError::message(e.to_string()))?;
        let setting = [("physics.solver", serde_json::json!(solver))];
        self.spec = self.spec.with_settings(&setting).map_err(|_| {
            let kind = self.spec.task().kind();
            FieldError::message(format!("the {kind} task has no 2D physics solver to choose"))
        })?;
        Ok(())
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
