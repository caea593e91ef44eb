//! Dense symmetric eigendecomposition for CMA-ES: Householder reduction to tridiagonal form,
//! then the implicit QL algorithm with Wilkinson shifts (the classic `tred2`/`tql2` pair),
//! accumulating the eigenvectors.
//!
//! Why this method: CMA-ES needs `C = B D² Bᵀ` for n up to ~1,500 genes. Householder + QL costs
//! a fixed ≈ 7n³ flops, does no sweeps, and is written so that every O(n³) loop runs over
//! contiguous rows. The cyclic Jacobi method used before touched two strided columns per
//! rotation and needed several O(n³) sweeps: 15–30 s against ≈ 0.26 s now for n = 784 (release
//! build, 2 threads with AVX, shared 2-core machine). Householder + QL is backward stable:
//! eigenvalues are accurate to ≈ ε‖C‖ in absolute terms and the eigenvectors are orthonormal to
//! working precision. Hand-written to avoid a linear-algebra dependency; single-threaded, with a
//! fixed order of operations (Rust does not fuse multiply-adds), so the same input gives the
//! same bits, with or without AVX (`simd`) and for any number of threads.
//!
//! Layout (all matrices row-major):
//! - the reduction works on the upper triangle, row by row; the symmetric matrix-vector product
//!   and the rank-2 update both stream along rows;
//! - the orthogonal factor Q is accumulated from the reflectors row by row, then transposed into
//!   strips of 32 columns, so that each QL (Givens) rotation combines two contiguous rows of a
//!   strip;
//! - the rotations of several QL sweeps are recorded (they depend only on the tridiagonal
//!   matrix) and then applied strip by strip, in parallel, each strip staying in cache. Each
//!   entry sees the same operations in the same order as without strips, so neither the strip
//!   width nor the thread count changes the result;
//! - the row updates of the reduction and of the accumulation (each row on its own) are spread
//!   over threads for large blocks, and every kernel runs with AVX where the CPU has it
//!   (`simd`: the same bits).

use crate::simd;
use rayon::prelude::*;

/// Eigenvalues and orthonormal eigenvectors of the symmetric `n × n` row-major matrix `a`:
/// returns `(values, vectors)` with eigenvector `k` in column `k` of the row-major `vectors`
/// (`vectors[i * n + k]`). Only the upper triangle of `a` is read. Values are not sorted.
///
/// An already diagonal matrix gives its diagonal and exactly the identity. If an entry of the
/// upper triangle is not finite, every value and vector entry is NaN. QL iterations are capped
/// at 60 per eigenvalue (one to three are the rule); if the cap is ever hit, the
/// remaining off-diagonal coupling of that eigenvalue is dropped and the decomposition returned
/// as it stands (vectors still orthonormal, that eigenpair less accurate).
pub fn symmetric_eigen(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    assert_eq!(a.len(), n * n, "symmetric_eigen: matrix is not n × n");
    decompose(a, n)
}

/// As [`symmetric_eigen`], for callers that hold an approximate eigenbasis (row-major, columns =
/// eigenvectors of a previous, similar matrix). `basis` is only checked for size and otherwise
/// ignored: Householder + QL does not profit from a starting basis the way the former Jacobi
/// method did, so the result is bit-identical to `symmetric_eigen(a, n)`. The order and signs
/// of the eigenvectors need not match those of `basis`.
pub fn symmetric_eigen_from(a: &[f64], n: usize, basis: &[f64]) -> (Vec<f64>, Vec<f64>) {
    assert_eq!(a.len(), n * n, "symmetric_eigen_from: matrix is not n × n");
    assert_eq!(basis.len(), n * n, "symmetric_eigen_from: basis is not n × n");
    decompose(a, n)
}

/// Cap on implicit QL iterations spent on one eigenvalue (typically 1–3 are needed).
const MAX_QL_ITERATIONS: usize = 60;

/// Recorded QL rotations are applied to the eigenvectors once this many per matrix row are
/// pending.
const ROTATIONS_PER_ROW: usize = 16;

/// Columns per strip when applying recorded rotations.
const STRIP: usize = 32;

/// Trailing blocks with at least this many rows get their rank-2 (reduction) and rank-1
/// (accumulation) updates spread over threads, a band of rows per task.
const PARALLEL_ROWS: usize = 128;

