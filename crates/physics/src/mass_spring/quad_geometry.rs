//! Pure geometry on points given as coordinates: the tests EvoGym's contact model is built from.

/// An axis-aligned box `[min_x, max_x] × [min_y, max_y]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aabb {
    pub min_x: f64,
    pub min_y: f64,
    pub max_x: f64,
    pub max_y: f64,
}

impl Aabb {
    /// A box that contains nothing: the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min_x: f64::INFINITY,
        min_y: f64::INFINITY,
        max_x: f64::NEG_INFINITY,
        max_y: f64::NEG_INFINITY,
    };

    /// The box around four points.
    pub fn of_quad(xs: [f64; 4], ys: [f64; 4]) -> Aabb {
        Aabb {
            min_x: xs[0].min(xs[1]).min(xs[2]).min(xs[3]),
            min_y: ys[0].min(ys[1]).min(ys[2]).min(ys[3]),
            max_x: xs[0].max(xs[1]).max(xs[2]).max(xs[3]),
            max_y: ys[0].max(ys[1]).max(ys[2]).max(ys[3]),
        }
    }

    /// The smallest box containing both.
    pub fn union(self, o: Aabb) -> Aabb {
        Aabb {
            min_x: self.min_x.min(o.min_x),
            min_y: self.min_y.min(o.min_y),
            max_x: self.max_x.max(o.max_x),
            max_y: self.max_y.max(o.max_y),
        }
    }

    /// Closed overlap test: boxes that only touch overlap.
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min_x <= o.max_x && o.min_x <= self.max_x && self.min_y <= o.max_y && o.min_y <= self.max_y
    }

    /// Whether the point lies in the box, boundary included.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        self.min_x <= x && x <= self.max_x && self.min_y <= y && y <= self.max_y
    }

    /// Overlap test with every side moved out by `tol`.
    pub fn overlaps_within(&self, o: &Aabb, tol: f64) -> bool {
        self.min_x <= o.max_x + tol
            && o.min_x <= self.max_x + tol
            && self.min_y <= o.max_y + tol
            && o.min_y <= self.max_y + tol
    }
}

/// Length of the vector (dx, dy) as the square root of its squared norm, as EvoGym (Eigen's
/// `norm`) computes it; unlike `f64::hypot` it may overflow for lengths near 1e154, which no
/// world reaches without first failing the non-finite check.
#[inline]
pub(crate) fn norm(dx: f64, dy: f64) -> f64 {
    (dx * dx + dy * dy).sqrt()
}

fn cross(ax: f64, ay: f64, bx: f64, by: f64) -> f64 {
    ax * by - ay * bx
}

/// Whether `(px, py)` lies in the quad (corners in cyclic order, either orientation), boundary
/// included. The quad is split along the diagonal corner 0 – corner 2 into two triangles and the
/// point is tested against each with cross-product signs, as EvoGym does.
pub(crate) fn point_in_quad(px: f64, py: f64, xs: [f64; 4], ys: [f64; 4]) -> bool {
    let (dx, dy) = (xs.map(|x| x - px), ys.map(|y| y - py));
    let c02 = cross(dx[2], dy[2], dx[0], dy[0]);
    let first = cross(dx[0], dy[0], dx[1], dy[1]);
    let second = cross(dx[1], dy[1], dx[2], dy[2]);
    if c02 * first >= 0.0 && c02 * second >= 0.0 {
        return true;
    }
    let third = cross(dx[0], dy[0], dx[3], dy[3]);
    let fourth = cross(dx[3], dy[3], dx[2], dy[2]);
    c02 * third >= 0.0 && c02 * fourth >= 0.0
}

/// Below this |cross product| of the two direction vectors, segments count as parallel and
/// never intersect (EvoGym's absolute threshold).
pub(crate) const PARALLEL_EPS: f64 = 1e-4;

/// Whether segment p0–p1 meets segment q0–q1, endpoints included; near-parallel pairs never do.
pub(crate) fn segments_intersect(p0: (f64, f64), p1: (f64, f64), q0: (f64, f64), q1: (f64, f64)) -> bool {
    let (d1x, d1y) = (p1.0 - p0.0, p1.1 - p0.1);
    let (d2x, d2y) = (q1.0 - q0.0, q1.1 - q0.1);
    let det = cross(d2x, d2y, d1x, d1y);
    if det.abs() < PARALLEL_EPS {
        return false;
    }
    let (ox, oy) = (q0.0 - p0.0, q0.1 - p0.1);
    let t = cross(d2x, d2y, ox, oy) / det;
    let s = cross(d1x, d1y, ox, oy) / det;
    (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&s)
}

