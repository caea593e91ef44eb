//! `vsrlab-tasks`: worlds, tasks, the one episode loop, outcomes and fitness.
//!
//! - [`Task`] (`task.rs`): what a robot is asked to do; [`TaskSpec`] and [`registry::TASKS`]
//!   list the kinds ([`Locomotion`], [`Jump`], [`Escape`], [`Carrier`]) for configs and the
//!   command line.
//! - [`Robot`] / [`Agent`] (`agent.rs`): a robot before and after it is put in a world;
//!   [`RobotSpec`] (the voxel robot of robot files) is one, [`PsaRobot`] (the pressure-based
//!   soft agent, thesis ch. 6) another; [`RobotSpec::from_short_forms`]
//!   (`short_forms.rs`) builds one from the command line's body, preset, sensors and brain.
//! - [`episode::run`]: the one loop, physics → sense → control → actuate (vsr-model.md §2.2),
//!   pure in (robot, task, seed).
//! - [`evaluate`] (`representation.rs`): genotype → robot → episode → outcome, through a
//!   [`Mapper`] for any genotype type.
#![warn(missing_docs)]

pub mod agent;
pub mod carrier;
pub mod channels;
pub mod damage;
pub mod ensemble;
pub mod episode;
pub mod escape;
pub mod files;
pub mod fitness;
pub mod java_random;
pub mod jump;
pub mod locomotion;
pub mod outcome;
pub mod psa_inflation;
pub mod psa_robot;
pub mod registry;
pub mod representation;
pub mod robot;
pub mod short_forms;
pub mod task;
pub mod terrain;
pub mod voxel_robot;

pub use agent::{Agent, Robot};
pub use carrier::Carrier;
pub use damage::Damage;
pub use episode::{Episode, EpisodeError};
pub use escape::Escape;
pub use fitness::Fitness;
pub use jump::Jump;
pub use locomotion::Locomotion;
pub use outcome::{DamageRecord, Outcome, Polygons, Recorded, Trace, TraceLevel};
pub use psa_robot::{PsaAgent, PsaRobot};
pub use registry::{FieldError, TaskParseError, TaskSpec};
pub use representation::{evaluate, evaluate_traced, BodyPart, EvaluationError, Mapper, Representation};
pub use robot::{RobotError, RobotSpec};
pub use short_forms::{RobotArgsError, RobotPart};
pub use task::{Flow, Metrics, Objective, Sense, Task};
pub use terrain::Terrain;
pub use vsrlab_body::{Channel, Probe};
