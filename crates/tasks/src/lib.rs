//! `vsrlab-tasks`: worlds, terrains, the episode loop and fitness.
//!
//! An episode is a pure function of (robot, task, seed): [`locomotion::run`] builds the world,
//! places the robot, and steps physics → sense → control → set rest lengths (vsr-model.md §2.2).
#![warn(missing_docs)]

pub mod files;
pub mod java_random;
pub mod locomotion;
pub mod outcome;
pub mod representation;
pub mod robot;
pub mod terrain;

pub use locomotion::{EpisodeError, Locomotion};
pub use outcome::{Outcome, Trace, TraceLevel};
pub use representation::{evaluate, evaluate_traced, BodyPart, EvaluationError, Representation};
pub use robot::RobotSpec;
pub use terrain::Terrain;
