//! The two O(n²λ) steps of a CMA-ES generation, for a whole population at once: sampling
//! `y_k = B (d ∘ z_k)` and the rank-μ update of the covariance matrix.
//!
//! Both compute every entry with exactly the operations, in the order, of the textbook loops
//! (`y_i = Σ_k B_ik d_k z_k` summed over k in order; `Σ_l w_l y_li y_lj` summed over l in order),
//! so results are bit-identical to them. What changes is the loop nest: each row of B (or of C)
//! is read once per generation instead of once per sample, the innermost loop runs over samples
//! or columns (vectorised, with AVX where the CPU has it: `simd`), and rows are spread over
//! threads. At n = 784, λ = 24 this took the optimizer's share of a ch. 6 generation from
//! ≈ 48 ms to a few ms (docs/performance.md).

use crate::simd;
use rayon::prelude::*;

/// Rows of at least this many entries per task when rows are spread over threads.
const MIN_ROWS_PER_TASK: usize = 16;

/// Samples per block of the sampling kernel (one AVX register of f64).
const SAMPLES: usize = 4;
/// Rows of B per block of the sampling kernel: `ROWS × SAMPLES` independent sums in registers.
const ROWS: usize = 8;
/// Columns per block of the rank-μ kernel: that many independent sums in registers.
const COLUMNS: usize = 32;

/// `y_k = B (scales ∘ z_k)` for every `z_k` of `zs` (`scales = None`: `y_k = B z_k`), with `B`
/// row-major `n × n`. Each entry is `Σ_k B_ik (scales_k z_k)` summed over k in order.
pub(crate) fn transform_all(basis: &[f64], scales: Option<&[f64]>, zs: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let lambda = zs.len();
    let n = zs.first().map_or(0, Vec::len);
    assert_eq!(basis.len(), n * n, "transform_all: basis is not n × n");
    if n == 0 {
        return vec![Vec::new(); lambda];
    }
    // Blocks of SAMPLES samples (the last padded with zeros); in each, dz[k][q] = scales_k z_qk.
    let blocks = lambda.div_ceil(SAMPLES);
    let mut dz = vec![0.0; blocks * n * SAMPLES];
    for (l, z) in zs.iter().enumerate() {
        let block = &mut dz[(l / SAMPLES) * n * SAMPLES..(l / SAMPLES + 1) * n * SAMPLES];
        for (k, &zk) in z.iter().enumerate() {
            block[k * SAMPLES + l % SAMPLES] = match scales {
                Some(d) => zk * d[k],
                None => zk,
            };
        }
    }
    // yt[i][l] = y_li, l over the padded samples
    let width = blocks * SAMPLES;
    let mut yt = vec![0.0; n * width];
    yt.par_chunks_mut(ROWS * width)
        .zip(basis.par_chunks(ROWS * n))
        .for_each(|(out, rows)| rows_times(rows, n, &dz, out));
    (0..lambda)
        .map(|l| (0..n).map(|i| yt[i * width + l]).collect())
        .collect()
}

/// `out[r][l] = Σ_k rows[r][k]·dz[l][k]` (k in order) for up to [`ROWS`] rows of length `n` and
/// every block of samples in `dz`.
fn rows_times(rows: &[f64], n: usize, dz: &[f64], out: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if simd::avx() {
        // SAFETY: `simd::avx` checked that the CPU supports AVX.
        return unsafe { rows_times_avx(rows, n, dz, out) };
    }
    rows_times_body(rows, n, dz, out)
}

/// [`rows_times`] compiled with AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline(never)]
unsafe fn rows_times_avx(rows: &[f64], n: usize, dz: &[f64], out: &mut [f64]) {
    rows_times_body(rows, n, dz, out)
}

