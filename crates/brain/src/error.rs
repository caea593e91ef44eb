//! [`BrainError`]: why a brain could not be parsed, filled or built.

use crate::short_form;
use vsrlab_field::FieldError;

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

impl From<BrainError> for FieldError {
    /// An out-of-range parameter as an error on `brain.<field>`; an unknown brain as an error about
    /// the value as a whole. Shown exactly as the [`BrainError`].
    fn from(e: BrainError) -> Self {
        match e {
            BrainError::Invalid { field, msg } => FieldError::new(field, msg).at("brain"),
            unknown @ BrainError::Unknown(_) => FieldError::message(unknown.to_string()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_brain_error_becomes_a_field_error_shown_the_same() {
        let invalid = BrainError::Invalid {
            field: "hidden",
            msg: "must be at least 1".into(),
        };
        let shown = invalid.to_string();
        let e = FieldError::from(invalid);
        assert_eq!((e.path.as_str(), e.to_string()), ("brain.hidden", shown));
        let unknown = BrainError::Unknown("brian".into());
        let shown = unknown.to_string();
        let e = FieldError::from(unknown);
        assert_eq!((e.path.as_str(), e.to_string()), ("", shown));
    }
}
