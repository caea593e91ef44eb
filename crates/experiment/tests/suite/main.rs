//! Every integration test of this crate in one binary (one link instead of one per file: CI
//! time); each file is a module.

mod campaign;
mod codesign;
mod common;
mod config;
mod evogym;
mod graph_brain;
mod graph_genotype;
mod psa;
mod remote;
mod runner;
mod third_robot_kind;
mod toy_genotype_kind;
