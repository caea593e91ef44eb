//! What the wrapper brains (`step`, `smoothed`) share at run time: the controller they wrap, run at
//! every control step, and its latest actuations, which they post-process. Their descriptions share
//! the defaults of [`crate::BrainKind`] for a brain with an inner brain.

use crate::Controller;

/// A wrapper's inner controller and the actuations it computed last.
pub(crate) struct Inner {
    controller: Box<dyn Controller>,
    actuations: Vec<f64>,
}

impl Inner {
    /// Wraps `controller` for a body of `voxels` voxels.
    pub(crate) fn new(controller: Box<dyn Controller>, voxels: usize) -> Inner {
        Inner {
            controller,
            actuations: vec![0.0; voxels],
        }
    }

    /// Runs the inner controller; returns its actuations, one per voxel.
    pub(crate) fn control(&mut self, t: f64, readings: &[f64]) -> &[f64] {
        self.controller.control(t, readings, &mut self.actuations);
        &self.actuations
    }

    /// The inner controller, whose channels the wrapper publishes as its own.
    pub(crate) fn controller(&self) -> &dyn Controller {
        self.controller.as_ref()
    }

    /// Resets the inner controller.
    pub(crate) fn reset(&mut self) {
        self.controller.reset();
    }
}
