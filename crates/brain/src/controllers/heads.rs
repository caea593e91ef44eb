//! Linear heads: one layer from all readings to all outputs, tanh on the first outputs and none on
//! the last `linear_outputs` (thesis §6.2.3: the PSA's springs controller s = tanh(W_s o + b_s)
//! and pressure controller Δp = W_p o + b_p). Inputs are used as read (no input activation).
//!
//! Parameters: one row per output, bias first, then one weight per input (the [`crate::mlp`]
//! layout of a network without hidden layers): (n_in + 1) · n_out. For a PSA of n masses with
//! full control: (3n+4)(n+1) = 374 / 784 / 1,344 for 10 / 15 / 20 masses.

use crate::mlp::{Activation, Mlp};
use crate::short_form::{self, ShortForm};
use crate::validation::{check_count, check_units, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};
use vsrlab_lanes::fdlibm_tanh_in_place;

/// The heads controller: a one-layer network whose last outputs skip the tanh.
#[derive(Debug, Clone)]
pub struct HeadsController {
    mlp: Mlp,
    linear_outputs: usize,
    scratch: Vec<f64>,
}

impl Controller for HeadsController {
    fn reset(&mut self) {}

    fn control(&mut self, _t: f64, readings: &[f64], actuations: &mut [f64]) {
        self.mlp.apply(readings, actuations, &mut self.scratch);
        let n = self.mlp.outputs();
        fdlibm_tanh_in_place(&mut actuations[..n - self.linear_outputs]);
    }
}

/// Description of a heads brain (`{"kind": "heads", "linear_outputs": 1, "weights": [...]}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HeadsSpec {
    /// How many of the last outputs are linear (no tanh); default 1, the PSA's Δp.
    pub linear_outputs: usize,
    /// The weights, one row per output (bias first); default none (a template).
    pub weights: Vec<f64>,
}

impl Default for HeadsSpec {
    fn default() -> Self {
        HeadsSpec {
            linear_outputs: 1,
            weights: Vec::new(),
        }
    }
}

impl HeadsSpec {
    fn sizes(shape: &BrainShape) -> [usize; 2] {
        [shape.readings().iter().sum(), shape.units()]
    }
}

impl BrainKind for HeadsSpec {
    fn name(&self) -> &'static str {
        "heads"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_units(shape)?;
        let sizes = HeadsSpec::sizes(shape);
        Mlp::check_sizes(&sizes)?;
        if self.linear_outputs > sizes[1] {
            return Err(BrainError::Invalid {
                field: "linear_outputs",
                msg: format!(
                    "{} linear outputs for a brain of {} outputs",
                    self.linear_outputs, sizes[1]
                ),
            });
        }
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
        let sizes = HeadsSpec::sizes(shape);
        // identity everywhere; the tanh heads are applied after
        let mlp = Mlp::new(sizes.to_vec(), Activation::Identity, false, self.weights.clone())?;
        let scratch = vec![0.0; mlp.scratch_len()];
        Ok(Box::new(HeadsController {
            mlp,
            linear_outputs: self.linear_outputs,
            scratch,
        }))
    }
}

/// `heads` (the last output linear) or `heads:<linear outputs>`.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "heads",
    usage: "heads[:<linear outputs>]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let linear_outputs = match argument {
        None => 1,
        Some(k) => short_form::count(k)?,
    };
    Some(BrainSpec::Heads(HeadsSpec {
        linear_outputs,
        weights: Vec::new(),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_body::Morphology;

    fn row(n: usize) -> Morphology {
        Morphology::from_fn(n, 1, |_, _| true).unwrap()
    }

    #[test]
    fn parameter_counts_of_the_three_psa_sizes() {
        for (masses, expected) in [(10, 374), (15, 784), (20, 1344)] {
            let mut rpv = vec![3; masses + 1];
            let m = row(masses + 1);
            assert_eq!(
                HeadsSpec::default()
                    .parameter_count(&BrainShape::grid(&m, &rpv))
                    .unwrap(),
                expected
            );
            // without pressure control: n outputs, the whole body's readings on the last unit
            rpv.pop();
            rpv[masses - 1] += 3;
            let spec = HeadsSpec {
                linear_outputs: 0,
                ..HeadsSpec::default()
            };
            assert_eq!(
                spec.parameter_count(&BrainShape::grid(&row(masses), &rpv)).unwrap(),
                (3 * masses + 4) * masses
            );
        }
    }

    #[test]
    fn tanh_heads_then_linear_heads() {
        // 2 inputs → 3 outputs, the last linear: rows (bias, w1, w2)
        let weights = vec![0.0, 1.0, 0.0, 0.5, 0.0, 1.0, 1.0, 2.0, 3.0];
        let spec = HeadsSpec {
            linear_outputs: 1,
            weights,
        };
        let mut c = spec.build(&BrainShape::grid(&row(3), &[1, 1, 0])).unwrap();
        let mut out = [0.0; 3];
        c.control(0.0, &[2.0, -1.0], &mut out);
        assert!((out[0] - 2f64.tanh()).abs() < 1e-12);
        assert!((out[1] - (-0.5f64).tanh()).abs() < 1e-12);
        assert!((out[2] - (1.0 + 4.0 - 3.0)).abs() < 1e-12, "linear: {}", out[2]);
        let bad = HeadsSpec {
            linear_outputs: 4,
            weights: Vec::new(),
        };
        let err = bad.parameter_count(&BrainShape::grid(&row(3), &[1, 1, 0])).unwrap_err();
        assert!(err.to_string().contains("linear_outputs"), "{err}");
    }
}
