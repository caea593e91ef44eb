//! A policy learned by reinforcement learning (the co-design loop's PPO, `vsrlab-learning`), kept
//! as a brain so that a learned robot can be saved, replayed and drawn like any other: the
//! readings are normalised by the running statistics PPO ended with
//! (((x − mean) / √(var + 10⁻⁸)) clipped to ±10), pass through tanh hidden layers and a linear
//! output layer (the Gaussian policy's mean, without noise), and each output a becomes an
//! actuation, in one of two ways that map the policy's action space onto the robot's:
//!
//! - `scale`, `offset`: clamp(scale · a + offset, −1, 1);
//! - `target` ([`TargetAction`]): the environment's target t = clamp(a + shift, low, high), as
//!   actuation (t − centre) / half_range, so that a robot whose actuation o drives the target
//!   centre + half_range · o gets t to the last bit (the learned fitness replays exactly).
//!
//! # Parameter layout
//!
//! Layer by layer from the input: the layer's weights row by row (one row of inputs per output),
//! then its biases; sizes `[n_inputs, hidden…, n_outputs]`, all readings in, one output per unit.

use crate::validation::{check_count, check_finite, check_units, finite, set_finite};
use crate::{BrainError, BrainKind, BrainShape, Controller};
use serde::{Deserialize, Serialize};
use vsrlab_lanes::fdlibm_tanh_in_place;

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
    /// Each output a is applied as clamp(scale · a + offset, −1, 1) (default 1; not with `target`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<f64>,
    /// See `scale` (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub offset: Option<f64>,
    /// The environment's target convention, instead of `scale` and `offset`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetAction>,
    /// Weights and biases (module docs).
    #[serde(default)]
    pub weights: Vec<f64>,
}

/// An action that is an offset from a target, as EvoGym's: the target t = clamp(a + shift, low,
/// high) becomes the actuation (t − centre) / half_range. Not clamped to ±1: for EvoGym's range
/// [0.6, 1.6] around 1.1, t = 0.6 gives −1.0000000000000002, which maps back to 0.6 exactly where
/// −1 would give 0.6000000000000001. `half_range` should be a power of two for an exact round trip.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TargetAction {
    /// Added to the action (EvoGym: 1, the rest length ratio).
    pub shift: f64,
    /// Lowest target (EvoGym: 0.6).
    pub low: f64,
    /// Highest target (EvoGym: 1.6).
    pub high: f64,
    /// The target of actuation 0 (EvoGym's robots in vsrlab: 1.1).
    pub centre: f64,
    /// Target change per unit of actuation (EvoGym's robots in vsrlab: 0.5).
    pub half_range: f64,
}

impl TargetAction {
    fn check(&self) -> Result<(), BrainError> {
        for (field, v) in [
            ("target.shift", self.shift),
            ("target.low", self.low),
            ("target.high", self.high),
            ("target.centre", self.centre),
            ("target.half_range", self.half_range),
        ] {
            finite(field, v)?;
        }
        if self.low > self.high {
            return Err(BrainError::Invalid {
                field: "target.high",
                msg: format!("must be at least target.low ({}), got {}", self.low, self.high),
            });
        }
        if self.half_range <= 0.0 {
            return Err(BrainError::Invalid {
                field: "target.half_range",
                msg: format!("must be > 0, got {}", self.half_range),
            });
        }
        Ok(())
    }

    /// The actuation of action `a`.
    #[inline]
    fn actuation(&self, a: f64) -> f64 {
        ((a + self.shift).clamp(self.low, self.high) - self.centre) / self.half_range
    }
}

/// How a policy's action becomes an actuation, resolved from the spec's fields.
#[derive(Debug, Clone, Copy)]
enum ActionMap {
    Affine { scale: f64, offset: f64 },
    Target(TargetAction),
}

