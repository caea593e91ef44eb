//! Dynamic pose (thesis §3.3.3.1; thesis-code-facts §3.4): a "long-exposure photograph" of the
//! robot as a 16×16 binary grid, the 256 morphology features of the shape classifier.
//!
//! Per step, as 2D-VSR-Sim's `Outcome` (a300845) computes it: take each voxel's axis-aligned
//! box, the robot's overall box, enlarge its shorter side symmetrically to a square, map every
//! voxel box onto index ranges `round((b − min)/(max − min) · 15)` in x and y and set all the
//! cells covered. The dynamic pose is the element-wise mode over the steps: a cell is on iff it
//! was on in more than half of them.

use serde::{Deserialize, Serialize};
use vsrlab_physics::Vec2;
use vsrlab_tasks::Trace;

/// Side of the pose grid.
pub const POSE_SIDE: usize = 16;

/// A 16×16 binary pose, row-major from the bottom row: index = y·16 + x.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Pose(pub Vec<bool>);

impl Pose {
    /// An empty pose.
    pub fn empty() -> Pose {
        Pose(vec![false; POSE_SIDE * POSE_SIDE])
    }

    /// Whether cell (x, y) is on (y = 0 at the bottom).
    pub fn get(&self, x: usize, y: usize) -> bool {
        self.0[y * POSE_SIDE + x]
    }

    /// The 256 features (1.0 = on).
    pub fn features(&self) -> Vec<f64> {
        self.0.iter().map(|&b| if b { 1.0 } else { 0.0 }).collect()
    }

    /// Number of cells on.
    pub fn count(&self) -> usize {
        self.0.iter().filter(|&&b| b).count()
    }

    /// Rows of `#` and `.`, top row first.
    pub fn to_rows(&self) -> Vec<String> {
        (0..POSE_SIDE)
            .rev()
            .map(|y| (0..POSE_SIDE).map(|x| if self.get(x, y) { '#' } else { '.' }).collect())
            .collect()
    }
}

/// Java's `Math.round`: floor(x + 0.5).
pub(crate) fn java_round(x: f64) -> i64 {
    (x + 0.5).floor() as i64
}

/// The pose of one step, from the voxels' outer polygons.
pub fn pose_of<P: AsRef<[Vec2]>>(polygons: &[P]) -> Pose {
    let mut pose = Pose::empty();
    if polygons.is_empty() {
        return pose;
    }
    let boxes: Vec<[f64; 4]> = polygons
        .iter()
        .map(|p| {
            let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
            for v in p.as_ref() {
                x0 = x0.min(v.x);
                y0 = y0.min(v.y);
                x1 = x1.max(v.x);
                y1 = y1.max(v.y);
            }
            [x0, y0, x1, y1]
        })
        .collect();
    let mut x0 = boxes.iter().map(|b| b[0]).fold(f64::INFINITY, f64::min);
    let mut y0 = boxes.iter().map(|b| b[1]).fold(f64::INFINITY, f64::min);
    let x1 = boxes.iter().map(|b| b[2]).fold(f64::NEG_INFINITY, f64::max);
    let y1 = boxes.iter().map(|b| b[3]).fold(f64::NEG_INFINITY, f64::max);
    let (w, h) = (x1 - x0, y1 - y0);
    if !(w.is_finite() && h.is_finite()) {
        return pose;
    }
    // Enlarge the shorter side symmetrically: the square has side max(w, h).
    if w > h {
        y0 -= (w - h) / 2.0;
    } else {
        x0 -= (h - w) / 2.0;
    }
    let side = w.max(h);
    if side <= 0.0 {
        return pose;
    }
    let last = (POSE_SIDE - 1) as f64;
    let index = |v: f64, lo: f64| java_round((v - lo) / side * last).clamp(0, POSE_SIDE as i64 - 1) as usize;
    for b in &boxes {
        for y in index(b[1], y0)..=index(b[3], y0) {
            for x in index(b[0], x0)..=index(b[2], x0) {
                pose.0[y * POSE_SIDE + x] = true;
            }
        }
    }
    pose
}

