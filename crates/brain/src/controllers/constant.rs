//! A controller that applies the same actuation to every voxel, always.

use crate::Controller;

/// Constant actuation (calibration runs, passive bodies with value 0).
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantController {
    /// Actuation applied to every voxel.
    pub value: f64,
}

impl Controller for ConstantController {
    fn reset(&mut self) {}
    fn control(&mut self, _t: f64, _readings: &[f64], actuations: &mut [f64]) {
        actuations.fill(self.value);
    }
}
