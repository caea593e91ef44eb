//! A 3D soft-voxel engine on the model of Voxelyze (Hiller & Lipson, 2014) and voxcraft-sim:
//! cubic voxels (position, orientation, linear and angular momentum) joined face to face by
//! 6-DOF Euler–Bernoulli beams, internal (bond), global and collision damping, a floor with
//! static and kinetic Coulomb friction, thermal actuation as a voxel's rest size, gravity, and
//! semi-implicit Euler steps at the model's stable time step.
//!
//! What it knows: materials, voxels on a cubic lattice, the links between face neighbours,
//! per-voxel temperature, fixed degrees of freedom and external loads. Nothing of robots.
//! `docs/voxelyze-model.md` gives every rule with its source; `docs/voxels3d.md` what this
//! engine does and does not do yet (linear elastic, Poisson's ratio 0 as the affordance study
//! ran).

mod axis;
mod batching;
mod collision;
mod collision_lanes;
mod error;
mod floor;
pub mod laned_worlds;
mod lanes;
mod link;
mod link_batches;
#[doc(hidden)]
pub mod link_lanes;
mod material;
mod quat;
mod voxel;
mod voxel_batches;
#[doc(hidden)]
pub mod voxel_lanes;
mod world;
pub mod world_lanes;

#[cfg(test)]
mod validation;

pub use error::Physics3dError;
pub use material::Material;
pub use world::{Dof, VoxelId, World, WorldSettings, STANDARD_GRAVITY};
