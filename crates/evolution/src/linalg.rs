//! Dense symmetric eigendecomposition by the cyclic Jacobi method, for CMA-ES.
//!
//! Why hand-written: CMA-ES needs `C = B D² Bᵀ` of a small symmetric matrix (n ≲ a few hundred)
//! once per generation or less; Jacobi is short, unconditionally stable, deterministic and
//! accurate to machine precision for symmetric matrices, and avoids a linear-algebra
//! dependency. It costs O(n³) per sweep. Because C changes little between generations, CMA-ES
//! warm-starts from the previous eigenbasis ([`symmetric_eigen_from`]): `Bᵀ C B` is nearly
//! diagonal and converges in a few sweeps instead of the 6–10 a cold start needs.

/// Eigenvalues and orthonormal eigenvectors of the symmetric `n × n` row-major matrix `a`:
/// returns `(values, vectors)` with eigenvector `k` in column `k` of the row-major `vectors`
/// (`vectors[i * n + k]`). Only the upper triangle of `a` is read. Values are not sorted.
pub fn symmetric_eigen(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    assert_eq!(a.len(), n * n, "symmetric_eigen: matrix is not n × n");
    let mut m = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            m[i * n + j] = a[i * n + j];
            m[j * n + i] = a[i * n + j];
        }
    }
    let mut v = vec![0.0; n * n];
    for i in 0..n {
        v[i * n + i] = 1.0;
    }
    jacobi(&mut m, &mut v, n);
    ((0..n).map(|i| m[i * n + i]).collect(), v)
}

/// As [`symmetric_eigen`], starting from `basis`, an orthogonal matrix (row-major, columns =
/// approximate eigenvectors, e.g. those of a previous, similar matrix): diagonalises
/// `basisᵀ a basis` and returns `basis` times its rotations as the eigenvectors.
pub fn symmetric_eigen_from(a: &[f64], n: usize, basis: &[f64]) -> (Vec<f64>, Vec<f64>) {
    assert_eq!(a.len(), n * n, "symmetric_eigen_from: matrix is not n × n");
    assert_eq!(basis.len(), n * n, "symmetric_eigen_from: basis is not n × n");
    // t = a · basis (a read from its upper triangle), then m = basisᵀ · t, symmetrised.
    let upper = |i: usize, j: usize| if i <= j { a[i * n + j] } else { a[j * n + i] };
    let mut t = vec![0.0; n * n];
    for i in 0..n {
        for k in 0..n {
            let aik = upper(i, k);
            if aik != 0.0 {
                for j in 0..n {
                    t[i * n + j] += aik * basis[k * n + j];
                }
            }
        }
    }
    let mut m = vec![0.0; n * n];
    for i in 0..n {
        for j in i..n {
            let value: f64 = (0..n).map(|k| basis[k * n + i] * t[k * n + j]).sum();
            m[i * n + j] = value;
            m[j * n + i] = value;
        }
    }
    let mut v = basis.to_vec();
    jacobi(&mut m, &mut v, n);
    ((0..n).map(|i| m[i * n + i]).collect(), v)
}

/// Cyclic Jacobi sweeps on the symmetric `m` until its off-diagonal part is negligible; the
/// rotations are accumulated into the columns of `v`.
fn jacobi(m: &mut [f64], v: &mut [f64], n: usize) {
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
            .map(|(i, j)| m[i * n + j] * m[i * n + j])
            .sum();
        let diag: f64 = (0..n).map(|i| m[i * n + i] * m[i * n + i]).sum();
        if off <= 1e-32 * diag || off < f64::MIN_POSITIVE {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                rotate(m, v, n, p, q);
            }
        }
    }
}

