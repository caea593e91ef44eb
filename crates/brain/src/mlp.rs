//! A fully connected feed-forward network (multi-layer perceptron) with a bias on every neuron.
//!
//! # Parameter layout
//!
//! For layer sizes `[n_0, n_1, …, n_L]` (`n_0` inputs, `n_L` outputs) the flat weight vector is
//! ordered layer → destination neuron → `[bias, one weight per source neuron]`:
//!
//! ```text
//! layer 0→1: neuron 0 of layer 1: [b, w_0, w_1, …, w_{n_0−1}], neuron 1 of layer 1: [b, w_0, …], …
//! layer 1→2: neuron 0 of layer 2: [b, w_0, …, w_{n_1−1}], …
//! …
//! ```
//!
//! so the count is Σ_l n_{l+1}·(n_l + 1) ([`Mlp::parameter_count`]); e.g. 40 inputs, one hidden
//! layer of 26 neurons and 10 outputs give 26·41 + 10·27 = 1336. This is the layout of 2D-VSR-Sim
//! ≥ v1.8 (`MultiLayerPerceptron`, vsr-model.md §4.3). The activation is applied on every layer,
//! the output layer included, and, when `input_activation` is set (2D-VSR-Sim ≥ v1.9.1), also to the
//! raw inputs before the first layer.

use crate::validation::check_finite;
use crate::BrainError;
use serde::{Deserialize, Serialize};
use vsrlab_lanes::{fdlibm_tanh, fdlibm_tanh_in_place};

/// Largest layer of any network (neurons); larger ones are refused, naming `hidden`.
pub const MAX_LAYER_SIZE: usize = 100_000;

/// Most parameters of one brain (50 million weights, 400 MB); more are refused before anything
/// is allocated.
pub const MAX_PARAMETERS: usize = 50_000_000;

/// Refuses a parameter total above [`MAX_PARAMETERS`], naming `hidden`.
pub(crate) fn check_parameter_total(total: usize) -> Result<(), BrainError> {
    check_at_most("hidden", "parameters of the brain", total, MAX_PARAMETERS)
}

/// Refuses `value` above `limit`, naming `field`: the one check behind every size limit.
pub(crate) fn check_at_most(field: &'static str, what: &str, value: usize, limit: usize) -> Result<(), BrainError> {
    if value <= limit {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("{value} {what}, more than the limit of {limit}"),
        })
    }
}

/// The nonlinearity applied by every neuron.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Activation {
    /// tanh(x), in (−1, 1); the thesis' choice everywhere.
    #[default]
    Tanh,
    /// 1 / (1 + e^−x), in (0, 1).
    Sigmoid,
    /// max(0, x).
    Relu,
    /// sin(x), in [−1, 1].
    Sin,
    /// x.
    Identity,
}

impl Activation {
    /// Applies the function to one value.
    #[inline]
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Activation::Tanh => fdlibm_tanh(x),
            Activation::Sigmoid => 1.0 / (1.0 + (-x).exp()),
            Activation::Relu => x.max(0.0),
            Activation::Sin => x.sin(),
            Activation::Identity => x,
        }
    }

    /// Applies the function to every value: tanh four or eight at a time in vector lanes, the
    /// bits of [`Activation::apply`] one at a time.
    #[inline]
    pub fn apply_in_place(self, values: &mut [f64]) {
        match self {
            Activation::Tanh => fdlibm_tanh_in_place(values),
            _ => values.iter_mut().for_each(|v| *v = self.apply(*v)),
        }
    }

    /// Lower-case name, as in configs.
    pub fn name(self) -> &'static str {
        match self {
            Activation::Tanh => "tanh",
            Activation::Sigmoid => "sigmoid",
            Activation::Relu => "relu",
            Activation::Sin => "sin",
            Activation::Identity => "identity",
        }
    }
}

/// A multi-layer perceptron with fixed weights (layout in the module documentation).
///
/// [`Mlp::apply`] allocates nothing: the caller passes a scratch buffer of at least
/// [`Mlp::scratch_len`] values, allocated once.
#[derive(Debug, Clone, PartialEq)]
pub struct Mlp {
    sizes: Vec<usize>,
    activation: Activation,
    input_activation: bool,
    weights: Vec<f64>,
}

impl Mlp {
    /// Number of weights (biases included) of a network with these layer sizes:
    /// Σ_l n_{l+1}·(n_l + 1). Fewer than two sizes means no layer: 0.
    pub fn parameter_count(sizes: &[usize]) -> usize {
        sizes
            .windows(2)
            .map(|p| p[1].saturating_mul(p[0].saturating_add(1)))
            .fold(0, usize::saturating_add)
    }

