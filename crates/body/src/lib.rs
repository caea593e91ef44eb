//! `vsrlab-body`: voxel-based soft robots on top of `vsrlab-physics`.
//!
//! A voxel is four rigid corner squares joined by 18 soft distance constraints (and, in the 2021
//! preset, 4 ropes); neighbouring voxels are welded at their facing corners (vsr-model.md §1).
//! Actuation in [-1, 1] changes the springs' rest lengths (positive contracts). This crate also
//! holds morphologies (named shapes and text grids) and sensors, and the second body kind: the
//! pressure-based soft agent ([`psa`]).
#![warn(missing_docs)]

pub mod body;
pub mod descriptors;
pub mod encodings;
pub mod morphology;
pub mod params;
pub mod probe;
pub mod psa;
pub mod robot;
pub mod sensors;
pub mod voxel;

pub use body::Body;
pub use descriptors::MorphologyDescriptors;
pub use morphology::{Morphology, MorphologyError};
pub use params::{Preset, VoxelParams};
pub use probe::{Capture, Channel, Probe};
pub use robot::{VoxelState, Vsr};
