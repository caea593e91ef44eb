//! Length projection after each substep: springs are pushed back toward a band around their
//! initial length, first all at once (loose bands), then one after another (tight limits), each
//! removing a fraction of the excess.

use super::points::Points;
use super::quad_geometry::norm;
use super::springs::Springs;

/// Tight limits, applied in order, and scratch space for the loose pass.
#[derive(Debug, Clone)]
pub(crate) struct Projection {
    pub limit_spring: Vec<u32>,
    pub limit_band: Vec<f64>,
    shift_x: Vec<f64>,
    shift_y: Vec<f64>,
}

/// By how much `len` lies outside `initial × [1 - band, 1 + band]` (negative when too short).
fn excess(len: f64, initial: f64, band: f64) -> f64 {
    if len > initial * (1.0 + band) {
        len - initial * (1.0 + band)
    } else if len < initial * (1.0 - band) {
        len - initial * (1.0 - band)
    } else {
        0.0
    }
}

impl Projection {
    /// Tight limits `(spring, band)` for a world of `point_count` points.
    pub fn new(limits: &[(u32, f64)], point_count: usize) -> Self {
        Self {
            limit_spring: limits.iter().map(|l| l.0).collect(),
            limit_band: limits.iter().map(|l| l.1).collect(),
            shift_x: vec![0.0; point_count],
            shift_y: vec![0.0; point_count],
        }
    }

    /// Loose pass: every spring with a free end outside its band moves each free end by `correction / 2`
    /// of the excess, all shifts computed from the same positions and then applied together.
    pub fn project_bands(&mut self, springs: &Springs, points: &mut Points, correction: f64) {
        self.shift_x.fill(0.0);
        self.shift_y.fill(0.0);
        for s in springs.touching_free().indices() {
            let (a, b) = (springs.a[s] as usize, springs.b[s] as usize);
            let (dx, dy) = (points.x[a] - points.x[b], points.y[a] - points.y[b]);
            let len = norm(dx, dy);
            let e = excess(len, springs.initial[s], springs.band[s]);
            if e == 0.0 || len == 0.0 {
                continue;
            }
            let k = e / (2.0 * len) * correction;
            self.shift_x[a] -= dx * k;
            self.shift_y[a] -= dy * k;
            self.shift_x[b] += dx * k;
            self.shift_y[b] += dy * k;
        }
        for i in points.free.indices() {
            points.x[i] += self.shift_x[i];
            points.y[i] += self.shift_y[i];
        }
    }

    /// Tight pass: each limit in turn moves each free end of its spring by `correction / 2` of
    /// the excess over its band, using the positions the previous limits left.
    pub fn project_limits(&self, springs: &Springs, points: &mut Points, correction: f64) {
        for (&s, &band) in self.limit_spring.iter().zip(&self.limit_band) {
            let s = s as usize;
            let (a, b) = (springs.a[s] as usize, springs.b[s] as usize);
            let (dx, dy) = (points.x[a] - points.x[b], points.y[a] - points.y[b]);
            let len = norm(dx, dy);
            let e = excess(len, springs.initial[s], band);
            if e == 0.0 || len == 0.0 {
                continue;
            }
            let k = e / (2.0 * len) * correction;
            if !points.fixed[a] {
                points.x[a] -= dx * k;
                points.y[a] -= dy * k;
            }
            if !points.fixed[b] {
                points.x[b] += dx * k;
                points.y[b] += dy * k;
            }
        }
    }
}
