//! `vsrlab-tasks`: worlds, tasks, the one episode loop, outcomes and fitness.
//!
//! - [`Task`] (`task.rs`): what a robot is asked to do; [`TaskSpec`] and [`registry::TASKS`]
//!   list the kinds ([`Locomotion`], [`Jump`], [`Escape`], [`Carrier`]) for configs and the
//!   command line.
//! - [`Robot`] / [`Agent`] (`agent.rs`): a robot before and after it is put in a world.
//! - Robot kinds (`kinds/`, [`ROBOT_KINDS`]): each in its own folder with its robot-file form and
//!   command-line short form: the voxel robot ([`RobotSpec`], `kinds/voxel/`) and the
//!   pressure-based soft agent ([`PsaRobot`], thesis ch. 6, `kinds/psa/`); [`AnyRobot`] holds a
//!   robot of any kind, [`kinds::from_short_forms`] builds one from the command line.
//! - [`episode::run`]: the one loop, physics → sense → control → actuate (vsr-model.md §2.2),
//!   pure in (robot, task, seed).
//! - [`evaluate`] (`representation.rs`): genotype → robot → episode → outcome, through a
//!   [`Mapper`] for any genotype type.
#![warn(missing_docs)]

pub mod agent;
pub mod body_part;
pub mod body_summary;
pub mod carrier;
pub mod channels;
pub mod damage;
pub mod ensemble;
pub mod episode;
pub mod escape;
pub mod files;
pub mod fitness;
pub mod fixed_body;
pub mod java_random;
pub mod jump;
pub mod kinds;
pub mod locomotion;
pub mod outcome;
pub mod registry;
pub mod representation;
pub mod task;
pub mod terrain;

pub use agent::{Agent, Robot};
pub use body_summary::BodySummary;
pub use carrier::Carrier;
pub use damage::Damage;
pub use episode::{Episode, EpisodeError};
/// Type-erased serialisation, which a body form's [`body_part::BodyFormCopy::as_serialize`] returns.
pub use erased_serde;
pub use escape::Escape;
pub use fitness::Fitness;
pub use jump::Jump;
pub use kinds::psa::robot::{PsaAgent, PsaRobot};
pub use kinds::voxel::robot::{RobotError, RobotSpec};
pub use kinds::voxel::short_forms::{RobotArgsError, RobotPart};
pub use kinds::{AnyRobot, RobotArgs, RobotDescription, RobotKind, ROBOT_KINDS};
pub use locomotion::Locomotion;
pub use outcome::{DamageRecord, Outcome, Polygons, Recorded, Trace, TraceLevel};
pub use registry::{FieldError, TaskParseError, TaskSpec};
pub use representation::{
    evaluate, evaluate_traced, BodyPart, BodySource, EvaluationError, Mapper, Representation, Stored, StoredGenotypes,
};
pub use task::{Flow, Metrics, Objective, RigidTask, Sense, Task};
pub use terrain::Terrain;
pub use vsrlab_body::{Channel, Probe};
