//! Timing of the CMA-ES eigendecomposition (`vsrlab_evolution::linalg`): a cold
//! `symmetric_eigen` of a random symmetric positive-definite matrix, then a warm
//! `symmetric_eigen_from` of a small perturbation of it (the next generation's covariance) from
//! the first basis, with the residual ‖B V − V Λ‖_max / ‖B‖_max on a few columns and a
//! checksum of the result's bits (equal checksums: bit-identical decompositions, e.g. before
//! and after a speed change, or on CPUs with and without AVX).
//!
//! ```text
//! cargo run --release -p vsrlab-evolution --example linalg_timing -- [374 784 1344]
//! ```

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vsrlab_evolution::linalg::{symmetric_eigen, symmetric_eigen_from};

/// A standard normal draw (Box–Muller).
fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let uniform = |rng: &mut ChaCha8Rng| (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    let (u, v) = (1.0 - uniform(rng), uniform(rng));
    (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
}

/// `G Gᵀ / n` plus a diagonal with scales spread over 10⁻³…10³, G standard normal.
fn random_spd(n: usize, rng: &mut ChaCha8Rng) -> Vec<f64> {
    let g: Vec<f64> = (0..n * n).map(|_| normal(rng)).collect();
    let mut a = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            let dot: f64 = g[i * n..(i + 1) * n]
                .iter()
                .zip(&g[j * n..(j + 1) * n])
                .map(|(x, y)| x * y)
                .sum();
            a[i * n + j] = dot / n as f64;
            a[j * n + i] = dot / n as f64;
        }
        a[i * n + i] += 10f64.powi(i as i32 % 7 - 3);
    }
    a
}

fn main() {
    let sizes: Vec<usize> = std::env::args().skip(1).filter_map(|s| s.parse().ok()).collect();
    let sizes = if sizes.is_empty() { vec![374, 784, 1344] } else { sizes };
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for n in sizes {
        let a = random_spd(n, &mut rng);
        let mut b = a.clone();
        for i in 0..n {
            for j in i..n {
                let d = normal(&mut rng);
                b[i * n + j] += 2e-3 * d;
                b[j * n + i] = b[i * n + j];
            }
        }
        let start = std::time::Instant::now();
        let (_, basis) = symmetric_eigen(&a, n);
        let cold = start.elapsed();
        let start = std::time::Instant::now();
        let (values, vectors) = symmetric_eigen_from(&b, n, &basis);
        let warm = start.elapsed();
        let scale = b.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        let mut residual = 0.0f64;
        for k in (0..n).step_by((n / 8).max(1)) {
            for i in 0..n {
                let bv: f64 = (0..n).map(|j| b[i * n + j] * vectors[j * n + k]).sum();
                residual = residual.max((bv - values[k] * vectors[i * n + k]).abs() / scale);
            }
        }
        let checksum = values
            .iter()
            .chain(&vectors)
            .fold(0u64, |h, v| h.rotate_left(5) ^ v.to_bits());
        println!(
            "n {n}: symmetric_eigen {cold:.3?}, symmetric_eigen_from (warm) {warm:.3?}, residual {residual:.1e}, bits {checksum:016x}"
        );
    }
}