    /// A network with layer sizes `[n_in, hidden…, n_out]`.
    ///
    /// Errors (field `hidden`) when there are fewer than two sizes or a hidden or output size is 0,
    /// (field `weights`) when the weight count differs from [`Mlp::parameter_count`] or a weight is
    /// not finite. `n_in` may be 0 (the outputs then depend on the biases only).
    pub fn new(
        sizes: Vec<usize>,
        activation: Activation,
        input_activation: bool,
        weights: Vec<f64>,
    ) -> Result<Mlp, BrainError> {
        Mlp::check_sizes(&sizes)?;
        let expected = Mlp::parameter_count(&sizes);
        if weights.len() != expected {
            return Err(BrainError::Invalid {
                field: "weights",
                msg: format!("expected {expected} for layer sizes {sizes:?}, got {}", weights.len()),
            });
        }
        check_finite("weights", &weights)?;
        Ok(Mlp {
            sizes,
            activation,
            input_activation,
            weights,
        })
    }

    /// Checks layer sizes: at least input and output, and no empty hidden or output layer.
    pub(crate) fn check_sizes(sizes: &[usize]) -> Result<(), BrainError> {
        if let Some(&big) = sizes.iter().find(|&&n| n > MAX_LAYER_SIZE) {
            return Err(BrainError::Invalid {
                field: "hidden",
                msg: format!(
                    "a layer of {big} neurons is more than the limit of {MAX_LAYER_SIZE}, got sizes {sizes:?}"
                ),
            });
        }
        if sizes.len() < 2 {
            return Err(BrainError::Invalid {
                field: "hidden",
                msg: format!("a network needs at least an input and an output layer, got sizes {sizes:?}"),
            });
        }
        if sizes[1..].contains(&0) {
            return Err(BrainError::Invalid {
                field: "hidden",
                msg: format!("hidden and output layers need at least one neuron, got sizes {sizes:?}"),
            });
        }
        check_parameter_total(Mlp::parameter_count(sizes))
    }

