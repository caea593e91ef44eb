//! Body–brain co-design (thesis ch. 5.2): an outer evolutionary loop over bodies (EvoGym material
//! grids, made by a direct or a CPPN encoding, [`body`]) and, for every body, an inner PPO
//! training that learns its controller on an EvoGym task ([`learn()`]). A body's fitness is the
//! mean reward per step of one off-line episode of the policy PPO ends with (eq. 5.7); the
//! evaluation also records the learning curve, the same quantity after every PPO iteration.
//!
//! The genotype kinds `material-grid` and `cppn` ([`crate::genotypes`]) run experiments through
//! [`CodesignEvaluator`], which makes each evaluation the pure function (genotype, task, seed) →
//! outcome that the runner parallelises, checkpoints and resumes like any other.

pub mod body;
mod evaluator;
mod learn;
mod settings;

pub use body::{cppn_body, kept_body, OUTPUT_MATERIALS};
pub use evaluator::{material_shares, BodyOf, CodesignEvaluator, MATERIAL_COLUMNS};
pub use learn::{learn, learned_robot, policy_brain, Episode, LearnError, Learned, LEARNING_CURVE, TRAINING_REWARD};
pub use settings::{
    codesign_evaluator, column_figures, evogym_task, implied_representation, run_codesign, time_codesign, timed_ppo,
    validate_codesign, FITNESS_NAME, TIMED_ITERATIONS,
};
