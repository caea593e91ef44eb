//! What can go wrong making or stepping an EvoGym environment.

use vsrlab_field::FieldError;
use vsrlab_physics::mass_spring::MassSpringError;

/// Errors of [`EvoGymEnv`](super::EvoGymEnv). None of them panics.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvoGymError {
    /// The robot's grid is not a valid robot; the error names the field.
    #[error("robot: {0}")]
    Robot(FieldError),
    /// The robot does not fit the task's world (it overlaps an object).
    #[error("world: {0}")]
    World(FieldError),
    /// The physics engine refused the world or a step.
    #[error("physics: {0}")]
    Physics(MassSpringError),
    /// `step` got a number of actions other than the robot's number of actuators.
    #[error("expected {expected} actions (one per actuator voxel), got {got}")]
    ActionCount {
        /// Actuators of the robot.
        expected: usize,
        /// Actions passed.
        got: usize,
    },
    /// An action was NaN or infinite.
    #[error("action {index} is not finite ({value})")]
    NonFiniteAction {
        /// Its position.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// `step` after the episode ended (goal, instability or its length): call `reset`.
    #[error("the episode is over: reset the environment first")]
    EpisodeOver,
    /// Environments given to lanes that cannot step them together (too many, another body or
    /// task, a missing action list).
    #[error("{0}")]
    Lanes(String),
}
