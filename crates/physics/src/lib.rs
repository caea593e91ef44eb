//! `vsrlab-physics`: a 2D rigid-body engine written for one workload: small scenes (a handful to a
//! few hundred bodies) joined by many soft distance constraints, simulated for thousands of steps,
//! millions of times.
//!
//! What it provides: rigid bodies with rotation; soft distance constraints ("springs") set by a
//! natural frequency and a damping ratio whose rest length may change every step; minimum-distance
//! ropes; rigid welds (welded parts are merged into one rigid body, exactly rigid and free of cost);
//! contacts with Coulomb friction and restitution between convex polygons and against static
//! polygons; gravity (any vector, including none for top-down worlds); linear and angular damping;
//! external forces; ray casts against static geometry; circles (dynamic only); parts that never
//! rotate; gas pressure inside closed rings of parts.
//!
//! Guarantees: a step allocates nothing once the world is warm; the same world stepped the same
//! way gives bit-identical states (no hashing, no threads, fixed iteration order); a state that
//! becomes non-finite is reported as [`PhysicsError::NonFinite`] instead of propagating NaNs.
//!
//! Beside it, [`mass_spring`] is a separate point-mass and spring engine that reproduces EvoGym's
//! soft-voxel physics (RK4, tracked rest lengths, penalty contacts) without knowing about voxels.
//!
//! Layout follows the rapier/parry seam: [`geometry`] answers "where do shapes touch, where does a
//! ray hit"; [`dynamics`] answers "how do bodies move".
#![warn(missing_docs)]

pub mod dynamics;
pub mod geometry;
pub mod mass_spring;
mod math;

pub use dynamics::{
    builder::{PartDesc, PressureRingDesc, RopeDesc, SpringDesc, WorldBuilder},
    pressure::EdgeLength,
    settings::{ContactModel, Dyn4jVersion, Solver, SpringMassModel, WorldSettings},
    world::{PartHandle, RingHandle, RopeHandle, SpringHandle, World},
};
pub use geometry::shape::Polygon;
pub use math::{Rot, Vec2};

/// Errors the engine reports instead of panicking or silently producing NaNs.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PhysicsError {
    /// A body's position or velocity became NaN or infinite during a step.
    #[error("physics state became non-finite at step {step} (body {body}): the simulation exploded")]
    NonFinite {
        /// Index of the step (counted from 0) at which the state was found non-finite.
        step: u64,
        /// Index of the first offending simulated body.
        body: usize,
    },
    /// A world description is invalid (bad mass, empty polygon, unknown handle...).
    #[error("invalid world description: {0}")]
    Invalid(String),
}
