//! Statistics: descriptive summaries, the two-sided Mann–Whitney U test (as
//! `scipy.stats.mannwhitneyu` with its defaults), and the normal tail it needs.

use serde::{Deserialize, Serialize};

/// Arithmetic mean (NaN when empty).
pub fn mean(v: &[f64]) -> f64 {
    if v.is_empty() {
        f64::NAN
    } else {
        v.iter().sum::<f64>() / v.len() as f64
    }
}

/// Sample standard deviation (n − 1 in the denominator; 0 for one value, NaN when empty).
pub fn std_dev(v: &[f64]) -> f64 {
    match v.len() {
        0 => f64::NAN,
        1 => 0.0,
        n => {
            let m = mean(v);
            (v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1) as f64).sqrt()
        }
    }
}

/// Quantile q ∈ [0, 1] with linear interpolation between order statistics (NumPy's default
/// "linear" method); NaN when empty. NaNs in the input sort last.
pub fn quantile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let pos = q.clamp(0.0, 1.0) * (s.len() - 1) as f64;
    let (lo, hi) = (pos.floor() as usize, pos.ceil() as usize);
    s[lo] + (s[hi] - s[lo]) * (pos - lo as f64)
}

/// Median (mean of the two middle values for an even count; NaN when empty).
pub fn median(v: &[f64]) -> f64 {
    quantile(v, 0.5)
}

/// Five-number summary for a boxplot: whiskers at the most extreme values within 1.5 IQR of the
/// quartiles (Tukey), and the values beyond them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoxStats {
    /// Lower whisker.
    pub low: f64,
    /// First quartile.
    pub q1: f64,
    /// Median.
    pub median: f64,
    /// Third quartile.
    pub q3: f64,
    /// Upper whisker.
    pub high: f64,
    /// Values beyond the whiskers.
    pub outliers: Vec<f64>,
}

impl BoxStats {
    /// The summary of `v` (None when empty).
    pub fn of(v: &[f64]) -> Option<BoxStats> {
        let v: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
        if v.is_empty() {
            return None;
        }
        let (q1, med, q3) = (quantile(&v, 0.25), quantile(&v, 0.5), quantile(&v, 0.75));
        let iqr = q3 - q1;
        let (lo_fence, hi_fence) = (q1 - 1.5 * iqr, q3 + 1.5 * iqr);
        let inside: Vec<f64> = v.iter().copied().filter(|&x| x >= lo_fence && x <= hi_fence).collect();
        Some(BoxStats {
            low: inside.iter().copied().fold(f64::INFINITY, f64::min),
            q1,
            median: med,
            q3,
            high: inside.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            outliers: v.iter().copied().filter(|&x| x < lo_fence || x > hi_fence).collect(),
        })
    }
}

/// erfc(x), accurate to about 1e-15 relative for x ≤ 3 and better beyond.
pub fn erfc(x: f64) -> f64 {
    if x.is_nan() {
        return f64::NAN;
    }
    if x < 0.0 {
        return 2.0 - erfc(-x);
    }
    if x > 27.3 {
        return 0.0; // below the smallest subnormal
    }
    if x < 3.0 {
        // erf x = 2/√π · e^(−x²) · Σ 2ⁿ x^(2n+1) / (1·3·…·(2n+1)): positive terms, no cancellation.
        let mut term = x;
        let mut sum = x;
        let mut n = 0.0;
        while term > sum * 1e-17 {
            n += 1.0;
            term *= 2.0 * x * x / (2.0 * n + 1.0);
            sum += term;
        }
        1.0 - 2.0 / std::f64::consts::PI.sqrt() * (-x * x).exp() * sum
    } else {
        // erfc x = e^(−x²)/√π · 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + …)))), by modified Lentz.
        let tiny = 1e-300;
        let mut f = x;
        let mut c = x;
        let mut d = 0.0;
        for k in 1..500 {
            let a = k as f64 / 2.0;
            d = x + a * d;
            d = if d.abs() < tiny { tiny } else { d };
            c = x + a / c;
            c = if c.abs() < tiny { tiny } else { c };
            d = 1.0 / d;
            let delta = c * d;
            f *= delta;
            if (delta - 1.0).abs() < 1e-16 {
                break;
            }
        }
        (-x * x).exp() / std::f64::consts::PI.sqrt() / f
    }
}

