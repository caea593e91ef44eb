//! Progress notes of the long pipelines (what is being replayed, warnings about robots that
//! could not be): the caller decides where they go.

/// Receives one line of progress at a time, from any thread.
pub trait Progress: Sync {
    /// One line of progress (no trailing newline).
    fn note(&self, line: &str);
}

impl<F: Fn(&str) + Sync> Progress for F {
    fn note(&self, line: &str) {
        self(line)
    }
}

/// Progress to standard error, one line per note.
#[derive(Debug, Clone, Copy, Default)]
pub struct Stderr;

impl Progress for Stderr {
    fn note(&self, line: &str) {
        eprintln!("{line}");
    }
}

/// Progress discarded.
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Progress for Quiet {
    fn note(&self, _line: &str) {}
}
