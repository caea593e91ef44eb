//! Principal component analysis by eigen-decomposition of the covariance matrix, with a small
//! cyclic Jacobi solver for symmetric matrices.

use serde::{Deserialize, Serialize};

/// Eigen-decomposition of a symmetric matrix (row-major, n×n) by cyclic Jacobi rotations.
/// Returns eigenvalues in decreasing order and the matching unit eigenvectors (one per entry).
pub fn symmetric_eigen(matrix: &[Vec<f64>]) -> (Vec<f64>, Vec<Vec<f64>>) {
    let n = matrix.len();
    let mut a: Vec<Vec<f64>> = matrix.to_vec();
    let mut v: Vec<Vec<f64>> = (0..n)
        .map(|i| (0..n).map(|j| f64::from(u8::from(i == j))).collect())
        .collect();
    let scale: f64 = a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    for _sweep in 0..100 {
        let off: f64 = (0..n)
            .flat_map(|i| (0..n).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        if off.sqrt() <= 1e-15 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
        for p in 0..n {
            for q in p + 1..n {
                if a[p][q].abs() <= f64::MIN_POSITIVE {
                    continue;
                }
                // Rotation angle zeroing a[p][q] (Rutishauser's stable form).
                let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (row_p, row_q) = (a[p].clone(), a[q].clone());
                for (k, (apk, aqk)) in row_p.into_iter().zip(row_q).enumerate() {
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                }
                for row in v.iter_mut() {
                    let (vp, vq) = (row[p], row[q]);
                    row[p] = c * vp - s * vq;
                    row[q] = s * vp + c * vq;
                }
            }
        }
    }
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| a[j][j].total_cmp(&a[i][i]));
    let values = order.iter().map(|&i| a[i][i]).collect();
    let vectors = order.iter().map(|&i| (0..n).map(|k| v[k][i]).collect()).collect();
    (values, vectors)
}

/// A fitted PCA.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Pca {
    /// Column means of the data.
    pub mean: Vec<f64>,
    /// Column scales (standard deviations when standardised, else 1).
    pub scale: Vec<f64>,
    /// Principal axes, one unit vector per component, by decreasing variance. The sign of each
    /// is chosen so that its largest-magnitude entry is positive.
    pub components: Vec<Vec<f64>>,
    /// Variance along each component (covariance eigenvalues, n − 1 denominator).
    pub variance: Vec<f64>,
    /// Fraction of the total variance along each component.
    pub variance_ratio: Vec<f64>,
}

impl Pca {
    /// Fits a PCA to rows `x`; with `standardise`, columns are first divided by their standard
    /// deviation (columns with zero spread are left as they are).
    pub fn fit(x: &[Vec<f64>], standardise: bool) -> Pca {
        let n = x.len();
        let p = x.first().map_or(0, Vec::len);
        let mut mean = vec![0.0; p];
        for r in x {
            for (m, v) in mean.iter_mut().zip(r) {
                *m += v / n as f64;
            }
        }
        let denom = (n.max(2) - 1) as f64;
        let mut scale = vec![1.0; p];
        if standardise {
            for (j, s) in scale.iter_mut().enumerate() {
                let var: f64 = x.iter().map(|r| (r[j] - mean[j]).powi(2)).sum::<f64>() / denom;
                if var > 0.0 {
                    *s = var.sqrt();
                }
            }
        }
        let mut cov = vec![vec![0.0; p]; p];
        for r in x {
            let z: Vec<f64> = (0..p).map(|j| (r[j] - mean[j]) / scale[j]).collect();
            for i in 0..p {
                for j in i..p {
                    cov[i][j] += z[i] * z[j] / denom;
                }
            }
        }
        let upper = cov.clone();
        for (i, row) in cov.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate().take(i) {
                *v = upper[j][i];
            }
        }
        let (values, mut vectors) = symmetric_eigen(&cov);
        for v in vectors.iter_mut() {
            let big = v
                .iter()
                .copied()
                .fold(0.0f64, |a, b| if b.abs() > a.abs() { b } else { a });
            if big < 0.0 {
                v.iter_mut().for_each(|c| *c = -*c);
            }
        }
        let variance: Vec<f64> = values.iter().map(|v| v.max(0.0)).collect();
        let total: f64 = variance.iter().sum();
        let variance_ratio = variance
            .iter()
            .map(|v| if total > 0.0 { v / total } else { 0.0 })
            .collect();
        Pca {
            mean,
            scale,
            components: vectors,
            variance,
            variance_ratio,
        }
    }

    /// Coordinates of a row on the first `k` components.
    pub fn transform(&self, row: &[f64], k: usize) -> Vec<f64> {
        self.components
            .iter()
            .take(k)
            .map(|c| {
                c.iter()
                    .enumerate()
                    .map(|(j, w)| w * (row[j] - self.mean[j]) / self.scale[j])
                    .sum()
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobi_on_a_known_matrix() {
        // [[2, 1], [1, 2]]: eigenvalues 3 and 1, vectors (1, 1)/√2 and (1, −1)/√2.
        let (vals, vecs) = symmetric_eigen(&[vec![2.0, 1.0], vec![1.0, 2.0]]);
        assert!((vals[0] - 3.0).abs() < 1e-12 && (vals[1] - 1.0).abs() < 1e-12);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((vecs[0][0].abs() - h).abs() < 1e-12 && (vecs[0][0] - vecs[0][1]).abs() < 1e-12);
    }

    #[test]
    fn jacobi_reconstructs_a_random_symmetric_matrix() {
        let n = 6;
        let m: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| ((i * 7 + j * 3) % 5) as f64 + ((i + j) % 3) as f64 * 0.3 + if i == j { 2.0 } else { 0.0 })
                    .collect()
            })
            .collect();
        let sym: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..n).map(|j| (m[i][j] + m[j][i]) / 2.0).collect())
            .collect();
        let (vals, vecs) = symmetric_eigen(&sym);
        for i in 0..n {
            for j in 0..n {
                let r: f64 = (0..n).map(|k| vals[k] * vecs[k][i] * vecs[k][j]).sum();
                assert!((r - sym[i][j]).abs() < 1e-10);
            }
        }
        assert!(vals.windows(2).all(|w| w[0] >= w[1]));
    }

    #[test]
    fn pca_finds_the_direction_of_spread() {
        // Points along y = 2x with a little orthogonal noise.
        let x: Vec<Vec<f64>> = (0..50)
            .map(|i| {
                let t = i as f64 / 10.0 - 2.5;
                let e = if i % 2 == 0 { 0.01 } else { -0.01 };
                vec![t - 2.0 * e, 2.0 * t + e]
            })
            .collect();
        let p = Pca::fit(&x, false);
        let d = (1.0f64 / 5.0).sqrt();
        assert!((p.components[0][0] - d).abs() < 1e-3 && (p.components[0][1] - 2.0 * d).abs() < 1e-3);
        assert!(p.variance_ratio[0] > 0.999);
        let z = p.transform(&[1.0 + p.mean[0], 2.0 + p.mean[1]], 2);
        assert!((z[0] - 5.0f64.sqrt()).abs() < 1e-3 && z[1].abs() < 1e-3);
    }
}
