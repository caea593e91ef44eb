//! Curves across runs: each run's step-wise series (e.g. best fitness after each generation) is
//! read on a common evaluation grid, and summarised by the median and the standard deviation
//! across the runs that have a value there.

use crate::stats::{median, std_dev};

/// Value of a step-wise series at x: the y of the last point with x' ≤ x (NaN before the first
/// point). `points` must be sorted by x.
pub fn step_at(points: &[(f64, f64)], x: f64) -> f64 {
    let i = points.partition_point(|p| p.0 <= x);
    if i == 0 {
        f64::NAN
    } else {
        points[i - 1].1
    }
}

/// `n` evenly spaced values from `lo` to `hi` inclusive.
pub fn linspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    match n {
        0 => Vec::new(),
        1 => vec![lo],
        _ => (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect(),
    }
}

/// Median and sd across runs on a grid.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// Grid.
    pub x: Vec<f64>,
    /// Median across the runs with a (finite) value at x; NaN if none.
    pub median: Vec<f64>,
    /// Sample standard deviation across those runs (0 for one run).
    pub sd: Vec<f64>,
    /// Number of runs with a value at x.
    pub runs: Vec<usize>,
}

/// Summarises step-wise run curves on `grid`. Runs stop contributing after their last point
/// only if `extend` is false; with `extend` a finished run keeps its last value.
pub fn band(curves: &[Vec<(f64, f64)>], grid: &[f64], extend: bool) -> Band {
    let mut out = Band {
        x: grid.to_vec(),
        median: Vec::new(),
        sd: Vec::new(),
        runs: Vec::new(),
    };
    for &x in grid {
        let vals: Vec<f64> = curves
            .iter()
            .filter(|c| extend || c.last().is_some_and(|l| x <= l.0 + 1e-9))
            .map(|c| step_at(c, x))
            .filter(|v| v.is_finite())
            .collect();
        out.median.push(if vals.is_empty() { f64::NAN } else { median(&vals) });
        out.sd.push(if vals.is_empty() { f64::NAN } else { std_dev(&vals) });
        out.runs.push(vals.len());
    }
    out
}

/// A grid of `n` points spanning the curves, from the earliest first x to the latest last x.
pub fn grid_for(curves: &[Vec<(f64, f64)>], n: usize) -> Vec<f64> {
    let lo = curves
        .iter()
        .filter_map(|c| c.first())
        .map(|p| p.0)
        .fold(f64::INFINITY, f64::min);
    let hi = curves
        .iter()
        .filter_map(|c| c.last())
        .map(|p| p.0)
        .fold(f64::NEG_INFINITY, f64::max);
    if lo.is_finite() && hi.is_finite() {
        linspace(lo, hi, n)
    } else {
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn step_values_and_bands() {
        let a = vec![(100.0, 1.0), (200.0, 2.0), (300.0, 3.0)];
        let b = vec![(100.0, 3.0), (250.0, 5.0)];
        assert!(step_at(&a, 50.0).is_nan());
        assert_eq!(step_at(&a, 250.0), 2.0);
        let g = grid_for(&[a.clone(), b.clone()], 5);
        assert_eq!(g, vec![100.0, 150.0, 200.0, 250.0, 300.0]);
        let bd = band(&[a.clone(), b.clone()], &g, false);
        assert_eq!(bd.median, vec![2.0, 2.0, 2.5, 3.5, 3.0]);
        assert_eq!(bd.runs, vec![2, 2, 2, 2, 1]);
        assert!((bd.sd[0] - 2.0f64.sqrt()).abs() < 1e-12);
        assert_eq!(bd.sd[4], 0.0);
        let ext = band(&[a, b], &g, true);
        assert_eq!(ext.median[4], 4.0);
    }
}