impl ActionMap {
    fn of(spec: &PolicySpec) -> Result<ActionMap, BrainError> {
        let Some(target) = spec.target else {
            let (scale, offset) = (spec.scale.unwrap_or(1.0), spec.offset.unwrap_or(0.0));
            finite("scale", scale)?;
            finite("offset", offset)?;
            return Ok(ActionMap::Affine { scale, offset });
        };
        for (field, given) in [("scale", spec.scale), ("offset", spec.offset)] {
            if given.is_some() {
                return Err(BrainError::Invalid {
                    field,
                    msg: "give either target or scale and offset, not both".into(),
                });
            }
        }
        target.check()?;
        Ok(ActionMap::Target(target))
    }

    #[inline]
    fn actuation(&self, a: f64) -> f64 {
        match self {
            ActionMap::Affine { scale, offset } => (scale * a + offset).clamp(-1.0, 1.0),
            ActionMap::Target(t) => t.actuation(a),
        }
    }
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
        let action = ActionMap::of(self)?;
        let widest = sizes.iter().copied().max().unwrap_or(0);
        Ok(Box::new(PolicyController {
            spec: self.clone(),
            action,
            sizes,
            layers: [vec![0.0; widest], vec![0.0; widest]],
        }))
    }
}

/// The controller of a [`PolicySpec`]; allocation-free per step.
#[derive(Debug, Clone)]
pub struct PolicyController {
    spec: PolicySpec,
    action: ActionMap,
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
                output[o] = z;
            }
            if l != last {
                fdlibm_tanh_in_place(&mut output[..outputs]);
            }
            offset += inputs * outputs + outputs;
            std::mem::swap(input, output);
        }
        for (a, z) in actuations.iter_mut().zip(input.iter()) {
            *a = self.action.actuation(*z);
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
            scale: Some(2.0),
            offset: Some(-0.2),
            target: None,
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

    fn evogym_target() -> TargetAction {
        TargetAction {
            shift: 1.0,
            low: 0.6,
            high: 1.6,
            centre: 1.1,
            half_range: 0.5,
        }
    }

    /// A robot that drives centre + half_range · o gets EvoGym's clipped target 1 + a to the last
    /// bit, at the range's ends too (where clamping o to ±1 would miss by an ulp).
    #[test]
    fn a_target_action_round_trips_to_the_clipped_target_bit_for_bit() {
        let t = evogym_target();
        for i in 0..=4000 {
            let a = -1.5 + 3.0 * i as f64 / 4000.0;
            let o = t.actuation(a);
            assert_eq!(
                (1.1 + 0.5 * o).to_bits(),
                (1.0 + a).clamp(0.6, 1.6).to_bits(),
                "a = {a}"
            );
        }
        assert_eq!(1.1 + 0.5 * t.actuation(-3.0), 0.6);
        let clamped = t.actuation(-3.0).clamp(-1.0, 1.0);
        assert_ne!(1.1 + 0.5 * clamped, 0.6, "clamping the actuation would miss the end");
    }

    #[test]
    fn target_and_scale_exclude_each_other_and_are_checked() {
        let both = PolicySpec {
            target: Some(evogym_target()),
            ..spec()
        };
        assert!(matches!(
            both.build(&shape(2, 2)),
            Err(BrainError::Invalid { field: "scale", .. })
        ));
        let mut target = PolicySpec {
            scale: None,
            offset: None,
            target: Some(evogym_target()),
            ..spec()
        };
        let mut c = target.build(&shape(2, 2)).unwrap();
        let mut a = [0.0; 2];
        c.control(0.0, &[3.0, 0.5], &mut a);
        assert!(a.iter().all(|o| (-1.0000000000000002..=1.0).contains(o)), "{a:?}");
        target.target = Some(TargetAction {
            half_range: 0.0,
            ..evogym_target()
        });
        assert!(matches!(
            target.build(&shape(2, 2)),
            Err(BrainError::Invalid {
                field: "target.half_range",
                ..
            })
        ));
        let json = serde_json::to_string(&BrainSpec::Policy(target.clone())).unwrap();
        assert!(!json.contains("scale"), "{json}");
        let back: BrainSpec = serde_json::from_str(&json).unwrap();
        assert_eq!(back, BrainSpec::Policy(target));
    }
}