fn decompose(a: &[f64], n: usize) -> (Vec<f64>, Vec<f64>) {
    if n == 0 {
        return (Vec::new(), Vec::new());
    }
    if (0..n).any(|i| a[i * n + i..(i + 1) * n].iter().any(|x| !x.is_finite())) {
        return (vec![f64::NAN; n], vec![f64::NAN; n * n]);
    }
    let mut work = a.to_vec();
    let (mut values, mut off_diagonal, taus) = tridiagonalize(&mut work, n);
    let q = accumulate_reflectors(&work, &taus, n);
    drop(work);
    // Rows of Qᵀ are the columns of Q, the eigenvector candidates; QL rotates pairs of them.
    let mut candidates = Strips::transposed(&q, n);
    drop(q);
    tridiagonal_ql(&mut values, &mut off_diagonal, &mut candidates, n);
    (values, candidates.transposed_back())
}

/// Reduces the symmetric `a` (upper triangle, overwritten) to tridiagonal `T = Qᵀ a Q` with
/// `Q = H₀ H₁ ⋯ H_{n−3}`, `H_k = I − τ_k u_k u_kᵀ` acting on indices `k+1..n`. Returns the
/// diagonal, the off-diagonal (`e[i]` couples `i` and `i+1`, `e[n−1] = 0`) and the `τ_k`;
/// `u_k` is left in row `k`, columns `k+1..n` of `a` (with `u_k[0] = 1`). `τ_k = 0` means
/// `H_k = I` (the row was already reduced), which keeps diagonal matrices exact.
fn tridiagonalize(a: &mut [f64], n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    #[cfg(target_arch = "x86_64")]
    if simd::avx() {
        // SAFETY: `simd::avx` checked that the CPU supports AVX.
        return unsafe { tridiagonalize_avx(a, n) };
    }
    tridiagonalize_body(a, n)
}

/// [`tridiagonalize`] compiled with AVX (the same operations: see [`simd`]).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline(never)]
unsafe fn tridiagonalize_avx(a: &mut [f64], n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    tridiagonalize_body(a, n)
}

#[inline(always)]
fn tridiagonalize_body(a: &mut [f64], n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut d = vec![0.0; n];
    let mut e = vec![0.0; n];
    let mut taus = vec![0.0; n];
    let mut p = vec![0.0; n];
    for k in 0..n.saturating_sub(2) {
        let m = n - k - 1;
        d[k] = a[k * n + k];
        let (head, tail) = a.split_at_mut((k + 1) * n);
        // x = a[k][k+1..n]: reflect it onto β e₁.
        let x = &mut head[k * n + k + 1..];
        let tail_max = x[1..].iter().fold(0.0f64, |s, v| s.max(v.abs()));
        if tail_max == 0.0 {
            e[k] = x[0];
            continue;
        }
        let scale = tail_max.max(x[0].abs());
        let norm = scale * x.iter().map(|v| (v / scale) * (v / scale)).sum::<f64>().sqrt();
        let x0 = x[0];
        let beta = if x0 >= 0.0 { -norm } else { norm };
        let tau = (beta - x0) / beta;
        // u = (1, x[1..] / (x₀ − β)); |x₀ − β| = |x₀| + ‖x‖, so |u_j| ≤ 1.
        let pivot = x0 - beta;
        x[0] = 1.0;
        x[1..].iter_mut().for_each(|v| *v /= pivot);
        e[k] = beta;
        taus[k] = tau;
        let u: &[f64] = x;
        // Trailing block A₂₂ = a[k+1..n][k+1..n] (rows of `tail`, upper triangle):
        // p = τ A₂₂ u, w = p − (τ/2)(pᵀu) u, A₂₂ ← A₂₂ − u wᵀ − w uᵀ.
        let p = &mut p[..m];
        p.fill(0.0);
        for r in 0..m {
            let row = &tail[r * n + k + 1 + r..(r + 1) * n];
            let ur = u[r];
            let (p_head, p_rest) = p[r..].split_first_mut().expect("r < m");
            let s = dot_and_axpy(&row[1..], &u[r + 1..], ur, p_rest);
            *p_head += row[0] * ur + s;
        }
        p.iter_mut().for_each(|v| *v *= tau);
        let kappa = 0.5 * tau * dot(p, u);
        p.iter_mut().zip(u).for_each(|(w, &uj)| *w -= kappa * uj);
        let w: &[f64] = p;
        let update = |(r, row): (usize, &mut [f64])| {
            rank_two_update(&mut row[k + 1 + r..], &u[r..], &w[r..], u[r], w[r]);
        };
        let rows = &mut tail[..m * n];
        if m >= PARALLEL_ROWS {
            rows.par_chunks_mut(n).enumerate().with_min_len(16).for_each(update);
        } else {
            rows.chunks_mut(n).enumerate().for_each(update);
        }
    }
    if n >= 2 {
        d[n - 2] = a[(n - 2) * n + n - 2];
        e[n - 2] = a[(n - 2) * n + n - 1];
    }
    if n >= 1 {
        d[n - 1] = a[n * n - 1];
    }
    (d, e, taus)
}

