//! The activation functions a NEAT node may have (those of neat-python, which EvoGym's
//! CPPN-NEAT used).

use serde::{Deserialize, Serialize};
use vsrlab_lanes::fdlibm_tanh;

/// A node's activation function.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Activation {
    /// 1 / (1 + e^(−5x)), neat-python's steepened sigmoid.
    Sigmoid,
    /// tanh(2.5x), neat-python's.
    Tanh,
    /// sin(5x), neat-python's.
    Sin,
    /// e^(−5x²), neat-python's Gaussian.
    Gauss,
    /// max(0, x).
    Relu,
    /// x.
    Identity,
    /// |x|.
    Abs,
}

impl Activation {
    /// Every activation, in a fixed order (for mutation).
    pub const ALL: [Activation; 7] = [
        Activation::Sigmoid,
        Activation::Tanh,
        Activation::Sin,
        Activation::Gauss,
        Activation::Relu,
        Activation::Identity,
        Activation::Abs,
    ];

    /// The function's value at `x` (inputs clamped as neat-python does, so that it never
    /// overflows).
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Activation::Sigmoid => 1.0 / (1.0 + (-5.0 * x.clamp(-60.0, 60.0)).exp()),
            Activation::Tanh => fdlibm_tanh(2.5 * x.clamp(-60.0, 60.0)),
            Activation::Sin => (5.0 * x.clamp(-60.0, 60.0)).sin(),
            Activation::Gauss => (-5.0 * x.clamp(-3.4, 3.4).powi(2)).exp(),
            Activation::Relu => x.max(0.0),
            Activation::Identity => x,
            Activation::Abs => x.abs(),
        }
    }
}
