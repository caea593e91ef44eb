//! The MLP's forward and backward passes over a whole minibatch, with the bits of the
//! one-sample passes ([`Mlp::forward`], [`Mlp::backward`]) row by row.
//!
//! Every sum keeps the order and the start (−0.0, as `Iterator::sum`) of its one-sample
//! counterpart, so the speed comes only from doing several independent sums side by side: a
//! forward pass computes four outputs of a sample at once from the transposed weights, a backward
//! pass four weights' gradients (or four inputs' deltas) at once, each adding its samples in
//! order. The lanes are plain arrays of four that the compiler keeps in vector registers; no
//! allocation once the buffers have grown.

use crate::mlp::Mlp;
use vsrlab_lanes::fdlibm_tanh_in_place;

/// Lanes side by side.
const LANES: usize = 4;

/// One forward pass over a batch: each layer's values, a row per sample (the input first), and
/// the buffers of the backward pass.
#[derive(Debug, Clone, Default)]
pub struct BatchPass {
    rows: usize,
    layers: Vec<Vec<f64>>,
    /// Transposed weights of one layer (inputs × outputs).
    transposed: Vec<f64>,
    delta: Vec<f64>,
    below: Vec<f64>,
    /// The rows a backward pass adds, in order.
    active: Vec<usize>,
}

impl BatchPass {
    /// Row `row` of the network's output.
    pub fn output(&self, row: usize) -> &[f64] {
        let last = self.layers.last().expect("a pass holds its input");
        let width = last.len() / self.rows.max(1);
        &last[row * width..(row + 1) * width]
    }
}

impl Mlp {
    /// The layer sizes and the weights and biases of layer `l` (its weights row-major by output).
    fn layer(&self, l: usize) -> (usize, usize, &[f64], &[f64]) {
        let sizes = self.sizes();
        let start: usize = sizes.windows(2).take(l).map(|p| p[0] * p[1] + p[1]).sum();
        let (inputs, outputs) = (sizes[l], sizes[l + 1]);
        let (w, b) = self.parameters[start..start + inputs * outputs + outputs].split_at(inputs * outputs);
        (inputs, outputs, w, b)
    }

    /// The outputs for `rows` inputs (`input` row-major), keeping every layer for
    /// [`Mlp::backward_batch`]: row by row the bits of [`Mlp::forward`].
    pub fn forward_batch(&self, input: &[f64], rows: usize, pass: &mut BatchPass) {
        assert_eq!(input.len(), rows * self.sizes()[0], "input size");
        let depth = self.sizes().len();
        pass.rows = rows;
        pass.layers.resize_with(depth, Vec::new);
        pass.layers[0].clear();
        pass.layers[0].extend_from_slice(input);
        for l in 0..depth - 1 {
            let (inputs, outputs, w, b) = self.layer(l);
            transpose(w, outputs, inputs, &mut pass.transposed);
            let (done, rest) = pass.layers.split_at_mut(l + 1);
            let (x, y) = (&done[l], &mut rest[0]);
            y.clear();
            y.resize(rows * outputs, 0.0);
            for s in 0..rows {
                let xs = &x[s * inputs..(s + 1) * inputs];
                layer_row(&pass.transposed, b, xs, &mut y[s * outputs..(s + 1) * outputs]);
            }
            if l + 2 < depth {
                fdlibm_tanh_in_place(y);
            }
        }
    }

    /// Adds to `gradient` the gradients of the rows of `pass` whose `active` flag is set, row
    /// `s`'s output gradient being row `s` of `output_gradient`: the bits of calling
    /// [`Mlp::backward`] on those rows in order.
    pub fn backward_batch(&self, pass: &mut BatchPass, output_gradient: &[f64], active: &[bool], gradient: &mut [f64]) {
        assert_eq!(gradient.len(), self.parameters.len(), "one gradient per parameter");
        let rows = pass.rows;
        assert_eq!(active.len(), rows, "one flag per row");
        pass.delta.clear();
        pass.delta.extend_from_slice(output_gradient);
        pass.active.clear();
        pass.active.extend((0..rows).filter(|&s| active[s]));
        let mut end = self.parameters.len();
        for l in (0..self.sizes().len() - 1).rev() {
            let (inputs, outputs, w, _) = self.layer(l);
            let start = end - inputs * outputs - outputs;
            let x = &pass.layers[l];
            let (weights_g, bias_g) = gradient[start..end].split_at_mut(inputs * outputs);
            for &s in &pass.active {
                for (g, d) in bias_g.iter_mut().zip(&pass.delta[s * outputs..(s + 1) * outputs]) {
                    *g += d;
                }
            }
            weight_gradients(weights_g, &pass.delta, x, &pass.active, inputs, outputs);
            if l > 0 {
                pass.below.clear();
                pass.below.resize(rows * inputs, 0.0);
                for &s in &pass.active {
                    let delta = &pass.delta[s * outputs..(s + 1) * outputs];
                    let xs = &x[s * inputs..(s + 1) * inputs];
                    back_row(w, delta, xs, &mut pass.below[s * inputs..(s + 1) * inputs]);
                }
                std::mem::swap(&mut pass.delta, &mut pass.below);
            }
            end = start;
        }
    }
}

