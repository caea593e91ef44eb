//! [`BrainError`]: why a brain could not be parsed, filled or built.

use crate::short_form;

/// Why a brain could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BrainError {
    /// A parameter is out of range.
    #[error("brain.{field}: {msg}")]
    Invalid {
        /// The offending field.
        field: &'static str,
        /// What is wrong.
        msg: String,
    },
    /// The brain name is unknown, or its short form is malformed; the message lists every short
    /// form of [`crate::SHORT_FORMS`].
    #[error("unknown brain '{0}': expected {forms}", forms = short_form::expected_forms())]
    Unknown(String),
}
