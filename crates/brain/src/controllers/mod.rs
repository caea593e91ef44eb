//! The controllers, one per file.

pub mod constant;
pub mod phase;
pub mod random;
