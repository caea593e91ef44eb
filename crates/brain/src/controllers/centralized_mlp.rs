//! Centralized MLP controller (2D-VSR-Sim `CentralizedSensing`, vsr-model.md §4.2): one network
//! sees every reading and drives every voxel.
//!
//! # Parameter layout
//!
//! Inputs: all readings, in voxel order (row-major from the bottom row), each voxel's readings in
//! sensor order; n_in = Σ_v readings_v. Outputs: one actuation per voxel, same order. The weights are
//! those of an [`Mlp`] with sizes `[n_in, hidden…, n_voxels]` (layout in [`crate::mlp`]). With the
//! default hidden layer (one layer of max(2, round(0.65·n_in)) neurons, [`default_hidden`]) a
//! biped-4x3 (10 voxels) with 4 readings per voxel has 40 inputs, 26 hidden neurons and 1336 weights.

use crate::mlp::Mlp;
use crate::Controller;

/// The hidden layer 2D-VSR-Sim's drivers use by default: one layer of max(2, round(0.65·n_in)).
pub fn default_hidden(n_inputs: usize) -> Vec<usize> {
    vec![((0.65 * n_inputs as f64).round() as usize).max(2)]
}

/// One MLP from all readings to all actuations; the actuations are clamped to [−1, 1] (a no-op with
/// tanh).
#[derive(Debug, Clone)]
pub struct CentralizedMlpController {
    mlp: Mlp,
    scratch: Vec<f64>,
}

impl CentralizedMlpController {
    /// Wraps a network whose inputs are all readings and whose outputs are the voxels.
    pub fn new(mlp: Mlp) -> Self {
        let scratch = vec![0.0; mlp.scratch_len()];
        CentralizedMlpController { mlp, scratch }
    }

    /// The network.
    pub fn mlp(&self) -> &Mlp {
        &self.mlp
    }
}

impl Controller for CentralizedMlpController {
    fn reset(&mut self) {}

    fn control(&mut self, _t: f64, readings: &[f64], actuations: &mut [f64]) {
        debug_assert_eq!(readings.len(), self.mlp.inputs());
        debug_assert_eq!(actuations.len(), self.mlp.outputs());
        self.mlp.apply(readings, actuations, &mut self.scratch);
        for a in actuations.iter_mut() {
            *a = a.clamp(-1.0, 1.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mlp::Activation;

    #[test]
    fn default_hidden_layer_follows_the_0_65_rule() {
        assert_eq!(default_hidden(40), vec![26]);
        assert_eq!(default_hidden(0), vec![2]);
        assert_eq!(default_hidden(1), vec![2]);
        assert_eq!(default_hidden(10), vec![7]); // 6.5 rounds up, as Java's Math.round
        assert_eq!(Mlp::parameter_count(&[40, 26, 10]), 1336);
    }

    #[test]
    fn each_output_drives_its_voxel_and_is_clamped() {
        // 2 inputs → 3 outputs, identity: out_j = bias_j + readings·w_j
        let w = vec![0.1, 1.0, 0.0, -0.2, 0.0, 1.0, 5.0, 0.0, 0.0];
        let mlp = Mlp::new(vec![2, 3], Activation::Identity, false, w).unwrap();
        let mut c = CentralizedMlpController::new(mlp);
        let mut a = [0.0; 3];
        c.control(1.0 / 60.0, &[0.3, -0.4], &mut a);
        assert_eq!(a, [0.1 + 0.3, -0.2 - 0.4, 1.0]);
    }
}
