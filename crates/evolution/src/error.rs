//! Errors of the optimizers: misuse of the ask/tell protocol, malformed evaluations and invalid
//! configurations. Each message says what was expected so the caller can fix the call.

use thiserror::Error;

/// Everything that can go wrong when configuring or driving an optimizer.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum EvolutionError {
    /// A configuration value is out of its valid range.
    #[error("invalid configuration: {0}")]
    InvalidConfig(String),
    /// `tell` was called without a preceding `ask`.
    #[error("tell() called with no batch pending: call ask() first")]
    NoPendingBatch,
    /// The results do not match the pending batch (count, unknown or repeated ids).
    #[error("results do not match the asked batch of {expected} candidates: {detail}")]
    BatchMismatch {
        /// Size of the pending batch.
        expected: usize,
        /// What is wrong with the results.
        detail: String,
    },
    /// An evaluation has the wrong number of objectives.
    #[error("candidate {id}: expected {expected} objective value(s), got {got}")]
    ObjectiveCount {
        /// Candidate id.
        id: usize,
        /// Objectives the optimizer was configured with.
        expected: usize,
        /// Objectives supplied.
        got: usize,
    },
    /// An evaluation has a descriptor of the wrong length (MAP-Elites).
    #[error("candidate {id}: expected a descriptor of length {expected}, got {got}")]
    DescriptorLength {
        /// Candidate id.
        id: usize,
        /// Descriptor dimensions of the archive.
        expected: usize,
        /// Length supplied.
        got: usize,
    },
    /// The stop criteria can never stop a run.
    #[error("no stop criterion set: give a maximum number of evaluations or generations")]
    Unbounded,
}
