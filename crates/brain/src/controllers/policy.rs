//! A policy learned by reinforcement learning (the co-design loop's PPO, `vsrlab-learning`), kept
//! as a brain so that a learned robot can be saved, replayed and drawn like any other: the
//! readings are normalised by the running statistics PPO ended with
//! (((x − mean) / √(var + 10⁻⁸)) clipped to ±10), pass through tanh hidden layers and a linear
//! output layer (the Gaussian policy's mean, without noise), and each output a becomes the
//! actuation clamp(scale · a + offset, −1, 1), which maps the policy's action space onto the
//! robot's actuation range.
//!
//! # Parameter layout
//!
//! Layer by layer from the input: the layer's weights row by row (one row of inputs per output),
//! then its biases; sizes `[n_inputs, hidden…, n_outputs]`, all readings in, one output per unit.

use crate::validation::{check_count, check_finite, check_units, finite, set_finite};
use crate::{BrainError, BrainKind, BrainShape, Controller};
use serde::{Deserialize, Serialize};

/// Added to the variance before its root.
const EPSILON: f64 = 1e-8;
/// Normalised readings are clipped to ± this.
const CLIP: f64 = 10.0;

/// Description of a learned policy (`{"kind": "policy", …}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolicySpec {
    /// Hidden layer sizes (tanh).
    pub hidden: Vec<usize>,
    /// Running mean of each reading.
    pub mean: Vec<f64>,
    /// Running variance of each reading.
    pub var: Vec<f64>,
    /// Each output a is applied as clamp(scale · a + offset, −1, 1).
    pub scale: f64,
    /// See `scale`.
    pub offset: f64,
    /// Weights and biases (module docs).
    #[serde(default)]
    pub weights: Vec<f64>,
}

impl PolicySpec {
    fn sizes(&self, shape: &BrainShape) -> Vec<usize> {
        let inputs: usize = shape.readings().iter().sum();
        [vec![inputs], self.hidden.clone(), vec![shape.units()]].concat()
    }
}

/// The parameters of layers of these sizes.
fn parameter_count(sizes: &[usize]) -> usize {
    sizes.windows(2).map(|p| p[0] * p[1] + p[1]).sum()
}

impl BrainKind for PolicySpec {
    fn name(&self) -> &'static str {
        "policy"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_units(shape)?;
        if self.hidden.contains(&0) {
            return Err(BrainError::Invalid {
                field: "hidden",
                msg: "every hidden layer needs at least one neuron".into(),
            });
        }
        Ok(parameter_count(&self.sizes(shape)))
    }

    fn parameters(&self) -> &[f64] {
        &self.weights
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("weights", &mut self.weights, params)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        let sizes = self.sizes(shape);
        check_count("weights", self.parameter_count(shape)?, self.weights.len())?;
        check_count("mean", sizes[0], self.mean.len())?;
        check_count("var", sizes[0], self.var.len())?;
        check_finite("weights", &self.weights)?;
        check_finite("mean", &self.mean)?;
        check_finite("var", &self.var)?;
        if self.var.iter().any(|&v| v < 0.0) {
            return Err(BrainError::Invalid {
                field: "var",
                msg: "variances must be ≥ 0".into(),
            });
        }
        finite("scale", self.scale)?;
        finite("offset", self.offset)?;
        let widest = sizes.iter().copied().max().unwrap_or(0);
        Ok(Box::new(PolicyController {
            spec: self.clone(),
            sizes,
            layers: [vec![0.0; widest], vec![0.0; widest]],
        }))
    }
}

/// The controller of a [`PolicySpec`]; allocation-free per step.
#[derive(Debug, Clone)]
pub struct PolicyController {
    spec: PolicySpec,
    sizes: Vec<usize>,
    /// The current layer's input and output.
    layers: [Vec<f64>; 2],
}

impl Controller for PolicyController {
    fn reset(&mut self) {}

