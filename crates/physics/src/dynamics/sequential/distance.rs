//! Distance between two separated convex polygons, by dyn4j's GJK distance iteration, with the
//! behaviour of each dyn4j version kept where they differ.
//!
//! The iteration keeps a segment (a, b) of the Minkowski difference A − B and moves it towards
//! the origin: the support point c in the direction of the origin replaces a or b, whichever
//! leaves the segment closer. It stops when c brings the segment no closer than a did
//! (`TOLERANCE`), when one of the two candidate segments touches the origin, or after
//! `MAX_ITERATIONS`.
//!
//! **dyn4j 3.3.0's quirk, kept for that version**: it compares c only with a, so when the closest
//! point of the difference is the vertex b, c keeps being b and the iteration runs to its limit;
//! it then reports the distance with the wrong sign (−|d|) and the normal pointing from B to A.
//! dyn4j 4.x takes distance and normal from the closest points instead, always ≥ 0. The continuous
//! collision pass of 3.3.0 treats the negative distance as an impact at time 0 (docs/physics.md).

use crate::dynamics::settings::Dyn4jVersion;
use crate::math::Vec2;

/// Most iterations of the distance loop (dyn4j's default).
const MAX_ITERATIONS: usize = 30;
/// dyn4j's epsilon: machine epsilon.
const EPSILON: f64 = f64::EPSILON;

/// The distance between two shapes, the closest points on each, and the unit normal from the
/// first towards the second.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Separation {
    pub distance: f64,
    pub normal: Vec2,
    pub point1: Vec2,
    pub point2: Vec2,
}

/// A point of the Minkowski difference and the two support points it came from.
#[derive(Debug, Clone, Copy)]
struct Support {
    point: Vec2,
    on1: Vec2,
    on2: Vec2,
}

/// The first vertex of `vertices` farthest along `d`.
fn farthest(vertices: &[Vec2], d: Vec2) -> Vec2 {
    let mut best = vertices[0];
    let mut max = d.dot(best);
    for &v in &vertices[1..] {
        let p = d.dot(v);
        if p > max {
            max = p;
            best = v;
        }
    }
    best
}

fn support(shape1: &[Vec2], shape2: &[Vec2], d: Vec2) -> Support {
    let on1 = farthest(shape1, d);
    let on2 = farthest(shape2, -d);
    Support {
        point: on1 - on2,
        on1,
        on2,
    }
}

/// The point of segment p1–p2 closest to the origin (p1 when the segment is degenerate).
fn closest_to_origin(p1: Vec2, p2: Vec2) -> Vec2 {
    let line = p2 - p1;
    let ab2 = line.dot(line);
    let ap_ab = (-p1).dot(line);
    if ab2 <= EPSILON {
        return p1;
    }
    let t = (ap_ab / ab2).clamp(0.0, 1.0);
    line * t + p1
}

/// Whether triangle a, b, c holds the origin strictly inside.
fn contains_origin(a: Vec2, b: Vec2, c: Vec2) -> bool {
    let sa = a.cross(b);
    let sb = b.cross(c);
    let sc = c.cross(a);
    sa * sb > 0.0 && sa * sc > 0.0
}

/// `v` scaled to unit length, and its length before (0 and `v` unchanged when about zero).
fn normalized(v: Vec2) -> (Vec2, f64) {
    let length = (v.x * v.x + v.y * v.y).sqrt();
    if length <= EPSILON {
        return (v, 0.0);
    }
    let m = 1.0 / length;
    (Vec2::new(v.x * m, v.y * m), length)
}

fn is_zero(v: Vec2) -> bool {
    v.x.abs() <= EPSILON && v.y.abs() <= EPSILON
}

/// The closest points of the two shapes, from the difference's segment a–b.
fn closest_points(a: &Support, b: &Support, version: Dyn4jVersion) -> (Vec2, Vec2) {
    let l = b.point - a.point;
    if is_zero(l) {
        return (a.on1, a.on2);
    }
    let l2 = -l.dot(a.point) / l.dot(l);
    match version {
        Dyn4jVersion::V3_3_0 => {
            let l1 = 1.0 - l2;
            if l1 < 0.0 {
                (b.on1, b.on2)
            } else if l2 < 0.0 {
                (a.on1, a.on2)
            } else {
                (
                    Vec2::new(a.on1.x * l1 + b.on1.x * l2, a.on1.y * l1 + b.on1.y * l2),
                    Vec2::new(a.on2.x * l1 + b.on2.x * l2, a.on2.y * l1 + b.on2.y * l2),
                )
            }
        }
        Dyn4jVersion::V4_2_1 => {
            if l2 > 1.0 {
                (b.on1, b.on2)
            } else if l2 < 0.0 {
                (a.on1, a.on2)
            } else {
                (a.on1 + (b.on1 - a.on1) * l2, a.on2 + (b.on2 - a.on2) * l2)
            }
        }
    }
}

