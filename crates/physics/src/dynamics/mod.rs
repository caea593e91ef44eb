//! Dynamics: bodies, constraints and the solver that moves them.
//!
//! A step is a pipeline of named stages (see [`world::World::step`]): integrate forces, detect
//! contacts, then several sub-steps each solving springs, ropes and contacts and integrating
//! positions, then restitution and bookkeeping.

pub(crate) mod broad_phase;
pub mod builder;
pub(crate) mod colour;
pub(crate) mod contact;
pub(crate) mod contact_batch;
pub(crate) mod dyn4j_contacts;
pub mod pressure;
pub(crate) mod rope;
pub(crate) mod sequential;
pub mod settings;
pub(crate) mod simd;
pub(crate) mod soft;
pub(crate) mod spring;
pub mod world;
