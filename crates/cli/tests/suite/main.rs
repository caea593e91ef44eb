//! Every integration test of this crate in one binary (one link instead of one per file: CI
//! time); each file is a module.

mod analyze;
mod attention;
mod bench;
mod campaign;
mod codesign;
mod common;
mod ensemble;
mod evaluate;
mod fidelity;
mod fuzz;
mod graph;
mod hebbian;
mod identity;
mod psa;
mod readme;
mod robot_files;
mod run;
mod view;
mod voxels3d;