#[inline(always)]
fn rows_times_body(rows: &[f64], n: usize, dz: &[f64], out: &mut [f64]) {
    let count = rows.len() / n;
    let width = out.len() / count;
    for (b, block) in dz.chunks_exact(n * SAMPLES).enumerate() {
        let column = b * SAMPLES;
        if count == ROWS {
            // −0.0 is the neutral start of a float sum: −0.0 + x = x for every x.
            let mut acc = [[-0.0f64; SAMPLES]; ROWS];
            for (k, d) in block.chunks_exact(SAMPLES).enumerate() {
                let d: &[f64; SAMPLES] = d.try_into().expect("a block of samples");
                for (r, sums) in acc.iter_mut().enumerate() {
                    let entry = rows[r * n + k];
                    for (sum, &dq) in sums.iter_mut().zip(d) {
                        *sum += entry * dq;
                    }
                }
            }
            for (r, sums) in acc.iter().enumerate() {
                out[r * width + column..r * width + column + SAMPLES].copy_from_slice(sums);
            }
        } else {
            for r in 0..count {
                let mut sums = [-0.0f64; SAMPLES];
                for (d, &entry) in block.chunks_exact(SAMPLES).zip(&rows[r * n..(r + 1) * n]) {
                    for (sum, &dq) in sums.iter_mut().zip(d) {
                        *sum += entry * dq;
                    }
                }
                out[r * width + column..r * width + column + SAMPLES].copy_from_slice(&sums);
            }
        }
    }
}

/// The weights and vectors of one rank-μ update:
/// `C ← decay·C + c_1 p pᵀ + c_μ Σ_l w_l y_l y_lᵀ` (upper triangle computed, lower mirrored).
pub(crate) struct CovarianceUpdate<'a> {
    pub decay: f64,
    pub c_1: f64,
    pub c_mu: f64,
    /// The evolution path p_c.
    pub path: &'a [f64],
    /// `w_l` of each sample (zero weights are skipped).
    pub weights: &'a [f64],
    pub ys: &'a [Vec<f64>],
}

impl CovarianceUpdate<'_> {
    /// Applies the update to the row-major `n × n` symmetric `covariance`. Entry (i, j):
    /// `decay·C_ij + c_1 p_i p_j + c_μ Σ_l (w_l y_li) y_lj`, the sum over l in order from +0.
    pub(crate) fn apply(&self, covariance: &mut [f64]) {
        let n = self.path.len();
        assert_eq!(covariance.len(), n * n, "covariance is not n × n");
        // (w_l, y_l) with w_l ≠ 0, in order
        let terms: Vec<(f64, &[f64])> = self
            .weights
            .iter()
            .zip(self.ys)
            .filter(|(w, _)| **w != 0.0)
            .map(|(&w, y)| (w, y.as_slice()))
            .collect();
        covariance
            .par_chunks_mut(n.max(1))
            .enumerate()
            .with_min_len(MIN_ROWS_PER_TASK)
            .for_each_init(
                || vec![0.0; terms.len()],
                |scales, (i, row)| self.update_row(i, &terms, &mut row[i..], scales),
            );
        mirror_upper(covariance, n);
    }

    /// Row `i` from the diagonal on (`row = C[i][i..]`); `scales` (one per term) is scratch.
    fn update_row(&self, i: usize, terms: &[(f64, &[f64])], row: &mut [f64], scales: &mut [f64]) {
        #[cfg(target_arch = "x86_64")]
        if simd::avx() {
            // SAFETY: `simd::avx` checked that the CPU supports AVX.
            return unsafe { self.update_row_avx(i, terms, row, scales) };
        }
        self.update_row_body(i, terms, row, scales)
    }

    /// [`CovarianceUpdate::update_row`] compiled with AVX.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    unsafe fn update_row_avx(&self, i: usize, terms: &[(f64, &[f64])], row: &mut [f64], scales: &mut [f64]) {
        self.update_row_body(i, terms, row, scales)
    }

    #[inline(always)]
    fn update_row_body(&self, i: usize, terms: &[(f64, &[f64])], row: &mut [f64], scales: &mut [f64]) {
        for (a, &(w, y)) in scales.iter_mut().zip(terms) {
            *a = w * y[i];
        }
        let c_1_p_i = self.c_1 * self.path[i];
        let combine = |c: &mut f64, p_j: f64, sum: f64| *c = self.decay * *c + c_1_p_i * p_j + self.c_mu * sum;
        let full = row.len() - row.len() % COLUMNS;
        let (blocks, rest) = row.split_at_mut(full);
        for (b, block) in blocks.chunks_exact_mut(COLUMNS).enumerate() {
            let j0 = i + b * COLUMNS;
            let mut sums = [0.0f64; COLUMNS];
            for (&a, &(_, y)) in scales.iter().zip(terms) {
                let y: &[f64; COLUMNS] = y[j0..j0 + COLUMNS].try_into().expect("a full block");
                for q in 0..COLUMNS {
                    sums[q] += a * y[q];
                }
            }
            for ((c, &p_j), &sum) in block.iter_mut().zip(&self.path[j0..]).zip(&sums) {
                combine(c, p_j, sum);
            }
        }
        let j0 = i + full;
        let mut sums = [0.0f64; COLUMNS];
        for (&a, &(_, y)) in scales.iter().zip(terms) {
            for (sum, &yj) in sums.iter_mut().zip(&y[j0..]) {
                *sum += a * yj;
            }
        }
        for ((c, &p_j), &sum) in rest.iter_mut().zip(&self.path[j0..]).zip(&sums) {
            combine(c, p_j, sum);
        }
    }
}

