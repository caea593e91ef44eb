//! Every integration test of this crate in one binary (one link instead of one per file: CI
//! time); each file is a module.

mod common;
mod damage;
mod determinism;
mod external_control;
mod fidelity;
mod field_errors;
mod psa;
mod representation;
mod robustness;
mod second_body;