/// One Jacobi rotation zeroing `m[p][q]`, accumulated into the eigenvector matrix `v`.
fn rotate(m: &mut [f64], v: &mut [f64], n: usize, p: usize, q: usize) {
    let apq = m[p * n + q];
    if apq == 0.0 {
        return;
    }
    let app = m[p * n + p];
    let aqq = m[q * n + q];
    let theta = (aqq - app) / (2.0 * apq);
    // t = tan φ, the smaller root of t² + 2θt − 1 = 0.
    let t = if theta.abs() > 1e150 {
        0.5 / theta
    } else {
        theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt())
    };
    let c = 1.0 / (t * t + 1.0).sqrt();
    let s = t * c;
    m[p * n + p] = app - t * apq;
    m[q * n + q] = aqq + t * apq;
    m[p * n + q] = 0.0;
    m[q * n + p] = 0.0;
    for k in 0..n {
        if k != p && k != q {
            let akp = m[k * n + p];
            let akq = m[k * n + q];
            let new_kp = c * akp - s * akq;
            let new_kq = s * akp + c * akq;
            m[k * n + p] = new_kp;
            m[p * n + k] = new_kp;
            m[k * n + q] = new_kq;
            m[q * n + k] = new_kq;
        }
        let vkp = v[k * n + p];
        let vkq = v[k * n + q];
        v[k * n + p] = c * vkp - s * vkq;
        v[k * n + q] = s * vkp + c * vkq;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{SeededRng, Stream};

    #[test]
    fn reconstructs_random_symmetric_matrices() {
        for (n, seed) in [(1, 0), (2, 1), (5, 2), (40, 3)] {
            let mut rng = SeededRng::derive(seed, 0, 0, Stream::Sampling);
            // A = G Gᵀ + diagonal with a wide spread of scales (ill-conditioned, like late CMA-ES).
            let g: Vec<f64> = rng.normal_vec(n * n);
            let mut a = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    a[i * n + j] = (0..n).map(|k| g[i * n + k] * g[j * n + k]).sum::<f64>();
                }
                a[i * n + i] += 10f64.powi(i as i32 % 7 - 3);
            }
            let (values, vectors) = symmetric_eigen(&a, n);
            let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            for i in 0..n {
                for j in 0..n {
                    let rebuilt: f64 = (0..n)
                        .map(|k| vectors[i * n + k] * values[k] * vectors[j * n + k])
                        .sum();
                    assert!((rebuilt - a[i * n + j]).abs() < 1e-11 * scale, "n {n}");
                    let dot: f64 = (0..n).map(|k| vectors[k * n + i] * vectors[k * n + j]).sum();
                    let expected = if i == j { 1.0 } else { 0.0 };
                    assert!((dot - expected).abs() < 1e-12, "orthonormality n {n}");
                }
            }
        }
    }

    #[test]
    fn warm_start_matches_cold_start() {
        let n = 12;
        let mut rng = SeededRng::derive(9, 0, 0, Stream::Sampling);
        let g: Vec<f64> = rng.normal_vec(n * n);
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] = (0..n).map(|k| g[i * n + k] * g[j * n + k]).sum::<f64>();
            }
        }
        let (_, basis) = symmetric_eigen(&a, n);
        // Perturb the matrix a little, as one CMA-ES generation does.
        let mut b = a.clone();
        for i in 0..n {
            for j in 0..n {
                b[i * n + j] += 0.01 * (g[i * n + j] + g[j * n + i]);
            }
        }
        let (cold, _) = symmetric_eigen(&b, n);
        let (warm, vectors) = symmetric_eigen_from(&b, n, &basis);
        let mut cold = cold;
        let mut warm_sorted = warm.clone();
        cold.sort_by(f64::total_cmp);
        warm_sorted.sort_by(f64::total_cmp);
        for (c, w) in cold.iter().zip(&warm_sorted) {
            assert!((c - w).abs() < 1e-10 * cold[n - 1], "{c} vs {w}");
        }
        for i in 0..n {
            for j in 0..n {
                let rebuilt: f64 = (0..n).map(|k| vectors[i * n + k] * warm[k] * vectors[j * n + k]).sum();
                assert!((rebuilt - b[i * n + j]).abs() < 1e-10 * cold[n - 1]);
            }
        }
    }

    #[test]
    fn diagonal_and_known_matrices() {
        let (values, _) = symmetric_eigen(&[2.0, 1.0, 1.0, 2.0], 2);
        let mut sorted = values.clone();
        sorted.sort_by(f64::total_cmp);
        assert!((sorted[0] - 1.0).abs() < 1e-14 && (sorted[1] - 3.0).abs() < 1e-14);
        let (values, vectors) = symmetric_eigen(&[4.0, 0.0, 0.0, 9.0], 2);
        assert_eq!(values, vec![4.0, 9.0]);
        assert_eq!(vectors, vec![1.0, 0.0, 0.0, 1.0]);
    }
}
