//! The controllers, one per file.

pub mod attention;
pub mod centralized_mlp;
pub mod constant;
pub mod distributed_mlp;
pub mod elman;
pub mod graph;
pub mod heads;
pub mod hebbian;
pub mod phase;
pub mod phase_grid;
pub mod policy;
pub mod random;
pub mod smoothed;
pub mod step;
mod wrapper;