/// Distance returned for a side shorter than [`MIN_SIDE`]: never the closest.
pub(crate) const FAR: f64 = 1000.0;
/// Sides shorter than this have no direction.
pub(crate) const MIN_SIDE: f64 = 1e-6;

/// Distance from a point to the infinite line through a–b ([`FAR`] for a degenerate side).
pub(crate) fn line_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (bx, by) = (b.0 - a.0, b.1 - a.1);
    let len = norm(bx, by);
    if len < MIN_SIDE {
        return FAR;
    }
    cross(bx, by, p.0 - a.0, p.1 - a.1).abs() / len
}

/// Twice the signed area of a quad (positive when its corners run counter-clockwise).
pub(crate) fn twice_signed_area(xs: [f64; 4], ys: [f64; 4]) -> f64 {
    (0..4)
        .map(|i| cross(xs[i], ys[i], xs[(i + 1) % 4], ys[(i + 1) % 4]))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    const UX: [f64; 4] = [0.0, 1.0, 1.0, 0.0];
    const UY: [f64; 4] = [0.0, 0.0, 1.0, 1.0];

    #[test]
    fn point_in_quad_inside_outside_and_on_the_boundary() {
        assert!(point_in_quad(0.5, 0.5, UX, UY));
        assert!(point_in_quad(0.9, 0.1, UX, UY), "triangle 0-1-2");
        assert!(point_in_quad(0.1, 0.9, UX, UY), "triangle 2-3-0");
        assert!(point_in_quad(1.0, 0.5, UX, UY), "boundary counts");
        assert!(!point_in_quad(1.01, 0.5, UX, UY));
        assert!(!point_in_quad(0.5, -0.01, UX, UY));
        // Clockwise order gives the same answers.
        let (cx, cy) = ([0.0, 0.0, 1.0, 1.0], [0.0, 1.0, 1.0, 0.0]);
        assert!(point_in_quad(0.3, 0.6, cx, cy));
        assert!(!point_in_quad(-0.3, 0.6, cx, cy));
    }

    #[test]
    fn point_in_a_concave_quad_uses_the_0_2_diagonal() {
        // Dart with its reflex corner at 3: (0.5, 0.2) lies outside the dart but inside the hull.
        let (xs, ys) = ([0.0, 1.0, 0.5, 0.5], [0.0, 0.0, 1.0, 0.3]);
        assert!(point_in_quad(0.6, 0.1, xs, ys));
        assert!(!point_in_quad(0.1, 0.5, xs, ys));
    }

    #[test]
    fn segments_cross_touch_and_miss() {
        assert!(segments_intersect((0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)));
        assert!(
            segments_intersect((0.0, 0.0), (1.0, 0.0), (1.0, -1.0), (1.0, 1.0)),
            "endpoint touch"
        );
        assert!(!segments_intersect((0.0, 0.0), (1.0, 0.0), (1.1, -1.0), (1.1, 1.0)));
        assert!(
            !segments_intersect((0.0, 0.0), (1.0, 0.0), (0.0, 0.0), (2.0, 0.0)),
            "parallel"
        );
    }

    #[test]
    fn line_distance_is_perpendicular_and_ignores_the_segment_ends() {
        assert!((line_distance((5.0, 2.0), (0.0, 0.0), (1.0, 0.0)) - 2.0).abs() < 1e-15);
        assert!((line_distance((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)) - 0.5f64.sqrt()).abs() < 1e-15);
        assert_eq!(line_distance((0.0, 0.0), (1.0, 1.0), (1.0, 1.0)), FAR);
    }

    #[test]
    fn boxes_overlap_when_touching() {
        let a = Aabb::of_quad(UX, UY);
        let b = Aabb::of_quad(UX.map(|x| x + 1.0), UY);
        let c = Aabb::of_quad(UX.map(|x| x + 1.001), UY);
        assert!(a.overlaps(&b));
        assert!(!a.overlaps(&c));
        assert!(a.overlaps_within(&c, 0.01));
        assert_eq!(Aabb::EMPTY.union(a), a);
        assert!(a.contains(1.0, 0.5) && !a.contains(1.001, 0.5) && !Aabb::EMPTY.contains(0.0, 0.0));
        assert_eq!(twice_signed_area(UX, UY), 2.0);
    }
}
