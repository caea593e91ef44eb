//! Convex polygons and circles, the shapes the engine collides (boxes are polygons; a circle is a
//! one-vertex polygon with a radius, so both share one inline layout).

use crate::math::{Rot, Vec2};
use serde::{Deserialize, Serialize};

/// Most vertices a collision polygon may have (keeps polygons inline, without heap storage).
pub const MAX_POLYGON_VERTICES: usize = 8;

/// A convex polygon in counter-clockwise order, in its owner's local frame; or a circle (one
/// vertex, the centre, and a radius).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Polygon {
    /// Number of used vertices (3..=8 for a polygon, 1 for a circle).
    pub count: usize,
    /// Vertices, counter-clockwise; only the first `count` are used.
    pub vertices: [Vec2; MAX_POLYGON_VERTICES],
    /// Outward unit normal of edge i (from vertex i to vertex i+1).
    pub normals: [Vec2; MAX_POLYGON_VERTICES],
    /// Radius of a circle (0 for a polygon).
    #[serde(default)]
    pub radius: f64,
}

impl Polygon {
    /// An axis-aligned box of half extents `hx`, `hy` centred at `center`.
    pub fn rect(center: Vec2, hx: f64, hy: f64) -> Polygon {
        let pts = [
            center + Vec2::new(-hx, -hy),
            center + Vec2::new(hx, -hy),
            center + Vec2::new(hx, hy),
            center + Vec2::new(-hx, hy),
        ];
        Polygon::convex(&pts).expect("a box with positive extents is a valid polygon")
    }

    /// A square of side `side` centred at `center`.
    pub fn square(center: Vec2, side: f64) -> Polygon {
        Polygon::rect(center, side / 2.0, side / 2.0)
    }

    /// Builds a polygon from counter-clockwise convex points; `None` when there are fewer than 3 or
    /// more than [`MAX_POLYGON_VERTICES`] points, or when the points are not strictly convex and CCW.
    pub fn convex(points: &[Vec2]) -> Option<Polygon> {
        let n = points.len();
        if !(3..=MAX_POLYGON_VERTICES).contains(&n) {
            return None;
        }
        let mut vertices = [Vec2::ZERO; MAX_POLYGON_VERTICES];
        let mut normals = [Vec2::ZERO; MAX_POLYGON_VERTICES];
        for i in 0..n {
            vertices[i] = points[i];
            let e = points[(i + 1) % n] - points[i];
            if e.length() < 1e-12 {
                return None;
            }
            normals[i] = Vec2::new(e.y, -e.x).normalize_or_zero();
            let next = points[(i + 2) % n] - points[(i + 1) % n];
            if e.cross(next) <= 0.0 {
                return None;
            }
        }
        Some(Polygon {
            count: n,
            vertices,
            normals,
            radius: 0.0,
        })
    }

    /// A circle of `radius` around `center` (`None` unless the radius is finite and > 0).
    pub fn circle(center: Vec2, radius: f64) -> Option<Polygon> {
        if !(radius.is_finite() && radius > 0.0 && center.is_finite()) {
            return None;
        }
        let mut vertices = [Vec2::ZERO; MAX_POLYGON_VERTICES];
        vertices[0] = center;
        Some(Polygon {
            count: 1,
            vertices,
            normals: [Vec2::ZERO; MAX_POLYGON_VERTICES],
            radius,
        })
    }

    /// True for a circle made by [`Polygon::circle`].
    #[inline]
    pub fn is_circle(&self) -> bool {
        self.count == 1
    }

    /// The used vertices.
    #[inline]
    pub fn verts(&self) -> &[Vec2] {
        &self.vertices[..self.count]
    }

    /// Area, centroid and second moment of area about the centroid (for unit density).
    pub fn mass_properties(&self) -> (f64, Vec2, f64) {
        if self.is_circle() {
            let area = std::f64::consts::PI * self.radius * self.radius;
            return (area, self.vertices[0], 0.5 * area * self.radius * self.radius);
        }
        let v = self.verts();
        let origin = v[0];
        let mut area = 0.0;
        let mut centroid = Vec2::ZERO;
        let mut inertia = 0.0;
        for i in 1..v.len() - 1 {
            let e1 = v[i] - origin;
            let e2 = v[i + 1] - origin;
            let d = e1.cross(e2);
            let tri_area = 0.5 * d;
            area += tri_area;
            centroid += (e1 + e2) * (tri_area / 3.0);
            let intx2 = e1.x * e1.x + e2.x * e1.x + e2.x * e2.x;
            let inty2 = e1.y * e1.y + e2.y * e1.y + e2.y * e2.y;
            inertia += (0.25 / 3.0) * d * (intx2 + inty2);
        }
        let c = centroid / area;
        // inertia is about `origin`; move it to the centroid
        let i_centroid = inertia - area * c.length_squared();
        (area, origin + c, i_centroid)
    }

    /// The polygon moved by a rotation and a translation.
    pub fn transformed(&self, rot: Rot, pos: Vec2) -> Polygon {
        let mut out = *self;
        out.set_transformed(self, rot, pos);
        out
    }

    /// Makes this polygon `src` moved by a rotation and a translation, writing only the used
    /// vertices and normals (the unused ones keep whatever they held).
    #[inline]
    pub(crate) fn set_transformed(&mut self, src: &Polygon, rot: Rot, pos: Vec2) {
        let n = src.count.min(MAX_POLYGON_VERTICES);
        self.count = n;
        self.radius = src.radius;
        for (v, s) in self.vertices[..n].iter_mut().zip(&src.vertices[..n]) {
            *v = rot.apply(*s) + pos;
        }
        for (v, s) in self.normals[..n].iter_mut().zip(&src.normals[..n]) {
            *v = rot.apply(*s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn square_mass_properties_match_formula() {
        let p = Polygon::square(Vec2::new(1.0, 2.0), 1.2);
        let (a, c, i) = p.mass_properties();
        assert!((a - 1.44).abs() < 1e-12);
        assert!((c - Vec2::new(1.0, 2.0)).length() < 1e-12);
        // I = A (w² + h²) / 12 for unit density
        assert!((i - 1.44 * (1.44 + 1.44) / 12.0).abs() < 1e-12);
    }

    #[test]
    fn circle_mass_properties_match_formula() {
        let c = Polygon::circle(Vec2::new(1.0, -2.0), 2.0).unwrap();
        let (a, centre, i) = c.mass_properties();
        let area = std::f64::consts::PI * 4.0;
        assert!((a - area).abs() < 1e-12);
        assert_eq!(centre, Vec2::new(1.0, -2.0));
        assert!((i - area * 2.0).abs() < 1e-12, "I = m r²/2 per unit density");
        assert!(Polygon::circle(Vec2::ZERO, 0.0).is_none());
        assert!(Polygon::circle(Vec2::ZERO, f64::NAN).is_none());
    }

    #[test]
    fn clockwise_or_degenerate_polygons_are_rejected() {
        let cw = [Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0), Vec2::new(1.0, 0.0)];
        assert!(Polygon::convex(&cw).is_none());
        let line = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(2.0, 0.0)];
        assert!(Polygon::convex(&line).is_none());
    }
}