/// `row[j] −= ur·w[j] + wr·u[j]`: one row of the reduction's update `A ← A − u wᵀ − w uᵀ`.
fn rank_two_update(row: &mut [f64], u: &[f64], w: &[f64], ur: f64, wr: f64) {
    #[cfg(target_arch = "x86_64")]
    if simd::avx() {
        // SAFETY: `simd::avx` checked that the CPU supports AVX.
        return unsafe { rank_two_update_avx(row, u, w, ur, wr) };
    }
    rank_two_update_body(row, u, w, ur, wr)
}

/// [`rank_two_update`] compiled with AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline(never)]
unsafe fn rank_two_update_avx(row: &mut [f64], u: &[f64], w: &[f64], ur: f64, wr: f64) {
    rank_two_update_body(row, u, w, ur, wr)
}

#[inline(always)]
fn rank_two_update_body(row: &mut [f64], u: &[f64], w: &[f64], ur: f64, wr: f64) {
    for ((a, &wj), &uj) in row.iter_mut().zip(w).zip(u) {
        *a -= ur * wj + wr * uj;
    }
}

/// `Q = H₀ H₁ ⋯ H_{n−3}` (row-major) from the reflectors left by [`tridiagonalize`], by
/// backward accumulation: `H_k` is applied from the left to `H_{k+1} ⋯ H_{n−3}`, which is the
/// identity outside rows and columns `k+2..n`, so only that block is touched, row by row.
fn accumulate_reflectors(reflectors: &[f64], taus: &[f64], n: usize) -> Vec<f64> {
    let mut q = vec![0.0; n * n];
    for i in 0..n {
        q[i * n + i] = 1.0;
    }
    let mut w = vec![0.0; n];
    for k in (0..n.saturating_sub(2)).rev() {
        let tau = taus[k];
        if tau == 0.0 {
            continue;
        }
        let c0 = k + 1;
        let m = n - c0;
        let u = &reflectors[k * n + c0..(k + 1) * n];
        // wᵀ = uᵀ Q[c0..][c0..], then Q[c0..][c0..] −= τ u wᵀ.
        let w = &mut w[..m];
        w.fill(0.0);
        for (r, &ur) in u.iter().enumerate() {
            axpy(ur, &q[(c0 + r) * n + c0..(c0 + r + 1) * n], w);
        }
        let w: &[f64] = w;
        let update = |(r, row): (usize, &mut [f64])| axpy(-(tau * u[r]), w, &mut row[c0..]);
        let rows = &mut q[c0 * n..];
        if m >= PARALLEL_ROWS {
            rows.par_chunks_mut(n).enumerate().with_min_len(16).for_each(update);
        } else {
            rows.chunks_mut(n).enumerate().for_each(update);
        }
    }
    q
}

/// `y[j] += f·x[j]`. (Adding `(−f)·x` is subtracting `f·x`: the same bits.)
fn axpy(f: f64, x: &[f64], y: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if simd::avx() {
        // SAFETY: `simd::avx` checked that the CPU supports AVX.
        return unsafe { axpy_avx(f, x, y) };
    }
    axpy_body(f, x, y)
}

