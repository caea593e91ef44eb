//! `vsrlab-field`: [`FieldError`], the error for a wrong value in a user's file or argument
//! (an experiment file, a robot file, a brain or sensor description, a command-line short form).
//!
//! It carries the dotted path of the field (`brain.hidden[1]`, `task.physics.dt`) apart from the
//! message, so that a caller nests an error under its own field with [`FieldError::at`] and a
//! reader (a config error that points at a line) takes the path as data: no library formats a
//! path into a string and parses it back.
#![warn(missing_docs)]

use std::fmt;

/// A wrong value in a user's file or argument: the dotted path of the field and what is wrong.
///
/// Both parts are public fields: `path` is empty when the error is about the value as a whole
/// (a terrain name, a command-line argument); `message` never repeats the path. Shown as
/// `path: message` ([`FieldError::new`]), or `path message` for an error phrased as a sentence
/// about the field ([`FieldError::sentence`]), or the message alone when the path is empty.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FieldError {
    /// Dotted path of the field (`brain.hidden[1]`); empty: the value as a whole.
    pub path: String,
    /// What is wrong (without the path).
    pub message: String,
    /// How the path and the message are joined when shown.
    phrasing: Phrasing,
}

/// How a [`FieldError`] joins its path and its message.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phrasing {
    /// `path: message`.
    Labelled,
    /// `path message`: the field is the subject of the sentence (`dt must be …`).
    Sentence,
}

impl FieldError {
    /// An error on the field at `path`, shown as `path: message`.
    pub fn new(path: impl Into<String>, message: impl Into<String>) -> FieldError {
        FieldError {
            path: path.into(),
            message: message.into(),
            phrasing: Phrasing::Labelled,
        }
    }

    /// An error about the value as a whole (no field), shown as the message alone until a
    /// caller places it under a field with [`FieldError::at`].
    pub fn message(message: impl Into<String>) -> FieldError {
        FieldError::new(String::new(), message)
    }

    /// An error phrased as a sentence whose subject is the field: `sentence("dt", "must be
    /// positive")` is shown as `dt must be positive`. The range checks of settings read this way;
    /// the path and the message are kept apart all the same.
    pub fn sentence(path: impl Into<String>, message: impl Into<String>) -> FieldError {
        FieldError {
            phrasing: Phrasing::Sentence,
            ..FieldError::new(path, message)
        }
    }

    /// The same error one level down, under the field `parent`: `brain` over `hidden[1]` gives
    /// `brain.hidden[1]`, over an index step `[2]` gives `brain[2]`, over no path `brain`.
    pub fn at(mut self, parent: &str) -> FieldError {
        self.path = join(parent, &self.path);
        self
    }

    /// The same error under the `index`-th element of a list: `[index]` before the path.
    pub fn at_index(self, index: usize) -> FieldError {
        self.at(&format!("[{index}]"))
    }
}

/// `parent` and `child` as one dotted path; an index step (`[k]`) is joined without a dot.
fn join(parent: &str, child: &str) -> String {
    if parent.is_empty() {
        child.to_string()
    } else if child.is_empty() {
        parent.to_string()
    } else if child.starts_with('[') {
        format!("{parent}{child}")
    } else {
        format!("{parent}.{child}")
    }
}

impl fmt::Display for FieldError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.path.is_empty(), self.phrasing) {
            (true, _) => write!(f, "{}", self.message),
            (false, Phrasing::Labelled) => write!(f, "{}: {}", self.path, self.message),
            (false, Phrasing::Sentence) => write!(f, "{} {}", self.path, self.message),
        }
    }
}

impl std::error::Error for FieldError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parents_are_prefixed_with_a_dot_and_indices_without() {
        let e = FieldError::new("hidden[1]", "must be ≥ 1").at("brain");
        assert_eq!(e.path, "brain.hidden[1]");
        assert_eq!(FieldError::message("bad").at("brain").path, "brain");
        assert_eq!(FieldError::new("[2]", "bad").at("sensors").path, "sensors[2]");
        let e = FieldError::new("window", "bad").at_index(3).at("sensors");
        assert_eq!(e.path, "sensors[3].window");
        assert_eq!(FieldError::message("bad").at_index(0).path, "[0]");
        assert_eq!(FieldError::new("dt", "bad").at("").path, "dt");
        assert_eq!(e.message, "bad");
    }

    #[test]
    fn display_joins_path_and_message_or_shows_the_message_alone() {
        assert_eq!(
            FieldError::new("kind", "unknown task").to_string(),
            "kind: unknown task"
        );
        assert_eq!(FieldError::message("expected a table").to_string(), "expected a table");
        let e = FieldError::sentence("dt", "must be a positive number, got 0")
            .at("physics")
            .at("task");
        assert_eq!(e.to_string(), "task.physics.dt must be a positive number, got 0");
        assert_eq!(
            (e.path.as_str(), e.message.as_str()),
            ("task.physics.dt", "must be a positive number, got 0")
        );
        assert_eq!(
            FieldError::message("too many").at("genes").to_string(),
            "genes: too many"
        );
        assert_eq!(FieldError::sentence("", "no subject").to_string(), "no subject");
    }
}
