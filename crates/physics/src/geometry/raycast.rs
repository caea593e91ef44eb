//! Ray casts against polygons.

use super::shape::Polygon;
use crate::math::Vec2;

/// Distance along the unit direction `dir` from `origin` to the first edge of `poly` hit within
/// `max_distance`, if any. A ray starting inside the polygon hits its far edge.
pub fn ray_cast_polygon(poly: &Polygon, origin: Vec2, dir: Vec2, max_distance: f64) -> Option<f64> {
    let mut best: Option<f64> = None;
    let v = poly.verts();
    for i in 0..v.len() {
        let a = v[i];
        let b = v[(i + 1) % v.len()];
        let e = b - a;
        let denom = dir.cross(e);
        if denom.abs() < 1e-14 {
            continue;
        }
        let ao = a - origin;
        let t = ao.cross(e) / denom;
        let u = ao.cross(dir) / denom;
        if (0.0..=max_distance).contains(&t) && (0.0..=1.0).contains(&u) && best.is_none_or(|bt| t < bt) {
            best = Some(t);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_down_hits_ground_top() {
        let ground = Polygon::rect(Vec2::new(0.0, -1.0), 10.0, 1.0);
        let d = ray_cast_polygon(&ground, Vec2::new(0.0, 3.0), Vec2::new(0.0, -1.0), 10.0);
        assert!((d.unwrap() - 3.0).abs() < 1e-12);
        assert!(ray_cast_polygon(&ground, Vec2::new(0.0, 3.0), Vec2::new(0.0, 1.0), 10.0).is_none());
        assert!(ray_cast_polygon(&ground, Vec2::new(0.0, 3.0), Vec2::new(0.0, -1.0), 2.0).is_none());
    }
}