/// Copies the upper triangle of the row-major `n × n` matrix onto the lower one, in tiles.
fn mirror_upper(m: &mut [f64], n: usize) {
    const TILE: usize = 32;
    for i0 in (0..n).step_by(TILE) {
        for j0 in (0..=i0).step_by(TILE) {
            for i in i0..(i0 + TILE).min(n) {
                for j in j0..(j0 + TILE).min(i) {
                    m[i * n + j] = m[j * n + i];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{SeededRng, Stream};

    /// The textbook loops these kernels replace.
    fn textbook_transform(basis: &[f64], scales: &[f64], z: &[f64]) -> Vec<f64> {
        let n = z.len();
        let dz: Vec<f64> = z.iter().zip(scales).map(|(a, d)| a * d).collect();
        (0..n).map(|i| (0..n).map(|k| basis[i * n + k] * dz[k]).sum()).collect()
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    #[test]
    fn population_sampling_has_the_bits_of_the_textbook_loop() {
        for (n, lambda) in [(1, 2), (7, 5), (64, 24), (131, 3)] {
            let mut rng = SeededRng::derive(3, n as u64, 0, Stream::Sampling);
            let basis = rng.normal_vec(n * n);
            let scales: Vec<f64> = rng.normal_vec(n).iter().map(|v| v.abs() + 0.1).collect();
            let zs: Vec<Vec<f64>> = (0..lambda).map(|_| rng.normal_vec(n)).collect();
            let ys = transform_all(&basis, Some(&scales), &zs);
            crate::simd::FORCE_PORTABLE.store(true, std::sync::atomic::Ordering::Relaxed);
            let portable = transform_all(&basis, Some(&scales), &zs);
            crate::simd::FORCE_PORTABLE.store(false, std::sync::atomic::Ordering::Relaxed);
            for ((y, z), p) in ys.iter().zip(&zs).zip(&portable) {
                let expected = textbook_transform(&basis, &scales, z);
                assert_eq!(bits(y), bits(&expected), "n {n}");
                assert_eq!(bits(p), bits(&expected), "portable, n {n}");
            }
            let unscaled = transform_all(&basis, None, &zs);
            let ones = vec![1.0; n];
            assert_eq!(bits(&unscaled[0]), bits(&textbook_transform(&basis, &ones, &zs[0])));
        }
    }

    #[test]
    fn rank_mu_update_has_the_bits_of_the_textbook_loop() {
        let (n, lambda) = (45, 12);
        let mut rng = SeededRng::derive(4, 0, 0, Stream::Sampling);
        let ys: Vec<Vec<f64>> = (0..lambda).map(|_| rng.normal_vec(n)).collect();
        let mut weights = rng.normal_vec(lambda);
        weights[3] = 0.0;
        let path = rng.normal_vec(n);
        let g = rng.normal_vec(n * n);
        let mut c = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                c[i * n + j] = g[i * n + j] + g[j * n + i];
            }
        }
        let (decay, c_1, c_mu) = (0.93, 0.01, 0.05);
        let mut expected = c.clone();
        for i in 0..n {
            for j in i..n {
                let mut rank_mu = 0.0;
                for (w, y) in weights.iter().zip(&ys) {
                    if *w != 0.0 {
                        rank_mu += w * y[i] * y[j];
                    }
                }
                let value = decay * c[i * n + j] + c_1 * path[i] * path[j] + c_mu * rank_mu;
                expected[i * n + j] = value;
                expected[j * n + i] = value;
            }
        }
        let update = CovarianceUpdate {
            decay,
            c_1,
            c_mu,
            path: &path,
            weights: &weights,
            ys: &ys,
        };
        update.apply(&mut c);
        assert_eq!(bits(&c), bits(&expected));
    }
}
