//! Axis-aligned bounding boxes for the broad phase.

use crate::math::Vec2;

/// An axis-aligned bounding box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Lower-left corner.
    pub min: Vec2,
    /// Upper-right corner.
    pub max: Vec2,
}

impl Aabb {
    /// The box around a set of points (which must not be empty).
    pub fn of_points(points: &[Vec2]) -> Aabb {
        let mut min = points[0];
        let mut max = points[0];
        for &p in &points[1..] {
            min = min.min(p);
            max = max.max(p);
        }
        Aabb { min, max }
    }
    /// The box grown by `margin` on every side.
    pub fn inflated(self, margin: f64) -> Aabb {
        Aabb {
            min: self.min - Vec2::new(margin, margin),
            max: self.max + Vec2::new(margin, margin),
        }
    }
    /// True when the two boxes overlap (touching counts). All four comparisons are evaluated,
    /// without branches: in the broad phase the outcome is unpredictable.
    #[inline(always)]
    pub fn overlaps(&self, o: &Aabb) -> bool {
        (self.min.x <= o.max.x) & (o.min.x <= self.max.x) & (self.min.y <= o.max.y) & (o.min.y <= self.max.y)
    }
}
