//! Standard benchmark functions (all minimised) for tests, examples and benchmarks.
//!
//! Single objective: sphere, Rosenbrock, Rastrigin (optimum 0). Bi-objective: ZDT1–3 (Zitzler,
//! Deb & Thiele 2000), defined on `[0, 1]^n`, with their true Pareto fronts.

use std::f64::consts::PI;

/// Σ x_i². Minimum 0 at the origin.
pub fn sphere(x: &[f64]) -> f64 {
    x.iter().map(|v| v * v).sum()
}

/// Σ 100 (x_{i+1} − x_i²)² + (1 − x_i)². Minimum 0 at (1, …, 1).
pub fn rosenbrock(x: &[f64]) -> f64 {
    x.windows(2)
        .map(|w| 100.0 * (w[1] - w[0] * w[0]).powi(2) + (1.0 - w[0]).powi(2))
        .sum()
}

/// 10 n + Σ x_i² − 10 cos(2π x_i). Minimum 0 at the origin; a local minimum at every integer
/// point.
pub fn rastrigin(x: &[f64]) -> f64 {
    10.0 * x.len() as f64 + x.iter().map(|v| v * v - 10.0 * (2.0 * PI * v).cos()).sum::<f64>()
}

fn zdt_g(x: &[f64]) -> f64 {
    1.0 + 9.0 * x[1..].iter().sum::<f64>() / (x.len() - 1) as f64
}

/// ZDT1: convex front f2 = 1 − √f1 (reached when x_2..n = 0).
pub fn zdt1(x: &[f64]) -> [f64; 2] {
    let f1 = x[0];
    let g = zdt_g(x);
    [f1, g * (1.0 - (f1 / g).sqrt())]
}

/// ZDT2: concave front f2 = 1 − f1².
pub fn zdt2(x: &[f64]) -> [f64; 2] {
    let f1 = x[0];
    let g = zdt_g(x);
    [f1, g * (1.0 - (f1 / g).powi(2))]
}

/// ZDT3: disconnected front, the non-dominated part of f2 = 1 − √f1 − f1 sin(10π f1).
pub fn zdt3(x: &[f64]) -> [f64; 2] {
    let f1 = x[0];
    let g = zdt_g(x);
    [f1, g * (1.0 - (f1 / g).sqrt() - f1 / g * (10.0 * PI * f1).sin())]
}

/// `points` samples of the true Pareto front of ZDT1, 2 or 3 (non-dominated points of
/// the g = 1 curve for evenly spaced f1 in [0, 1]).
pub fn zdt_true_front(problem: u8, points: usize) -> Vec<[f64; 2]> {
    let curve: Vec<[f64; 2]> = (0..points)
        .map(|i| {
            let f1 = i as f64 / (points - 1) as f64;
            let f2 = match problem {
                1 => 1.0 - f1.sqrt(),
                2 => 1.0 - f1 * f1,
                3 => 1.0 - f1.sqrt() - f1 * (10.0 * PI * f1).sin(),
                _ => panic!("ZDT{problem} is not provided"),
            };
            [f1, f2]
        })
        .collect();
    // f1 increases along the curve, so a point is non-dominated iff its f2 is below every f2
    // before it.
    let mut front = Vec::new();
    let mut lowest = f64::INFINITY;
    for p in curve {
        if p[1] < lowest {
            lowest = p[1];
            front.push(p);
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn optima_are_zero() {
        assert_eq!(sphere(&[0.0; 5]), 0.0);
        assert_eq!(rosenbrock(&[1.0; 5]), 0.0);
        assert!(rastrigin(&[0.0; 5]).abs() < 1e-12);
        assert!((rastrigin(&[1.0, 0.0]) - 1.0).abs() < 1e-9);
        let x = [0.25, 0.0, 0.0];
        assert_eq!(zdt1(&x), [0.25, 0.5]);
        assert_eq!(zdt2(&x), [0.25, 0.9375]);
    }
}