/// [`axpy`] compiled with AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline(never)]
unsafe fn axpy_avx(f: f64, x: &[f64], y: &mut [f64]) {
    axpy_body(f, x, y)
}

#[inline(always)]
fn axpy_body(f: f64, x: &[f64], y: &mut [f64]) {
    for (yj, &xj) in y.iter_mut().zip(x) {
        *yj += f * xj;
    }
}

/// A row-major `n × n` matrix stored as strips of [`STRIP`] columns (each strip `n` rows of
/// `STRIP` entries, contiguous; the last strip padded with zeros), so that strips can be
/// rotated independently, in parallel, each staying in cache.
struct Strips {
    n: usize,
    data: Vec<f64>,
}

impl Strips {
    /// `Mᵀ` of the row-major `m`, in strips.
    fn transposed(m: &[f64], n: usize) -> Self {
        let count = n.div_ceil(STRIP);
        let mut data = vec![0.0; count * n * STRIP];
        // (Mᵀ)[r][c] = M[c][r]
        for (c, row) in m.chunks_exact(n).enumerate() {
            let (strip, lane) = (c / STRIP, c % STRIP);
            let block = &mut data[strip * n * STRIP..(strip + 1) * n * STRIP];
            for (r, &v) in row.iter().enumerate() {
                block[r * STRIP + lane] = v;
            }
        }
        Self { n, data }
    }

    /// The transpose of the stored matrix, row-major.
    fn transposed_back(&self) -> Vec<f64> {
        let n = self.n;
        let mut out = vec![0.0; n * n];
        for (i, row) in out.chunks_exact_mut(n).enumerate() {
            let (strip, lane) = (i / STRIP, i % STRIP);
            let block = &self.data[strip * n * STRIP..(strip + 1) * n * STRIP];
            for (k, v) in row.iter_mut().enumerate() {
                *v = block[k * STRIP + lane];
            }
        }
        out
    }

    /// Applies `rotations` in order to the rows, every strip on its own (in parallel).
    fn rotate(&mut self, rotations: &[Rotation]) {
        if rotations.is_empty() {
            return;
        }
        self.data
            .par_chunks_mut(self.n * STRIP)
            .for_each(|strip| rotate_strip(strip, rotations));
    }
}

/// Implicit QL with Wilkinson shifts on the symmetric tridiagonal matrix (diagonal `d`,
/// off-diagonal `e`, `e[i]` coupling `i` and `i+1`). On return `d` holds the eigenvalues, and
/// the rotations `G` of all iterations have been applied to pairs of rows of `zt`
/// (`zt ← Gᵀ zt`): rows that started as the columns of Q end as the eigenvectors of `Q T Qᵀ`,
/// row `k` belonging to `d[k]`.
fn tridiagonal_ql(d: &mut [f64], e: &mut [f64], zt: &mut Strips, n: usize) {
    let mut rotations: Vec<Rotation> = Vec::with_capacity(ROTATIONS_PER_ROW * n + n);
    for l in 0..n {
        let mut iterations = 0;
        loop {
            // The unreduced block is l..=m: e[m] is negligible (or m = n−1).
            let mut m = l;
            while m + 1 < n {
                let dd = d[m].abs() + d[m + 1].abs();
                if e[m].abs() <= f64::EPSILON * dd || e[m].abs() < f64::MIN_POSITIVE {
                    break;
                }
                m += 1;
            }
            if m == l || iterations == MAX_QL_ITERATIONS {
                break;
            }
            iterations += 1;
            // Shift: the eigenvalue of the leading 2 × 2 block [d_l e_l; e_l d_{l+1}] closer to
            // d_l. `g` starts as the bottom entry of T − shift·I.
            let h = (d[l + 1] - d[l]) / (2.0 * e[l]);
            let root = h.hypot(1.0);
            let mut g = d[m] - d[l] + e[l] / (h + root.copysign(h));
            // Chase the bulge from the bottom (m) up to l with rotations in planes (i, i+1).
            let (mut s, mut c, mut p) = (1.0f64, 1.0f64, 0.0f64);
            let mut restarted = false;
            for i in (l..m).rev() {
                let f = s * e[i];
                let b = c * e[i];
                let r = f.hypot(g);
                e[i + 1] = r;
                if r == 0.0 {
                    // Underflow: T split at i+1; undo the pending shift there and start over.
                    d[i + 1] -= p;
                    e[m] = 0.0;
                    restarted = true;
                    break;
                }
                s = f / r;
                c = g / r;
                let g0 = d[i + 1] - p;
                let t = (d[i] - g0) * s + 2.0 * c * b;
                p = s * t;
                d[i + 1] = g0 + p;
                g = c * t - b;
                rotations.push(Rotation { i, c, s });
            }
            if !restarted {
                d[l] -= p;
                e[l] = g;
                e[m] = 0.0;
            }
        }
        if rotations.len() >= ROTATIONS_PER_ROW * n {
            zt.rotate(&rotations);
            rotations.clear();
        }
    }
    zt.rotate(&rotations);
}