/// Standard normal survival function P(Z > z).
pub fn normal_sf(z: f64) -> f64 {
    0.5 * erfc(z / std::f64::consts::SQRT_2)
}

/// Which distribution a Mann–Whitney p-value came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MwuMethod {
    /// The exact null distribution of U.
    Exact,
    /// Normal approximation with tie correction and continuity correction.
    Asymptotic,
}

/// Result of a Mann–Whitney U test.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MannWhitney {
    /// U₁ = R₁ − n₁(n₁+1)/2, the statistic of the first sample (scipy's `statistic`).
    pub u: f64,
    /// Two-sided p-value.
    pub p: f64,
    /// How p was computed.
    pub method: MwuMethod,
}

/// Average ranks (1-based) of `values`, and the sizes of the groups of tied values.
pub fn rank_average(values: &[f64]) -> (Vec<f64>, Vec<usize>) {
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
    let mut ranks = vec![0.0; values.len()];
    let mut ties = Vec::new();
    let mut i = 0;
    while i < order.len() {
        let mut j = i + 1;
        while j < order.len() && values[order[j]] == values[order[i]] {
            j += 1;
        }
        let r = (i + 1 + j) as f64 / 2.0;
        for &k in &order[i..j] {
            ranks[k] = r;
        }
        ties.push(j - i);
        i = j;
    }
    (ranks, ties)
}

/// Number of arrangements of n₁ + n₂ distinct values giving each U = 0..=n₁n₂ (as f64).
fn u_counts(n1: usize, n2: usize) -> Vec<f64> {
    let (a, b) = (n1.min(n2), n1.max(n2));
    // f[i][u]: arrangements of i "a" values among the j "b" values seen so far with U = u;
    // appending a "b" value leaves U unchanged, appending an "a" value after j "b"s adds j.
    let umax = a * b;
    let mut f = vec![vec![0.0f64; umax + 1]; a + 1];
    f[0][0] = 1.0;
    // Build by increasing total length: process positions, deciding a or b; equivalently iterate
    // j (number of b's) and insert a's with the recurrence f_j[i][u] = f_{j-1}[i][u] + f_j[i-1][u-j].
    for row in f.iter_mut() {
        // j = 0: a's only, U = 0.
        row[0] = 1.0;
    }
    for j in 1..=b {
        // Row i = 0 stays (one arrangement, U = 0). For i ≥ 1, in increasing i so that f[i−1] is
        // already the value for j.
        for i in 1..=a {
            let (prev, cur) = f.split_at_mut(i);
            let below = &prev[i - 1];
            let row = &mut cur[0];
            for u in (j..=umax).rev() {
                row[u] += below[u - j];
            }
        }
    }
    f.swap_remove(a)
}

