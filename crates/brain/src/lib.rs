//! `vsrlab-brain`: controllers that turn sensor readings into actuations, for any robot kind.
//!
//! Every controller implements [`Controller`]: at each control step it receives the time and all
//! units' readings (unit order; on a voxel grid the voxel order = grid order over the non-empty
//! cells, row-major from the bottom row: index = y·W + x) and writes one actuation per unit in
//! [-1, 1] (same order; positive contracts a voxel).
//!
//! A [`BrainSpec`] describes a brain in configs and robot files and builds the controller for a
//! body's [`BrainShape`]: its units, the readings count of each and their [`UnitLayout`] (a 2D
//! grid, a 3D grid, a ring, a plain set; the `layout` module). Brains ask the shape, never a body
//! type, so every brain runs on every robot kind whose layout answers its questions.
//! Parameterised brains (MLPs, per-voxel phases) expose their parameter vector through
//! [`BrainSpec::parameter_count`], [`BrainSpec::parameters`] and [`BrainSpec::with_parameters`], so
//! that an optimizer can treat the brain as a flat genotype; each controller module documents its
//! parameter layout.
//!
//! # Where things are
//!
//! - `controllers/<name>.rs`: one brain kind each — the controller, its description (e.g.
//!   [`MlpSpec`]) with its serde form and its [`BrainKind`] implementation, and its command-line
//!   short form(s);
//! - `kind.rs`: the [`BrainKind`] trait every description implements;
//! - `shape.rs`: [`BrainShape`]; `layout/`: [`UnitLayout`] and its implementations (one file
//!   each: [`GridLayout`], [`Grid3Layout`], [`RingLayout`], [`UnitSet`]);
//! - `spec.rs`: [`BrainSpec`], the list of registered kinds (the only `match` over them);
//! - `short_form.rs`: [`SHORT_FORMS`], the registry of command-line forms;
//! - `mlp.rs`: the network shared by the MLP controllers; `validation.rs`: field checks.
//!
//! # How to add a brain
//!
//! 1. Write `controllers/my_brain.rs` (and `pub mod my_brain;` in `controllers/mod.rs`): the
//!    [`Controller`]; a description struct `MyBrainSpec` deriving `Debug, Clone, PartialEq,
//!    Serialize, Deserialize` with `#[serde(deny_unknown_fields)]`; `impl BrainKind for
//!    MyBrainSpec` (`name` is the kebab-case variant name; the other methods default to a
//!    parameterless brain, or to a wrapper of the brain its `inner` names); and
//!    `pub const SHORT_FORM: ShortForm` with its parse function.
//! 2. Register it in `spec.rs`: a variant `MyBrain(MyBrainSpec)` of [`BrainSpec`] (its JSON/TOML
//!    tag is `"my-brain"`) and one arm in each of [`BrainSpec::as_kind`] and
//!    [`BrainSpec::as_kind_mut`].
//! 3. Add `controllers::my_brain::SHORT_FORM` to [`SHORT_FORMS`] in `short_form.rs`: the command
//!    line accepts it and the "unknown brain" message lists it.
//!
//! Nothing else matches on the kinds; the tests in `spec.rs` check every variant's `name` against
//! its tag.
//!
//! # How to add a layout
//!
//! A robot kind whose units are arranged in a new way (a tree of links, a hexagonal grid) writes
//! one type implementing [`UnitLayout`] (units, cells, neighbours per direction and opposite
//! directions) and builds its [`BrainShape`] with [`BrainShape::new`]; no brain changes. The
//! layout tests in `layout/mod.rs` check any layout's neighbours for symmetry.
#![warn(missing_docs)]

mod controller;
pub mod controllers;
mod error;
pub mod graph_modules;
pub mod graph_ops;
pub mod graph_transfer;
mod kind;
pub mod layout;
pub mod mlp;
mod shape;
mod short_form;
mod spec;
#[cfg(test)]
mod testing;
mod validation;

pub use controller::{plastic_weights, Controller, PLASTIC_WEIGHTS};
pub use controllers::attention::{AttentionController, AttentionSpec};
pub use controllers::centralized_mlp::{CentralizedMlpController, MlpSpec};
pub use controllers::constant::{ConstantController, ConstantSpec};
pub use controllers::distributed_mlp::{DistributedConfig, DistributedMlpController, DistributedMlpSpec, Layout};
pub use controllers::graph::{EdgeSpec, GraphController, GraphSpec, NeuronSpec};
pub use controllers::heads::{HeadsController, HeadsSpec};
pub use controllers::hebbian::{HebbianController, HebbianModel, HebbianSpec, Normalisation, WeightInit};
pub use controllers::phase::{PhaseController, PhaseSpec};
pub use controllers::phase_grid::{PhaseGridController, PhaseGridSpec, PhaseLayout};
pub use controllers::policy::{PolicyController, PolicySpec, TargetAction};
pub use controllers::random::{RandomController, RandomSpec};
pub use controllers::smoothed::{SmoothedController, SmoothedSpec};
pub use controllers::step::{StepController, StepSpec};
pub use error::BrainError;
pub use kind::BrainKind;
pub use layout::{Grid3Layout, GridLayout, RingLayout, UnitLayout, UnitSet};
pub use mlp::{Activation, Mlp};
pub use shape::BrainShape;
pub use short_form::{ShortForm, SHORT_FORMS};
pub use spec::BrainSpec;