/// The result the version reports for segment a–b: 3.3.0 distance −c·d̂ along the direction `d`
/// (which is the right sign only when `d` points at the origin); 4.x from the closest points.
fn separation(a: &Support, b: &Support, c: &Support, d: Vec2, version: Dyn4jVersion) -> Separation {
    let (point1, point2) = closest_points(a, b, version);
    match version {
        Dyn4jVersion::V3_3_0 => {
            let (normal, _) = normalized(d);
            Separation {
                distance: -c.point.dot(normal),
                normal,
                point1,
                point2,
            }
        }
        Dyn4jVersion::V4_2_1 => between(point1, point2),
    }
}

/// 4.x's result: the distance and direction from `point1` to `point2`.
fn between(point1: Vec2, point2: Vec2) -> Separation {
    let (normal, distance) = normalized(point2 - point1);
    Separation {
        distance,
        normal,
        point1,
        point2,
    }
}

/// The separation of two convex polygons given by their world vertices and centres (`None`
/// when they overlap or their centres coincide).
pub(crate) fn distance(
    shape1: &[Vec2],
    centre1: Vec2,
    shape2: &[Vec2],
    centre2: Vec2,
    version: Dyn4jVersion,
) -> Option<Separation> {
    iterate::<true>(shape1, centre1, shape2, centre2, version)
}

/// Whether an iteration left the segment and the direction exactly (bit for bit) as they were:
/// the loop is then at a fixed point, and running it to `MAX_ITERATIONS` changes nothing.
fn unchanged(before: (Support, Support, Vec2), after: (Support, Support, Vec2)) -> bool {
    let bits = |v: Vec2| (v.x.to_bits(), v.y.to_bits());
    let same = |p: Support, q: Support| {
        bits(p.point) == bits(q.point) && bits(p.on1) == bits(q.on1) && bits(p.on2) == bits(q.on2)
    };
    same(before.0, after.0) && same(before.1, after.1) && bits(before.2) == bits(after.2)
}

/// The distance iteration; `STOP_AT_FIXED_POINT` leaves the loop as soon as an iteration
/// changes nothing (same result, fewer iterations: the tests compare both).
fn iterate<const STOP_AT_FIXED_POINT: bool>(
    shape1: &[Vec2],
    centre1: Vec2,
    shape2: &[Vec2],
    centre2: Vec2,
    version: Dyn4jVersion,
) -> Option<Separation> {
    let tolerance = EPSILON.sqrt();
    let mut d = centre2 - centre1;
    if is_zero(d) {
        return None;
    }
    let mut a = support(shape1, shape2, d);
    d = -d;
    let mut b = support(shape1, shape2, d);
    d = closest_to_origin(b.point, a.point);
    let mut c = a;
    for _ in 0..MAX_ITERATIONS {
        let before = (a, b, d);
        d = -d;
        if d.length_squared() <= EPSILON {
            return None;
        }
        c = support(shape1, shape2, d);
        if contains_origin(a.point, b.point, c.point) {
            return None;
        }
        if c.point.dot(d) - a.point.dot(d) < tolerance {
            return Some(separation(&a, &b, &c, d, version));
        }
        let p1 = closest_to_origin(a.point, c.point);
        let p2 = closest_to_origin(c.point, b.point);
        let (m1, m2) = (p1.length_squared(), p2.length_squared());
        if m1 <= EPSILON {
            return Some(touching(&a, &c, d, p1, version));
        } else if m2 <= EPSILON {
            return Some(touching(&c, &b, d, p2, version));
        }
        if m1 < m2 {
            b = c;
            d = p1;
        } else {
            a = c;
            d = p2;
        }
        if STOP_AT_FIXED_POINT && unchanged(before, (a, b, d)) {
            // every further iteration would repeat this one to the limit (3.3.0's quirk)
            break;
        }
    }
    // out of iterations: `d` now points from the origin towards the difference (see the module)
    Some(separation(&a, &b, &c, d, version))
}