    fn control(&mut self, _t: f64, readings: &[f64], actuations: &mut [f64]) {
        let [input, output] = &mut self.layers;
        for (i, x) in readings.iter().enumerate() {
            input[i] = ((x - self.spec.mean[i]) / (self.spec.var[i] + EPSILON).sqrt()).clamp(-CLIP, CLIP);
        }
        let mut offset = 0;
        let last = self.sizes.len() - 2;
        for (l, pair) in self.sizes.windows(2).enumerate() {
            let (inputs, outputs) = (pair[0], pair[1]);
            let (w, b) = self.spec.weights[offset..offset + inputs * outputs + outputs].split_at(inputs * outputs);
            for o in 0..outputs {
                let z = b[o]
                    + w[o * inputs..(o + 1) * inputs]
                        .iter()
                        .zip(&input[..inputs])
                        .map(|(a, b)| a * b)
                        .sum::<f64>();
                output[o] = if l == last { z } else { z.tanh() };
            }
            offset += inputs * outputs + outputs;
            std::mem::swap(input, output);
        }
        for (a, z) in actuations.iter_mut().zip(input.iter()) {
            *a = (self.spec.scale * z + self.spec.offset).clamp(-1.0, 1.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BrainSpec, UnitSet};

    fn shape(readings: usize, units: usize) -> BrainShape {
        let mut per_unit = vec![0; units];
        per_unit[0] = readings;
        BrainShape::new(UnitSet::new(units), per_unit)
    }

    fn spec() -> PolicySpec {
        // 2 readings → 1 tanh neuron → 2 outputs
        PolicySpec {
            hidden: vec![1],
            mean: vec![1.0, 0.0],
            var: vec![4.0, 1.0],
            scale: 2.0,
            offset: -0.2,
            weights: vec![0.5, -1.0, 0.1, 1.0, -3.0, 0.0, 0.2],
        }
    }

    #[test]
    fn readings_are_normalised_passed_through_the_layers_and_mapped() {
        let mut c = spec().build(&shape(2, 2)).unwrap();
        let mut a = [0.0; 2];
        c.control(0.0, &[3.0, 0.5], &mut a);
        let x = [(3.0 - 1.0) / (4.0f64 + 1e-8).sqrt(), 0.5 / (1.0f64 + 1e-8).sqrt()];
        let h = (0.1 + 0.5 * x[0] - 1.0 * x[1]).tanh();
        let expected = [
            (2.0 * (0.0 + 1.0 * h) - 0.2).clamp(-1.0, 1.0),
            (2.0 * (0.2 - 3.0 * h) - 0.2).clamp(-1.0, 1.0),
        ];
        assert!(
            (a[0] - expected[0]).abs() < 1e-12 && (a[1] - expected[1]).abs() < 1e-12,
            "{a:?} {expected:?}"
        );
        // a reading 1000 deviations away is clipped to 10
        c.control(0.0, &[2001.0, 0.0], &mut a);
        let h = (0.1 + 0.5 * 10.0f64).tanh();
        assert!((a[0] - (2.0 * h - 0.2).clamp(-1.0, 1.0)).abs() < 1e-12, "{a:?}");
    }

    #[test]
    fn the_spec_reads_from_json_and_refuses_what_does_not_fit() {
        let json = serde_json::to_string(&BrainSpec::Policy(spec())).unwrap();
        let back: BrainSpec = serde_json::from_str(&json).unwrap();
        assert_eq!(back, BrainSpec::Policy(spec()));
        assert_eq!(back.parameter_count(&shape(2, 2)), Ok(7));
        let short = PolicySpec {
            mean: vec![0.0],
            ..spec()
        };
        assert!(matches!(
            short.build(&shape(2, 2)),
            Err(BrainError::Invalid { field: "mean", .. })
        ));
        let negative = PolicySpec {
            var: vec![1.0, -1.0],
            ..spec()
        };
        assert!(matches!(
            negative.build(&shape(2, 2)),
            Err(BrainError::Invalid { field: "var", .. })
        ));
        let e = serde_json::from_str::<BrainSpec>(
            r#"{"kind": "policy", "hidden": [1], "mean": [], "var": [], "scale": 1, "offset": 0, "bias": 3}"#,
        )
        .unwrap_err();
        assert!(e.to_string().contains("bias"), "{e}");
    }
}