/// Two-sided Mann–Whitney U test of `x` against `y`, as `scipy.stats.mannwhitneyu(x, y)`
/// (`use_continuity=True`, `alternative="two-sided"`, `method="auto"`): exact when one sample
/// has at most 8 values and there are no ties, otherwise the normal approximation with tie and
/// continuity correction. Returns None if a sample is empty or holds a NaN.
pub fn mann_whitney_u(x: &[f64], y: &[f64]) -> Option<MannWhitney> {
    if x.is_empty() || y.is_empty() || x.iter().chain(y).any(|v| v.is_nan()) {
        return None;
    }
    let (n1, n2) = (x.len(), y.len());
    let all: Vec<f64> = x.iter().chain(y).copied().collect();
    let (ranks, ties) = rank_average(&all);
    let r1: f64 = ranks[..n1].iter().sum();
    let u1 = r1 - (n1 * (n1 + 1)) as f64 / 2.0;
    let u2 = (n1 * n2) as f64 - u1;
    let u = u1.max(u2);
    let has_ties = ties.iter().any(|&t| t > 1);
    let exact = !has_ties && (n1 <= 8 || n2 <= 8);
    let p = if exact {
        let counts = u_counts(n1, n2);
        let total: f64 = counts.iter().sum();
        // P(U ≥ u) = P(U ≤ n₁n₂ − u) by symmetry: sum the short tail.
        let k = (n1 * n2) as f64 - u;
        let k = k.round() as usize;
        2.0 * counts[..=k].iter().sum::<f64>() / total
    } else {
        let (n1f, n2f) = (n1 as f64, n2 as f64);
        let n = n1f + n2f;
        let tie_term: f64 = ties.iter().map(|&t| (t * t * t - t) as f64).sum();
        let s = (n1f * n2f / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)))).sqrt();
        let z = (u - n1f * n2f / 2.0 - 0.5) / s;
        2.0 * if z.is_nan() { 0.5 } else { normal_sf(z) }
    };
    Some(MannWhitney {
        u: u1,
        p: p.clamp(0.0, 1.0),
        method: if exact { MwuMethod::Exact } else { MwuMethod::Asymptotic },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn descriptive() {
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
        assert!((std_dev(&[2.0, 4.0, 4.0, 4.0, 5.0, 5.0, 7.0, 9.0]) - (32.0f64 / 7.0).sqrt()).abs() < 1e-12);
        assert_eq!(quantile(&[1.0, 2.0, 3.0, 4.0], 0.25), 1.75);
        assert!(median(&[]).is_nan());
        let b = BoxStats::of(&[1.0, 2.0, 3.0, 4.0, 100.0]).unwrap();
        assert_eq!((b.q1, b.median, b.q3), (2.0, 3.0, 4.0));
        assert_eq!((b.low, b.high), (1.0, 4.0));
        assert_eq!(b.outliers, vec![100.0]);
    }

    #[test]
    fn erfc_known_values() {
        // Reference values: Python's math.erfc.
        for (x, e) in [
            (0.0, 1.0),
            (0.5, 0.4795001221869535),
            (1.0, 0.15729920705028513),
            (2.0, 0.004677734981047265),
            (3.0, 2.2090496998585438e-05),
            (5.0, 1.5374597944280351e-12),
            (-1.0, 1.842700792949715),
        ] {
            let got = erfc(x);
            assert!((got - e).abs() <= 1e-13 * e, "erfc({x}) = {got}, want {e}");
        }
        assert!((normal_sf(1.959963984540054) - 0.025).abs() < 1e-15);
    }

    #[test]
    fn exact_distribution_is_symmetric_and_sums_to_binomial() {
        let c = u_counts(3, 4);
        assert_eq!(c.len(), 13);
        assert_eq!(c.iter().sum::<f64>(), 35.0); // C(7, 3)
        for u in 0..13 {
            assert_eq!(c[u], c[12 - u]);
        }
        assert_eq!(&c[..4], &[1.0, 1.0, 2.0, 3.0]);
    }

    #[test]
    fn small_exact_example() {
        // x all below y: U1 = 0, p = 2 / C(6, 3) = 0.1.
        let r = mann_whitney_u(&[1.0, 2.0, 3.0], &[4.0, 5.0, 6.0]).unwrap();
        assert_eq!(r.u, 0.0);
        assert!((r.p - 0.1).abs() < 1e-15);
        assert_eq!(r.method, MwuMethod::Exact);
        // Identical samples: p = 1.
        let r = mann_whitney_u(&[1.0, 1.0], &[1.0, 1.0, 1.0]).unwrap();
        assert_eq!(r.p, 1.0);
        assert_eq!(r.method, MwuMethod::Asymptotic);
    }
}
