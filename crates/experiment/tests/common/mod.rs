//! Helpers shared by the experiment crate's integration tests.

use vsrlab_experiment::runner::{Flow, Observer, Progress, RunOptions};

/// Interrupts the run after `after` generations of run `run`, as a kill would.
pub struct Killer {
    /// The run to interrupt.
    pub run: usize,
    /// After how many of its generations.
    pub after: u64,
}

impl Observer for Killer {
    fn generation(&mut self, progress: &Progress) -> Flow {
        if progress.run == self.run && progress.generation >= self.after {
            Flow::Interrupt
        } else {
            Flow::Continue
        }
    }
}

/// Two worker threads, resuming or not.
pub fn two_threads(resume: bool) -> RunOptions {
    RunOptions {
        threads: 2,
        resume,
        ..RunOptions::default()
    }
}