    /// Layer sizes `[n_in, hidden…, n_out]`.
    pub fn sizes(&self) -> &[usize] {
        &self.sizes
    }
    /// Number of inputs.
    pub fn inputs(&self) -> usize {
        self.sizes[0]
    }
    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.sizes[self.sizes.len() - 1]
    }
    /// The activation function.
    pub fn activation(&self) -> Activation {
        self.activation
    }
    /// Whether the activation is applied to the raw inputs first.
    pub fn input_activation(&self) -> bool {
        self.input_activation
    }
    /// The flat weights (layout in the module documentation).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }
    /// Length of the scratch buffer [`Mlp::apply`] needs: twice the widest layer.
    pub fn scratch_len(&self) -> usize {
        2 * self.sizes.iter().copied().max().unwrap_or(0)
    }

    /// Forward pass: `inputs` (length [`Mlp::inputs`]) → `outputs` (length [`Mlp::outputs`]), using
    /// `scratch` (at least [`Mlp::scratch_len`] values) for the layer activations. No allocation.
    ///
    /// # Panics
    /// If a buffer is too short.
    pub fn apply(&self, inputs: &[f64], outputs: &mut [f64], scratch: &mut [f64]) {
        let n_in = self.inputs();
        let n_out = self.outputs();
        assert!(
            inputs.len() >= n_in,
            "mlp: {} inputs given, {n_in} needed",
            inputs.len()
        );
        assert!(
            outputs.len() >= n_out,
            "mlp: {} outputs given, {n_out} needed",
            outputs.len()
        );
        let widest = self.scratch_len() / 2;
        assert!(
            scratch.len() >= 2 * widest,
            "mlp: scratch of {} values, {} needed",
            scratch.len(),
            2 * widest
        );
        let act = self.activation;
        let (mut current, mut next) = scratch[..2 * widest].split_at_mut(widest);
        current[..n_in].copy_from_slice(&inputs[..n_in]);
        if self.input_activation {
            act.apply_in_place(&mut current[..n_in]);
        }
        for (layer, pair) in self.sizes.windows(2).enumerate() {
            let (n_src, n_dst) = (pair[0], pair[1]);
            self.layer_sums(layer, &current[..n_src], &mut next[..n_dst]);
            act.apply_in_place(&mut next[..n_dst]);
            std::mem::swap(&mut current, &mut next);
        }
        outputs[..n_out].copy_from_slice(&current[..n_out]);
    }

    /// Layer `layer`'s neurons before their activation: `dst[o] = b + Σᵢ wᵢ·src[i]`, summed from
    /// the bias in the sources' order (the sums of [`Mlp::apply`]). Lets a caller with many
    /// networks of one shape apply the activation to all their neurons at once.
    ///
    /// # Panics
    /// If `layer` is not a layer or a slice is shorter than the layer.
    pub fn layer_sums(&self, layer: usize, src: &[f64], dst: &mut [f64]) {
        let offset: usize = self.sizes[..layer + 1].windows(2).map(|p| p[1] * (p[0] + 1)).sum();
        let (n_src, n_dst) = (self.sizes[layer], self.sizes[layer + 1]);
        let src = &src[..n_src];
        let rows = self.weights[offset..offset + n_dst * (n_src + 1)].chunks_exact(n_src + 1);
        for (out, w) in dst[..n_dst].iter_mut().zip(rows) {
            let mut sum = w[0];
            for (wi, xi) in w[1..].iter().zip(src) {
                sum += wi * xi;
            }
            *out = sum;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::assert_invalid;
    use proptest::prelude::*;

    #[test]
    fn parameter_count_matches_the_2d_vsr_sim_check_value() {
        assert_eq!(Mlp::parameter_count(&[40, 26, 10]), 1336);
        assert_eq!(Mlp::parameter_count(&[8, 5]), 45);
        assert_eq!(Mlp::parameter_count(&[3]), 0);
        let m = Mlp::new(vec![40, 26, 10], Activation::Tanh, true, vec![0.0; 1336]).unwrap();
        assert_eq!((m.inputs(), m.outputs(), m.scratch_len()), (40, 10, 80));
    }

    #[test]
    fn forward_pass_of_a_2_2_1_network_by_hand() {
        // hidden neuron 0: bias 0.1, weights 0.5, −0.3; hidden 1: bias −0.2, weights 0.8, 0.4;
        // output: bias 0.05, weights 1.5, −0.7
        let w = vec![0.1, 0.5, -0.3, -0.2, 0.8, 0.4, 0.05, 1.5, -0.7];
        let (x0, x1) = (0.6, -1.2);
        let mut scratch = vec![0.0; 4];
        let mut out = [0.0];

        let raw = Mlp::new(vec![2, 2, 1], Activation::Tanh, false, w.clone()).unwrap();
        raw.apply(&[x0, x1], &mut out, &mut scratch);
        let h0 = (0.1 + 0.5 * x0 - 0.3 * x1).tanh();
        let h1 = (-0.2 + 0.8 * x0 + 0.4 * x1).tanh();
        let y = (0.05 + 1.5 * h0 - 0.7 * h1).tanh();
        assert!((out[0] - y).abs() < 1e-15, "{} vs {y}", out[0]);

        let squashed = Mlp::new(vec![2, 2, 1], Activation::Tanh, true, w).unwrap();
        squashed.apply(&[x0, x1], &mut out, &mut scratch);
        let (t0, t1) = (f64::tanh(x0), f64::tanh(x1));
        let h0 = (0.1 + 0.5 * t0 - 0.3 * t1).tanh();
        let h1 = (-0.2 + 0.8 * t0 + 0.4 * t1).tanh();
        let y = (0.05 + 1.5 * h0 - 0.7 * h1).tanh();
        assert!((out[0] - y).abs() < 1e-15, "{} vs {y}", out[0]);
    }

    #[test]
    fn each_activation_is_applied_on_every_layer() {
        // 1 → 1 → 1 with unit weights and zero biases: y = f(f(x))
        for act in [
            Activation::Tanh,
            Activation::Sigmoid,
            Activation::Relu,
            Activation::Sin,
            Activation::Identity,
        ] {
            let m = Mlp::new(vec![1, 1, 1], act, false, vec![0.0, 1.0, 0.0, 1.0]).unwrap();
            let mut out = [0.0];
            for x in [-2.0, -0.5, 0.0, 0.7, 3.0] {
                m.apply(&[x], &mut out, &mut [0.0; 2]);
                assert_eq!(out[0], act.apply(act.apply(x)), "{}", act.name());
            }
        }
        assert_eq!(Activation::Sigmoid.apply(0.0), 0.5);
        assert_eq!(Activation::Relu.apply(-3.0), 0.0);
    }

    #[test]
    fn no_input_network_outputs_its_biases() {
        let m = Mlp::new(vec![0, 2], Activation::Identity, true, vec![0.25, -0.5]).unwrap();
        let mut out = [0.0; 2];
        m.apply(&[], &mut out, &mut [0.0; 4]);
        assert_eq!(out, [0.25, -0.5]);
    }

    #[test]
    fn bad_sizes_and_weights_are_errors_naming_the_field() {
        let err = Mlp::new(vec![4, 3], Activation::Tanh, true, vec![0.0; 14]).unwrap_err();
        assert_eq!(
            err,
            BrainError::Invalid {
                field: "weights",
                msg: "expected 15 for layer sizes [4, 3], got 14".into()
            }
        );
        let mut w = vec![0.0; 15];
        w[7] = f64::NAN;
        let err = Mlp::new(vec![4, 3], Activation::Tanh, true, w).unwrap_err().to_string();
        assert!(err.contains("weights") && err.contains("value 7 is NaN"), "{err}");
        for sizes in [vec![4], vec![4, 0, 3], vec![4, 0]] {
            let err = Mlp::new(sizes, Activation::Tanh, true, vec![]).unwrap_err();
            assert_invalid(&err, "hidden");
        }
    }

    proptest! {
        #[test]
        fn tanh_outputs_stay_in_minus_one_one(
            weights in proptest::collection::vec(-50.0f64..50.0, Mlp::parameter_count(&[5, 7, 3])),
            inputs in proptest::collection::vec(-1e6f64..1e6, 5),
            input_activation in any::<bool>(),
        ) {
            let m = Mlp::new(vec![5, 7, 3], Activation::Tanh, input_activation, weights).unwrap();
            let mut out = [0.0; 3];
            let mut scratch = vec![0.0; m.scratch_len()];
            m.apply(&inputs, &mut out, &mut scratch);
            for y in out {
                prop_assert!((-1.0..=1.0).contains(&y), "{}", y);
            }
        }
    }
}
