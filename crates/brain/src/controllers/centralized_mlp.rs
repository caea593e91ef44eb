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
//!
//! Short forms: `mlp` (default hidden layer), `mlp:<sizes>` (e.g. `mlp:26` or `mlp:16,8`),
//! `mlp:none` (no hidden layer).

use crate::mlp::{Activation, Mlp};
use crate::short_form::{self, ShortForm};
use crate::validation::{check_count, check_units, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};

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

/// Description of a centralized MLP brain (`{"kind": "mlp", …}`): all readings in, one actuation
/// per voxel out (module documentation). Every field has a default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MlpSpec {
    /// Hidden layer sizes; absent = one layer of max(2, round(0.65·n_inputs)) neurons
    /// (2D-VSR-Sim's default, [`default_hidden`]), `[]` = no hidden layer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hidden: Option<Vec<usize>>,
    /// Activation of every layer (default tanh).
    pub activation: Activation,
    /// Apply the activation to the raw inputs first (2D-VSR-Sim ≥ v1.9.1; default true).
    pub input_activation: bool,
    /// The weights ([`crate::mlp`] layout), sizes `[n_inputs, hidden…, n_voxels]`; default none
    /// (a template).
    pub weights: Vec<f64>,
}

impl Default for MlpSpec {
    fn default() -> Self {
        MlpSpec {
            hidden: None,
            activation: Activation::Tanh,
            input_activation: true,
            weights: Vec::new(),
        }
    }
}

impl MlpSpec {
    /// Layer sizes for a body: `[n_inputs, hidden…, n_voxels]`.
    fn sizes(&self, shape: &BrainShape) -> Vec<usize> {
        let n_in: usize = shape.readings().iter().sum();
        let mut sizes = vec![n_in];
        match &self.hidden {
            Some(h) => sizes.extend_from_slice(h),
            None => sizes.extend(default_hidden(n_in)),
        }
        sizes.push(shape.units());
        sizes
    }
}

impl BrainKind for MlpSpec {
    fn name(&self) -> &'static str {
        "mlp"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_units(shape)?;
        let sizes = self.sizes(shape);
        Mlp::check_sizes(&sizes)?;
        Ok(Mlp::parameter_count(&sizes))
    }

    fn parameters(&self) -> &[f64] {
        &self.weights
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("weights", &mut self.weights, params)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        let expected = self.parameter_count(shape)?;
        check_count("weights", expected, self.weights.len())?;
        let sizes = self.sizes(shape);
        let mlp = Mlp::new(sizes, self.activation, self.input_activation, self.weights.clone())?;
        Ok(Box::new(CentralizedMlpController::new(mlp)))
    }
}

/// `mlp` (default hidden layer), `mlp:<sizes>` (comma separated) or `mlp:none` (no hidden layer).
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "mlp",
    usage: "mlp[:<hidden sizes, comma separated, or none>]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let hidden = match argument.map(str::trim) {
        None => None,
        Some("none") => Some(Vec::new()),
        Some(list) => Some(list.split(',').map(short_form::count).collect::<Option<Vec<_>>>()?),
    };
    Some(BrainSpec::Mlp(MlpSpec {
        hidden,
        ..MlpSpec::default()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped, build_error};

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

    #[test]
    fn the_spec_counts_the_check_values() {
        let (m, rpv) = biped();
        assert_eq!(
            BrainSpec::parse("mlp")
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv)),
            Ok(1336)
        );
        assert_eq!(
            BrainSpec::parse("mlp:none")
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv)),
            Ok(10 * 41)
        );
    }

    #[test]
    fn build_rejects_missing_weights_wrong_readings_and_empty_layers() {
        let (m, rpv) = biped();
        let err = build_error(&BrainSpec::parse("mlp").unwrap(), &rpv);
        assert_eq!(
            err,
            BrainError::Invalid {
                field: "weights",
                msg: "expected 1336 for this body and sensors, got 0".into()
            }
        );
        let err = build_error(&BrainSpec::parse("mlp").unwrap(), &[4; 9]);
        assert_invalid(&err, "readings_per_voxel");
        let err = BrainSpec::parse("mlp:4,0")
            .unwrap()
            .parameter_count(&BrainShape::grid(&m, &rpv))
            .unwrap_err();
        assert_invalid(&err, "hidden");
    }
}
