//! A dense network with tanh hidden layers and a linear output, its parameters in one flat
//! vector (each layer's weights, row-major by output, then its biases), with a forward pass
//! that keeps the activations and a backward pass that accumulates parameter gradients.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use vsrlab_lanes::fdlibm_tanh;

/// A multilayer perceptron: `sizes[0]` inputs, tanh hidden layers, `sizes[last]` linear outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Mlp {
    sizes: Vec<usize>,
    /// Weights and biases of every layer, flat.
    pub parameters: Vec<f64>,
}

/// The activations of one forward pass: the input, then each layer's output.
#[derive(Debug, Clone, PartialEq)]
pub struct Activations(Vec<Vec<f64>>);

impl Activations {
    /// The network's output.
    pub fn output(&self) -> &[f64] {
        self.0.last().expect("at least the input")
    }
}

impl Mlp {
    /// A network of these layer sizes, weights drawn from N(0, gain²/fan-in) (hidden layers
    /// gain √2, the output layer `output_gain`, as the orthogonal initialisation of the PPO
    /// reference scales them), biases 0.
    pub fn new(sizes: &[usize], output_gain: f64, rng: &mut ChaCha8Rng) -> Mlp {
        assert!(sizes.len() >= 2, "an input and an output size");
        let mut parameters = Vec::new();
        for (l, pair) in sizes.windows(2).enumerate() {
            let (inputs, outputs) = (pair[0], pair[1]);
            let gain = if l + 2 == sizes.len() {
                output_gain
            } else {
                std::f64::consts::SQRT_2
            };
            let sd = gain / (inputs.max(1) as f64).sqrt();
            for _ in 0..inputs * outputs {
                parameters.push(sd * standard_normal(rng));
            }
            parameters.extend(std::iter::repeat_n(0.0, outputs));
        }
        Mlp {
            sizes: sizes.to_vec(),
            parameters,
        }
    }

    /// Layer sizes, input first.
    pub fn sizes(&self) -> &[usize] {
        &self.sizes
    }

    /// Values of the output layer.
    pub fn outputs(&self) -> usize {
        *self.sizes.last().expect("checked at construction")
    }

    /// The output for `input`, keeping every layer's activation for [`Mlp::backward`].
    pub fn forward(&self, input: &[f64]) -> Activations {
        assert_eq!(input.len(), self.sizes[0], "input size");
        let mut layers = vec![input.to_vec()];
        let mut offset = 0;
        let last = self.sizes.len() - 2;
        for (l, pair) in self.sizes.windows(2).enumerate() {
            let (inputs, outputs) = (pair[0], pair[1]);
            let (w, b) = self.parameters[offset..offset + inputs * outputs + outputs].split_at(inputs * outputs);
            let x = layers.last().expect("the input at least");
            let y: Vec<f64> = (0..outputs)
                .map(|o| {
                    let z = b[o]
                        + w[o * inputs..(o + 1) * inputs]
                            .iter()
                            .zip(x)
                            .map(|(a, b)| a * b)
                            .sum::<f64>();
                    if l == last {
                        z
                    } else {
                        fdlibm_tanh(z)
                    }
                })
                .collect();
            offset += inputs * outputs + outputs;
            layers.push(y);
        }
        Activations(layers)
    }

    /// Adds to `gradient` (one value per parameter) the gradient of a loss whose derivative with
    /// respect to the outputs of the pass `activations` is `output_gradient`.
    pub fn backward(&self, activations: &Activations, output_gradient: &[f64], gradient: &mut [f64]) {
        assert_eq!(gradient.len(), self.parameters.len(), "one gradient per parameter");
        let layers = &activations.0;
        let mut delta = output_gradient.to_vec();
        let mut end = self.parameters.len();
        for l in (0..self.sizes.len() - 1).rev() {
            let (inputs, outputs) = (self.sizes[l], self.sizes[l + 1]);
            let start = end - inputs * outputs - outputs;
            let x = &layers[l];
            for o in 0..outputs {
                gradient[start + inputs * outputs + o] += delta[o];
                let row = start + o * inputs;
                for i in 0..inputs {
                    gradient[row + i] += delta[o] * x[i];
                }
            }
            if l > 0 {
                // through the weights, then the tanh of the layer below (its output is x)
                delta = (0..inputs)
                    .map(|i| {
                        let back: f64 = (0..outputs)
                            .map(|o| delta[o] * self.parameters[start + o * inputs + i])
                            .sum();
                        back * (1.0 - x[i] * x[i])
                    })
                    .collect();
            }
            end = start;
        }
    }
}

/// A draw from N(0, 1) (Box–Muller).
pub fn standard_normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1: f64 = rng.random_range(f64::EPSILON..1.0);
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn the_backward_pass_matches_finite_differences() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut net = Mlp::new(&[3, 5, 4, 2], 1.0, &mut rng);
        for p in net.parameters.iter_mut().rev().take(6) {
            *p += 0.3; // biases away from 0
        }
        let input = [0.3, -0.7, 1.1];
        // loss = 0.5 · Σ (y − t)²
        let target = [0.2, -0.4];
        let loss = |n: &Mlp| -> f64 {
            let y = n.forward(&input);
            y.output()
                .iter()
                .zip(target)
                .map(|(a, b)| 0.5 * (a - b) * (a - b))
                .sum()
        };
        let pass = net.forward(&input);
        let dy: Vec<f64> = pass.output().iter().zip(target).map(|(a, b)| a - b).collect();
        let mut gradient = vec![0.0; net.parameters.len()];
        net.backward(&pass, &dy, &mut gradient);
        for (k, &analytic) in gradient.iter().enumerate() {
            let h = 1e-6;
            let mut up = net.clone();
            up.parameters[k] += h;
            let mut down = net.clone();
            down.parameters[k] -= h;
            let numeric = (loss(&up) - loss(&down)) / (2.0 * h);
            assert!(
                (numeric - analytic).abs() < 1e-7,
                "parameter {k}: {numeric} vs {analytic}"
            );
        }
    }

    #[test]
    fn the_output_layer_starts_as_small_as_its_gain() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let net = Mlp::new(&[8, 64, 64, 3], 0.01, &mut rng);
        assert_eq!(net.parameters.len(), 8 * 64 + 64 + 64 * 64 + 64 + 64 * 3 + 3);
        let y = net.forward(&[0.5; 8]);
        assert!(y.output().iter().all(|v| v.abs() < 0.1), "{:?}", y.output());
    }
}