/// The result when segment a–b passes (almost) through the origin at `p`.
fn touching(a: &Support, b: &Support, d: Vec2, p: Vec2, version: Dyn4jVersion) -> Separation {
    let (point1, point2) = closest_points(a, b, version);
    match version {
        Dyn4jVersion::V3_3_0 => Separation {
            distance: normalized(p).1,
            normal: normalized(d).0,
            point1,
            point2,
        },
        Dyn4jVersion::V4_2_1 => between(point1, point2),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(cx: f64, cy: f64, h: f64) -> [Vec2; 4] {
        [
            Vec2::new(cx - h, cy - h),
            Vec2::new(cx + h, cy - h),
            Vec2::new(cx + h, cy + h),
            Vec2::new(cx - h, cy + h),
        ]
    }

    #[test]
    fn separated_squares_are_as_far_apart_as_their_facing_sides() {
        let (a, b) = (square(0.0, 0.0, 0.5), square(3.0, 0.2, 0.5));
        for version in [Dyn4jVersion::V3_3_0, Dyn4jVersion::V4_2_1] {
            let s = distance(&a, Vec2::new(0.0, 0.0), &b, Vec2::new(3.0, 0.2), version).unwrap();
            assert!((s.distance - 2.0).abs() < 1e-9, "{version:?}: {s:?}");
            assert!((s.normal - Vec2::new(1.0, 0.0)).length() < 1e-9, "{version:?}: {s:?}");
            assert!((s.point2.x - s.point1.x - 2.0).abs() < 1e-9);
        }
    }

    #[test]
    fn overlapping_squares_have_no_separation() {
        let (a, b) = (square(0.0, 0.0, 0.5), square(0.7, 0.2, 0.5));
        for version in [Dyn4jVersion::V3_3_0, Dyn4jVersion::V4_2_1] {
            assert!(distance(&a, Vec2::ZERO, &b, Vec2::new(0.7, 0.2), version).is_none());
        }
    }

    /// The flat terrain's left border quad (0,100)–(0,−45)–(10,−45)–(10,5) and its centre.
    fn left_border() -> ([Vec2; 4], Vec2) {
        let quad = [
            Vec2::new(0.0, 100.0),
            Vec2::new(0.0, -45.0),
            Vec2::new(10.0, -45.0),
            Vec2::new(10.0, 5.0),
        ];
        (quad, Vec2::new(4.188034188034188, 7.6068376068376065))
    }

    /// A square turned by −0.45 rad, right of and above the corner (10, 5) of the flat terrain's
    /// left border quad (0,100)–(0,−45)–(10,−45)–(10,5): the closest points are that corner and
    /// the square's lower-left corner. dyn4j 3.3.0 reports this distance negated (its quirk; one
    /// pose in 45 of a grid of squares near the wall, 12 ≤ x < 22, 5 ≤ y < 7.5, |angle| ≤ 0.5,
    /// does so); 4.2.1 does not.
    #[test]
    fn dyn4j_3_3_0_negates_the_distance_to_a_vertex_it_cannot_converge_on() {
        let (wall, wall_centre) = left_border();
        let centre = Vec2::new(12.0, 5.35);
        let r = crate::math::Rot::new(-0.45);
        let sq = square(0.0, 0.0, 0.6).map(|v| centre + r.apply(v));
        let true_distance = (sq[0] - Vec2::new(10.0, 5.0)).length();
        let new = distance(&sq, centre, &wall, wall_centre, Dyn4jVersion::V4_2_1).unwrap();
        assert!((new.distance - true_distance).abs() < 1e-9, "{new:?}");
        assert!(new.normal.x < -0.99, "{new:?}");
        let old = distance(&sq, centre, &wall, wall_centre, Dyn4jVersion::V3_3_0).unwrap();
        assert!((old.distance + true_distance).abs() < 1e-9, "{old:?}");
        assert!(old.normal.x > 0.99, "{old:?}");
    }

    /// Leaving the loop at its fixed point gives the result, bit for bit, of running it to the
    /// limit: 2,000 squares of random size and pose near the flat terrain's border corner, both
    /// versions. The poses 3.3.0 reports at a negative distance are those where its loop runs to
    /// the limit (the fixed point); the test requires some.
    #[test]
    fn stopping_at_the_fixed_point_changes_no_bit() {
        let (wall, wall_centre) = left_border();
        let bits = |s: Option<Separation>| {
            s.map(|s| {
                [
                    s.distance, s.normal.x, s.normal.y, s.point1.x, s.point1.y, s.point2.x, s.point2.y,
                ]
                .map(f64::to_bits)
            })
        };
        let mut fixed_points = 0;
        for i in 0..2000u32 {
            let f = |k: u32| ((i.wrapping_mul(2654435761).wrapping_add(k * 40503)) % 10007) as f64 / 10007.0;
            let centre = Vec2::new(10.0 + 12.0 * f(1), 4.0 + 4.0 * f(2));
            let r = crate::math::Rot::new(f(3) - 0.5);
            let sq = square(0.0, 0.0, 0.3 + 0.4 * f(4)).map(|v| centre + r.apply(v));
            for version in [Dyn4jVersion::V3_3_0, Dyn4jVersion::V4_2_1] {
                let fast = iterate::<true>(&sq, centre, &wall, wall_centre, version);
                let full = iterate::<false>(&sq, centre, &wall, wall_centre, version);
                assert_eq!(bits(fast), bits(full), "pose {i}, {version:?}");
                if version == Dyn4jVersion::V3_3_0 && fast.is_some_and(|s| s.distance < 0.0) {
                    fixed_points += 1;
                }
            }
        }
        // the quirk's poses (negative distances) are the ones that reach the fixed point
        assert!(fixed_points > 10, "only {fixed_points} poses ran to the limit");
    }
}
