//! `vsrlab-brain`: controllers that turn sensor readings into voxel actuations.
//!
//! Every controller implements [`Controller`]: at each control step it receives the time and all
//! voxels' readings (voxel order = grid order over the non-empty cells, row-major from the bottom
//! row: index = y·W + x) and writes one actuation per voxel in [-1, 1] (same order; positive
//! contracts).
//!
//! A [`BrainSpec`] describes a brain in configs and robot files and builds the controller for a
//! body. Parameterised brains (MLPs, per-voxel phases) expose their parameter vector through
//! [`BrainSpec::parameter_count`], [`BrainSpec::parameters`] and [`BrainSpec::with_parameters`], so
//! that an optimizer can treat the brain as a flat genotype; each controller module documents its
//! parameter layout.
#![warn(missing_docs)]

pub mod controllers;
pub mod mlp;
mod spec;

pub use controllers::centralized_mlp::CentralizedMlpController;
pub use controllers::constant::ConstantController;
pub use controllers::distributed_mlp::{DistributedConfig, DistributedMlpController, Layout};
pub use controllers::phase::PhaseController;
pub use controllers::phase_grid::{PhaseGridController, PhaseLayout};
pub use controllers::random::RandomController;
pub use controllers::smoothed::SmoothedController;
pub use controllers::step::StepController;
pub use mlp::{Activation, Mlp};
pub use spec::BrainSpec;

/// A brain: maps (time, readings) to actuations, possibly with internal state.
pub trait Controller: Send {
    /// Clears internal state, as at the start of an episode.
    fn reset(&mut self);
    /// Computes one actuation per voxel (grid order) from all readings (grid order).
    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]);
}

/// Why a brain could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BrainError {
    /// A parameter is out of range.
    #[error("brain.{field}: {msg}")]
    Invalid {
        /// The offending field.
        field: &'static str,
        /// What is wrong.
        msg: String,
    },
    /// The brain name is unknown.
    #[error(
        "unknown brain '{0}': expected phase, phase-grid[:freq], constant:<value>, random[:<period s>], \
         mlp[:<hidden sizes, comma separated, or none>], distributed-mlp[:<signals>], \
         distributed-mlp-hetero[:<signals>], step:<period s>:<brain> or smoothed:<speed>:<brain>"
    )]
    Unknown(String),
}