/// A Givens rotation of rows `i` and `i + 1`: `(z_i, z_{i+1}) ← (c z_i − s z_{i+1}, s z_i + c z_{i+1})`.
#[derive(Clone, Copy)]
struct Rotation {
    i: usize,
    c: f64,
    s: f64,
}

/// Applies `rotations` in order to the rows of one strip (`STRIP` entries per row).
fn rotate_strip(strip: &mut [f64], rotations: &[Rotation]) {
    #[cfg(target_arch = "x86_64")]
    if simd::avx() {
        // SAFETY: `simd::avx` checked that the CPU supports AVX.
        return unsafe { rotate_strip_avx(strip, rotations) };
    }
    rotate_strip_body(strip, rotations)
}

/// [`rotate_strip`] compiled with AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline(never)]
unsafe fn rotate_strip_avx(strip: &mut [f64], rotations: &[Rotation]) {
    rotate_strip_body(strip, rotations)
}

#[inline(always)]
fn rotate_strip_body(strip: &mut [f64], rotations: &[Rotation]) {
    for &Rotation { i, c, s } in rotations {
        let (upper, lower) = strip.split_at_mut((i + 1) * STRIP);
        let zi: &mut [f64; STRIP] = (&mut upper[i * STRIP..]).try_into().expect("a strip row");
        let zi1: &mut [f64; STRIP] = (&mut lower[..STRIP]).try_into().expect("a strip row");
        for (x, y) in zi.iter_mut().zip(zi1.iter_mut()) {
            let (a, b) = (*x, *y);
            *x = c * a - s * b;
            *y = s * a + c * b;
        }
    }
}

/// `Σ row[t]·u[t]` (eight interleaved partial sums, in a fixed order) while adding `f·row[t]`
/// to `y[t]`; all three slices have the same length.
#[inline(always)]
fn dot_and_axpy(row: &[f64], u: &[f64], f: f64, y: &mut [f64]) -> f64 {
    const LANES: usize = 8;
    let split = row.len() - row.len() % LANES;
    let mut acc = [0.0f64; LANES];
    for ((r, uu), yy) in row[..split]
        .chunks_exact(LANES)
        .zip(u[..split].chunks_exact(LANES))
        .zip(y[..split].chunks_exact_mut(LANES))
    {
        for q in 0..LANES {
            acc[q] += r[q] * uu[q];
            yy[q] += f * r[q];
        }
    }
    let mut sum = ((acc[0] + acc[4]) + (acc[2] + acc[6])) + ((acc[1] + acc[5]) + (acc[3] + acc[7]));
    for ((r, uu), yy) in row[split..].iter().zip(&u[split..]).zip(&mut y[split..]) {
        sum += r * uu;
        *yy += f * r;
    }
    sum
}

