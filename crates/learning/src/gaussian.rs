//! The diagonal Gaussian policy's log-density, entropy and their derivatives.

/// ½ ln(2π).
const HALF_LN_TAU: f64 = 0.918_938_533_204_672_7;

/// ln p(action) under N(mean, diag(exp(log_std))²).
pub fn log_prob(action: &[f64], mean: &[f64], log_std: &[f64]) -> f64 {
    action
        .iter()
        .zip(mean)
        .zip(log_std)
        .map(|((a, m), s)| {
            let z = (a - m) / s.exp();
            -0.5 * z * z - s - HALF_LN_TAU
        })
        .sum()
}

/// The entropy of N(mean, diag(exp(log_std))²): Σ (log σ + ½ ln(2πe)); its derivative with
/// respect to each log σ is 1.
pub fn entropy(log_std: &[f64]) -> f64 {
    log_std.iter().map(|s| s + HALF_LN_TAU + 0.5).sum()
}

/// Adds `scale` × ∂ ln p / ∂ mean to `d_mean` and `scale` × ∂ ln p / ∂ log σ to `d_log_std`.
pub fn add_log_prob_gradient(
    action: &[f64],
    mean: &[f64],
    log_std: &[f64],
    scale: f64,
    d_mean: &mut [f64],
    d_log_std: &mut [f64],
) {
    for i in 0..action.len() {
        let var = (2.0 * log_std[i]).exp();
        let diff = action[i] - mean[i];
        d_mean[i] += scale * diff / var;
        d_log_std[i] += scale * (diff * diff / var - 1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_density_and_its_gradient_agree_with_the_formula_and_finite_differences() {
        // one dimension, σ = 1: the standard normal density at 1
        assert!((log_prob(&[1.0], &[0.0], &[0.0]) - (-0.5 - HALF_LN_TAU)).abs() < 1e-12);
        let (a, m, s) = ([0.4, -1.2], [0.1, -0.5], [-0.3, 0.2]);
        let (mut dm, mut ds) = ([0.0; 2], [0.0; 2]);
        add_log_prob_gradient(&a, &m, &s, 1.0, &mut dm, &mut ds);
        let h = 1e-6;
        for i in 0..2 {
            let (mut up, mut down) = (m, m);
            up[i] += h;
            down[i] -= h;
            let numeric = (log_prob(&a, &up, &s) - log_prob(&a, &down, &s)) / (2.0 * h);
            assert!((numeric - dm[i]).abs() < 1e-6, "mean {i}");
            let (mut up, mut down) = (s, s);
            up[i] += h;
            down[i] -= h;
            let numeric = (log_prob(&a, &m, &up) - log_prob(&a, &m, &down)) / (2.0 * h);
            assert!((numeric - ds[i]).abs() < 1e-6, "log σ {i}");
        }
        // the entropy of a standard normal: ½ ln(2πe) ≈ 1.4189
        assert!((entropy(&[0.0]) - 1.418_938_533).abs() < 1e-8);
    }
}
