//! Replaying evolved robots: the one place where analysis runs episodes ([`replay`]), and the
//! setup an experiment's individuals are replayed with ([`ReplaySetup`]).
//!
//! A [`SetupReader`] turns an experiment folder into a [`ReplaySetup`]: commands use
//! [`crate::setup::read_setup`] (the experiment file, read by the experiment crate), tests their own.

use std::sync::Arc;
use vsrlab_analysis::results::SnapshotRow;
use vsrlab_analysis::run_folder::RunFolder;
use vsrlab_tasks::Task;
use vsrlab_tasks::{episode, EpisodeError, EvaluationError, Robot, StoredGenotypes, TaskSpec, Trace, TraceLevel};

/// An error of the caller's own type (setup readers, video writers).
pub type BoxError = Box<dyn std::error::Error + Send + Sync>;

/// Why a robot could not be replayed.
#[derive(Debug, thiserror::Error)]
pub enum ReplayError {
    /// The genotype does not make a robot of this representation.
    #[error("{0}")]
    Genotype(#[from] EvaluationError),
    /// The episode could not be run.
    #[error("{0}")]
    Episode(#[from] EpisodeError),
    /// The episode ran but recorded no trace.
    #[error("the episode recorded no trace")]
    NoTrace,
}

/// Runs one episode of `robot` on `task` with episode seed `seed` and returns its trace,
/// recorded at `level`. Every replay in analysis goes through here.
pub fn replay(robot: &dyn Robot, task: &dyn Task, seed: u64, level: TraceLevel) -> Result<Trace, ReplayError> {
    let outcome = episode::run(robot, task, seed, level)?;
    outcome.trace.ok_or(ReplayError::NoTrace)
}

/// How the individuals of one experiment are replayed: what its configuration says.
#[derive(Clone)]
pub struct ReplaySetup {
    /// Stored genotype → robot, for the experiment's genotype kind.
    pub genotypes: Arc<dyn StoredGenotypes>,
    /// The task.
    pub task: TaskSpec,
    /// The episode seed of every evaluation when `random_terrain` is off.
    pub episode_seed: u64,
    /// Whether every evaluation had its own seed (a new random terrain each time).
    pub random_terrain: bool,
}

impl std::fmt::Debug for ReplaySetup {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ReplaySetup")
            .field("task", &self.task)
            .field("episode_seed", &self.episode_seed)
            .field("random_terrain", &self.random_terrain)
            .finish_non_exhaustive()
    }
}

impl ReplaySetup {
    /// The robot of a snapshot row and its full trace, replayed with the row's episode seed
    /// (the episode evolution saw).
    pub fn replay_row(&self, row: &SnapshotRow) -> Result<(Box<dyn Robot>, Trace), ReplayError> {
        let robot = self.genotypes.robot(&row.genotype)?;
        let trace = replay(robot.as_ref(), self.task.task(), row.seed(), TraceLevel::Full)?;
        Ok((robot, trace))
    }

    /// The seed a run's best robot is replayed with: the experiment's episode seed, or 0 when
    /// every evaluation had its own.
    pub fn best_robot_seed(&self) -> u64 {
        if self.random_terrain {
            0
        } else {
            self.episode_seed
        }
    }
}

/// Reads the replay setup of an experiment folder (its `experiment.toml`).
pub trait SetupReader: Sync {
    /// The setup of the experiment in `folder`.
    fn read_setup(&self, folder: &RunFolder) -> Result<ReplaySetup, BoxError>;
}

impl<F> SetupReader for F
where
    F: Fn(&RunFolder) -> Result<ReplaySetup, BoxError> + Sync,
{
    fn read_setup(&self, folder: &RunFolder) -> Result<ReplaySetup, BoxError> {
        self(folder)
    }
}