/// `Σ x[t]·y[t]`, summed in order.
#[inline(always)]
fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
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

    /// AVX or not, one thread or several: the same bits (n = 300 spans several strips and the
    /// parallel row updates).
    #[test]
    fn bits_do_not_depend_on_avx_or_threads() {
        let n = 300;
        let a = random_spd(n, 11);
        let bits = |(values, vectors): (Vec<f64>, Vec<f64>)| -> Vec<u64> {
            values.iter().chain(&vectors).map(|v| v.to_bits()).collect()
        };
        let reference = bits(symmetric_eigen(&a, n));
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        assert!(one.install(|| bits(symmetric_eigen(&a, n)) == reference), "one thread");
        crate::simd::FORCE_PORTABLE.store(true, std::sync::atomic::Ordering::Relaxed);
        let portable = bits(symmetric_eigen(&a, n));
        crate::simd::FORCE_PORTABLE.store(false, std::sync::atomic::Ordering::Relaxed);
        assert!(portable == reference, "portable kernels");
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

    /// Checks `a = V Λ Vᵀ` to `tol · max|a|` and `VᵀV = I` to 1e-12 (upper triangle of `a`).
    fn check_decomposition(a: &[f64], n: usize, values: &[f64], vectors: &[f64], tol: f64) {
        let scale = a.iter().fold(0.0f64, |s, x| s.max(x.abs()));
        // rows of vt are the eigenvectors, so both checks run over contiguous rows
        let mut vt = vec![0.0; n * n];
        for i in 0..n {
            for k in 0..n {
                vt[k * n + i] = vectors[i * n + k];
            }
        }
        let mut worst_rebuilt = 0.0f64;
        let mut worst_dot = 0.0f64;
        for i in 0..n {
            for j in i..n {
                let rebuilt: f64 = (0..n)
                    .map(|k| vectors[i * n + k] * values[k] * vectors[j * n + k])
                    .sum();
                worst_rebuilt = worst_rebuilt.max((rebuilt - a[i * n + j]).abs());
                let dot: f64 = vt[i * n..(i + 1) * n]
                    .iter()
                    .zip(&vt[j * n..(j + 1) * n])
                    .map(|(x, y)| x * y)
                    .sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                worst_dot = worst_dot.max((dot - expected).abs());
            }
        }
        assert!(
            worst_rebuilt <= tol * scale,
            "n {n}: reconstruction error {worst_rebuilt:e} (scale {scale:e})"
        );
        assert!(worst_dot <= 1e-12, "n {n}: orthonormality error {worst_dot:e}");
    }

    #[test]
    fn reconstructs_n_200_spd_and_indefinite() {
        let n = 200;
        let a = random_spd(n, 11);
        let (values, vectors) = symmetric_eigen(&a, n);
        check_decomposition(&a, n, &values, &vectors, 1e-11);
        assert!(values.iter().all(|v| *v > 0.0));
        // A symmetric matrix with independent normal entries: indefinite.
        let g = SeededRng::derive(12, 0, 0, Stream::Sampling).normal_vec(n * n);
        let mut b = vec![0.0; n * n];
        for i in 0..n {
            for j in i..n {
                b[i * n + j] = g[i * n + j];
                b[j * n + i] = g[i * n + j];
            }
        }
        let (values, vectors) = symmetric_eigen(&b, n);
        check_decomposition(&b, n, &values, &vectors, 1e-11);
        assert!(values.iter().any(|v| *v < 0.0) && values.iter().any(|v| *v > 0.0));
    }

    /// An orthogonal matrix: a product of a few random Householder reflections.
    fn random_orthogonal(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = SeededRng::derive(seed, 0, 0, Stream::Sampling);
        let mut q = vec![0.0; n * n];
        for i in 0..n {
            q[i * n + i] = 1.0;
        }
        for _ in 0..4 {
            let w = rng.normal_vec(n);
            let ww: f64 = w.iter().map(|x| x * x).sum();
            for i in 0..n {
                let qw: f64 = (0..n).map(|j| q[i * n + j] * w[j]).sum();
                for j in 0..n {
                    q[i * n + j] -= 2.0 * qw * w[j] / ww;
                }
            }
        }
        q
    }

    #[test]
    fn repeated_eigenvalues() {
        let n = 60;
        let q = random_orthogonal(n, 13);
        // Multiplicities 20, 15, 10, 10, 5 (one of them zero, one negative).
        let spectrum: Vec<f64> = (0..n)
            .map(|i| match i {
                0..=19 => 2.0,
                20..=34 => 0.0,
                35..=44 => -1.5,
                45..=54 => 7.0,
                _ => 2.0 + 1e-9,
            })
            .collect();
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] = (0..n).map(|k| q[i * n + k] * spectrum[k] * q[j * n + k]).sum();
            }
        }
        let (values, vectors) = symmetric_eigen(&a, n);
        check_decomposition(&a, n, &values, &vectors, 1e-12);
        let mut sorted = values.clone();
        sorted.sort_by(f64::total_cmp);
        let mut expected = spectrum.clone();
        expected.sort_by(f64::total_cmp);
        for (v, x) in sorted.iter().zip(&expected) {
            assert!((v - x).abs() < 1e-13 * 7.0, "{v} vs {x}");
        }
        // Multiples of the identity and the zero matrix come back unchanged.
        for c in [3.0, 0.0] {
            let mut a = vec![0.0; n * n];
            for i in 0..n {
                a[i * n + i] = c;
            }
            let (values, vectors) = symmetric_eigen(&a, n);
            assert_eq!(values, vec![c; n]);
            let identity: Vec<f64> = (0..n * n).map(|i| if i % (n + 1) == 0 { 1.0 } else { 0.0 }).collect();
            assert_eq!(vectors, identity);
        }
    }

    #[test]
    fn small_and_structured_matrices() {
        let (values, vectors) = symmetric_eigen(&[], 0);
        assert!(values.is_empty() && vectors.is_empty());
        let (values, vectors) = symmetric_eigen(&[-2.5], 1);
        assert_eq!((values, vectors), (vec![-2.5], vec![1.0]));
        // Already tridiagonal, block diagonal (the QL iteration splits), widely scaled.
        let n = 30;
        let mut tri = vec![0.0; n * n];
        let mut blocks = vec![0.0; n * n];
        for i in 0..n {
            tri[i * n + i] = (i as f64 * 0.7).sin();
            if i + 1 < n {
                tri[i * n + i + 1] = 1.0;
                tri[(i + 1) * n + i] = 1.0;
            }
            for j in 0..n {
                if i / 10 == j / 10 {
                    blocks[i * n + j] = 1.0 / (1.0 + i as f64 + j as f64);
                }
            }
        }
        for a in [&tri, &blocks] {
            let (values, vectors) = symmetric_eigen(a, n);
            check_decomposition(a, n, &values, &vectors, 1e-13);
        }
        for factor in [1e-150, 1e150] {
            let scaled: Vec<f64> = tri.iter().map(|x| x * factor).collect();
            let (values, vectors) = symmetric_eigen(&scaled, n);
            check_decomposition(&scaled, n, &values, &vectors, 1e-13);
        }
    }

    #[test]
    fn reads_only_the_upper_triangle_and_is_deterministic() {
        let n = 50;
        let a = random_spd(n, 14);
        let mut garbage = a.clone();
        for i in 0..n {
            for j in 0..i {
                garbage[i * n + j] = 1e6 * (i + j) as f64;
            }
        }
        let first = symmetric_eigen(&a, n);
        let again = symmetric_eigen(&a, n);
        let upper_only = symmetric_eigen(&garbage, n);
        let warm = symmetric_eigen_from(&a, n, &random_orthogonal(n, 15));
        let bits = |(values, vectors): &(Vec<f64>, Vec<f64>)| -> Vec<u64> {
            values.iter().chain(vectors).map(|x| x.to_bits()).collect()
        };
        assert_eq!(bits(&first), bits(&again));
        assert_eq!(bits(&first), bits(&upper_only));
        assert_eq!(bits(&first), bits(&warm));
    }

    #[test]
    fn non_finite_input_gives_nan() {
        let (values, vectors) = symmetric_eigen(&[1.0, f64::NAN, 0.0, 1.0], 2);
        assert!(values.iter().chain(&vectors).all(|x| x.is_nan()));
        let (values, vectors) = symmetric_eigen(&[f64::INFINITY], 1);
        assert!(values[0].is_nan() && vectors[0].is_nan());
        // the lower triangle is not read
        let (values, _) = symmetric_eigen(&[1.0, 0.0, f64::NAN, 1.0], 2);
        assert_eq!(values, vec![1.0, 1.0]);
    }

    /// `G Gᵀ / n` plus a diagonal with scales spread over 10⁻³…10³, G standard normal.
    fn random_spd(n: usize, seed: u64) -> Vec<f64> {
        let mut rng = SeededRng::derive(seed, 0, 0, Stream::Sampling);
        let g: Vec<f64> = rng.normal_vec(n * n);
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
}