/// `w` (rows × columns, row-major) transposed into `out`.
fn transpose(w: &[f64], rows: usize, columns: usize, out: &mut Vec<f64>) {
    out.clear();
    out.resize(rows * columns, 0.0);
    for r in 0..rows {
        for c in 0..columns {
            out[c * rows + r] = w[r * columns + c];
        }
    }
}

/// One sample through one layer before its activation: y[o] = b[o] + Σᵢ w[o][i]·x[i], from the
/// transposed weights `wt`.
fn layer_row(wt: &[f64], b: &[f64], x: &[f64], y: &mut [f64]) {
    row_times_matrix(x, wt, y);
    for (out, bias) in y.iter_mut().zip(b) {
        *out += bias;
    }
}

/// out[c] = Σᵣ v[r]·m[r][c] (`m` row-major with `out.len()` columns), each sum from −0.0 in row
/// order as `Iterator::sum`, four columns at a time. The one-sample code multiplies in either
/// order; IEEE multiplication commutes exactly, so the bits agree.
fn row_times_matrix(v: &[f64], m: &[f64], out: &mut [f64]) {
    let columns = out.len();
    let mut c = 0;
    while c + LANES <= columns {
        let mut acc = [-0.0; LANES];
        for (r, &vr) in v.iter().enumerate() {
            let row = &m[r * columns + c..r * columns + c + LANES];
            for k in 0..LANES {
                acc[k] += vr * row[k];
            }
        }
        out[c..c + LANES].copy_from_slice(&acc);
        c += LANES;
    }
    for (c, slot) in out.iter_mut().enumerate().skip(c) {
        let mut acc = -0.0;
        for (r, &vr) in v.iter().enumerate() {
            acc += vr * m[r * columns + c];
        }
        *slot = acc;
    }
}

/// ∂w[o][i] += Σₛ delta[s][o]·x[s][i] over the `active` samples in order, four inputs at a time.
fn weight_gradients(g: &mut [f64], delta: &[f64], x: &[f64], active: &[usize], inputs: usize, outputs: usize) {
    for o in 0..outputs {
        let row = &mut g[o * inputs..(o + 1) * inputs];
        let mut i = 0;
        while i + LANES <= inputs {
            let mut acc = [row[i], row[i + 1], row[i + 2], row[i + 3]];
            for &s in active {
                let d = delta[s * outputs + o];
                let xs = &x[s * inputs + i..s * inputs + i + LANES];
                for k in 0..LANES {
                    acc[k] += d * xs[k];
                }
            }
            row[i..i + LANES].copy_from_slice(&acc);
            i += LANES;
        }
        for (i, slot) in row.iter_mut().enumerate().skip(i) {
            for &s in active {
                *slot += delta[s * outputs + o] * x[s * inputs + i];
            }
        }
    }
}

/// One sample's delta through a layer's weights `w` (outputs × inputs) and the tanh below:
/// below[i] = (Σₒ delta[o]·w[o][i]) · (1 − x[i]²).
fn back_row(w: &[f64], delta: &[f64], x: &[f64], below: &mut [f64]) {
    row_times_matrix(delta, w, below);
    for (out, xi) in below.iter_mut().zip(x) {
        *out *= 1.0 - xi * xi;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Forward and backward over a batch give, bit for bit, the one-sample passes row by row
    /// (widths that are and are not multiples of four; inactive rows add nothing).
    #[test]
    fn batch_passes_have_the_bits_of_one_sample_passes() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for sizes in [vec![7, 9, 5], vec![8, 64, 64, 25], vec![3, 4, 1], vec![74, 64, 64, 1]] {
            let net = Mlp::new(&sizes, 0.5, &mut rng);
            let rows = 13;
            let input: Vec<f64> = (0..rows * sizes[0]).map(|_| rng.random_range(-3.0..3.0)).collect();
            let outputs = *sizes.last().unwrap();
            let output_gradient: Vec<f64> = (0..rows * outputs).map(|_| rng.random_range(-1.0..1.0)).collect();
            let active: Vec<bool> = (0..rows).map(|s| s % 3 != 1).collect();
            let mut pass = BatchPass::default();
            net.forward_batch(&input, rows, &mut pass);
            let mut one_by_one = vec![0.0; net.parameters.len()];
            for s in 0..rows {
                let single = net.forward(&input[s * sizes[0]..(s + 1) * sizes[0]]);
                let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                assert_eq!(bits(single.output()), bits(pass.output(s)), "{sizes:?} row {s}");
                if active[s] {
                    net.backward(
                        &single,
                        &output_gradient[s * outputs..(s + 1) * outputs],
                        &mut one_by_one,
                    );
                }
            }
            let mut batched = vec![0.0; net.parameters.len()];
            net.backward_batch(&mut pass, &output_gradient, &active, &mut batched);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&one_by_one), bits(&batched), "{sizes:?}");
            assert!(batched.iter().any(|g| *g != 0.0));
        }
    }
}