/// Element-wise mode of many poses: a cell is on iff on in more than half of them.
pub fn mode_pose<'a>(poses: impl IntoIterator<Item = &'a Pose>) -> Pose {
    let mut counts = [0usize; POSE_SIDE * POSE_SIDE];
    let mut n = 0usize;
    for p in poses {
        n += 1;
        for (c, &b) in counts.iter_mut().zip(&p.0) {
            *c += b as usize;
        }
    }
    Pose(counts.iter().map(|&c| 2 * c > n).collect())
}

/// The dynamic pose over every recorded step of a full trace (empty when there is none).
pub fn dynamic_pose(trace: &Trace) -> Pose {
    let mut counts = [0usize; POSE_SIDE * POSE_SIDE];
    let mut n = 0usize;
    for k in 0..trace.len() {
        let polys: Vec<&[Vec2]> = trace.polygons_at(k).iter().collect();
        if polys.is_empty() {
            continue;
        }
        n += 1;
        for (c, &b) in counts.iter_mut().zip(&pose_of(&polys).0) {
            *c += b as usize;
        }
    }
    Pose(counts.iter().map(|&c| 2 * c > n).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::square;

    #[test]
    fn a_single_voxel_fills_the_grid() {
        let p = pose_of(&[square(3.0, 1.0, 3.0)]);
        assert_eq!(p.count(), 256);
    }

    #[test]
    fn a_worm_fills_the_bottom_half_band() {
        // 4×1 worm of side 1 from x = 0 to 4, y = 0..1: the square box spans y ∈ [−1.5, 2.5],
        // the worm covers y indices round(1.5/4·15) = 6 to round(2.5/4·15) = 9.
        let polys: Vec<_> = (0..4).map(|i| square(i as f64, 0.0, 1.0)).collect();
        let p = pose_of(&polys);
        for y in 0..POSE_SIDE {
            for x in 0..POSE_SIDE {
                assert_eq!(p.get(x, y), (6..=9).contains(&y), "({x}, {y})");
            }
        }
    }

    #[test]
    fn an_l_shape_leaves_a_hole() {
        // Voxels at cells (0,0), (1,0), (0,1) of side 1: the box is the 2×2 square; the empty
        // cell (1,1) covers x, y indices round(0.5·15) = 8..15 but its neighbours' boxes reach
        // index 8 too, so the empty part is x, y ∈ 9..15.
        let p = pose_of(&[square(0.0, 0.0, 1.0), square(1.0, 0.0, 1.0), square(0.0, 1.0, 1.0)]);
        for y in 0..POSE_SIDE {
            for x in 0..POSE_SIDE {
                assert_eq!(p.get(x, y), !(x >= 9 && y >= 9), "({x}, {y})");
            }
        }
    }

    #[test]
    fn mode_is_a_strict_majority() {
        let mut on = Pose::empty();
        on.0[0] = true;
        let off = Pose::empty();
        assert!(mode_pose([&on, &on, &off]).get(0, 0));
        assert!(!mode_pose([&on, &off]).get(0, 0));
    }

    #[test]
    fn dynamic_pose_of_a_trace() {
        let mut t = Trace {
            dt: 1.0 / 60.0,
            outline_corners: vec![4, 4],
            ..Default::default()
        };
        for k in 0..3 {
            t.times.push(k as f64 / 60.0);
            // Two voxels side by side, then (last step) stacked: the mode is the side-by-side pose.
            let second = if k < 2 {
                square(1.0, 0.0, 1.0)
            } else {
                square(0.0, 1.0, 1.0)
            };
            t.outlines.extend_from_slice(&square(0.0, 0.0, 1.0));
            t.outlines.extend_from_slice(&second);
        }
        let p = dynamic_pose(&t);
        let expected = pose_of(&[square(0.0, 0.0, 1.0), square(1.0, 0.0, 1.0)]);
        assert_eq!(p, expected);
    }
}
