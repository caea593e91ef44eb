//! Contact manifolds between two convex polygons (separating axis test plus edge clipping).

use super::shape::Polygon;
use crate::math::Vec2;

/// One contact point of a manifold, in world coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ManifoldPoint {
    /// World point midway between the two surfaces.
    pub point: Vec2,
    /// Signed distance along the normal (negative when overlapping).
    pub separation: f64,
    /// Which features made the point (reference edge, incident edge, incident vertex, which shape
    /// was the reference), so that a point can be recognised in the next step; 0 for circles.
    /// [`collide_polygons_dyn4j`] numbers the edges as dyn4j does.
    pub id: u32,
}

impl ManifoldPoint {
    /// Whether the second shape's edge was the reference edge (the first shape's vertex clipped).
    pub fn flipped(&self) -> bool {
        self.id & FLIPPED != 0
    }
}

/// Bit of [`ManifoldPoint::id`] set when the second shape holds the reference edge.
const FLIPPED: u32 = 1 << 24;

/// The id of a clipped point: edges and vertex in the low bytes, offset by one so that 0 stays free.
fn point_id(ref_edge: usize, inc_edge: usize, vertex: usize, flip: bool) -> u32 {
    1 + ref_edge as u32 + ((inc_edge as u32) << 8) + ((vertex as u32) << 16) + if flip { FLIPPED } else { 0 }
}

/// Up to two contact points sharing one normal, which points from the first shape to the second.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Manifold {
    /// Unit normal from shape A towards shape B.
    pub normal: Vec2,
    /// Contact points; only the first `count` are valid.
    pub points: [ManifoldPoint; 2],
    /// Number of valid points (0, 1 or 2).
    pub count: usize,
}

/// Largest separation of `b` from the edges of `a`: (separation, edge index of `a`).
fn max_separation(a: &Polygon, b: &Polygon) -> (f64, usize) {
    let mut best = f64::NEG_INFINITY;
    let mut best_edge = 0;
    for i in 0..a.count {
        let n = a.normals[i];
        let va = a.vertices[i];
        let mut min_d = f64::INFINITY;
        for vb in b.verts() {
            let d = n.dot(*vb - va);
            if d < min_d {
                min_d = d;
            }
        }
        if min_d > best {
            best = min_d;
            best_edge = i;
        }
    }
    (best, best_edge)
}

/// How much better B's separating axis must be for B to give the reference edge in
/// [`collide_polygons`] (avoids flip-flopping between near-equal axes).
const PREFER_FIRST_SHAPE: f64 = 0.1 * 0.005;

/// Computes the contact manifold of two world-space polygons, keeping points closer than `margin`.
pub fn collide_polygons(a: &Polygon, b: &Polygon, margin: f64) -> Manifold {
    collide_convex(a, b, margin, PREFER_FIRST_SHAPE, false)
}

/// The manifold as dyn4j makes it: the reference edge on the axis of least penetration (its EPA
/// normal), with no preference for either shape, and the incident edge clipped as dyn4j clips it,
/// which lists the end points kept before a point where the edge was cut (that order decides the
/// order in which the solver visits the points).
pub fn collide_polygons_dyn4j(a: &Polygon, b: &Polygon, margin: f64) -> Manifold {
    collide_convex(a, b, margin, 0.0, true)
}

fn collide_convex(a: &Polygon, b: &Polygon, margin: f64, prefer_first: f64, dyn4j_clipping: bool) -> Manifold {
    if a.is_circle() || b.is_circle() {
        return collide_with_circle(a, b, margin);
    }
    let mut out = Manifold::default();
    let (sep_a, edge_a) = max_separation(a, b);
    if sep_a > margin {
        return out;
    }
    let (sep_b, edge_b) = max_separation(b, a);
    if sep_b > margin {
        return out;
    }
    let (reference, incident, ref_edge, flip) = if sep_b > sep_a + prefer_first {
        (b, a, edge_b, true)
    } else {
        (a, b, edge_a, false)
    };
    let n_ref = reference.normals[ref_edge];
    // incident edge: the one whose normal is most anti-parallel to the reference normal
    let mut inc_edge = 0;
    let mut min_dot = f64::INFINITY;
    for i in 0..incident.count {
        let d = n_ref.dot(incident.normals[i]);
        if d < min_dot {
            min_dot = d;
            inc_edge = i;
        }
    }
    let i1 = incident.vertices[inc_edge];
    let i2 = incident.vertices[(inc_edge + 1) % incident.count];
    let r1 = reference.vertices[ref_edge];
    let r2 = reference.vertices[(ref_edge + 1) % reference.count];
    let normal = if flip { -n_ref } else { n_ref };
    if dyn4j_clipping {
        let ends = [(i1, inc_edge), (i2, (inc_edge + 1) % incident.count)];
        let Some(points) = clip_as_dyn4j(ends, r1, r2) else {
            return out;
        };
        let (ref_index, inc_index) = (
            dyn4j_edge_index(reference, ref_edge, reference_tilts_to_last(reference)),
            dyn4j_edge_index(incident, inc_edge, farther_last(incident, -n_ref)),
        );
        for (p, vertex) in points {
            let separation = n_ref.dot(p - r1);
            if separation <= margin {
                let point = p - n_ref * (0.5 * separation);
                let id = point_id(ref_index, inc_index, vertex, flip);
                out.points[out.count] = ManifoldPoint { point, separation, id };
                out.count += 1;
            }
        }
        out.normal = normal;
        return out;
    }
    let tangent = (r2 - r1).normalize_or_zero();
    // clip the incident segment to the slab [r1, r2] along the tangent
    let lower = tangent.dot(r1);
    let upper = tangent.dot(r2);
    let (mut p1, mut p2) = (i1, i2);
    let (d1, d2) = (tangent.dot(p1), tangent.dot(p2));
    if !clip_segment(&mut p1, &mut p2, d1, d2, lower, upper) {
        return out;
    }
    for (k, p) in [p1, p2].into_iter().enumerate() {
        let separation = n_ref.dot(p - r1);
        if separation <= margin {
            let point = p - n_ref * (0.5 * separation);
            let vertex = (inc_edge + k) % incident.count;
            let id = point_id(ref_edge, inc_edge, vertex, flip);
            out.points[out.count] = ManifoldPoint { point, separation, id };
            out.count += 1;
        }
    }
    out.normal = normal;
    out
}

/// dyn4j's index of edge `e` (from vertex e to e+1): e+1, except for the closing edge (last vertex
/// to vertex 0), which dyn4j numbers `count` when it reached the edge from its last vertex (the one
/// farther along the contact normal) and 0 when from vertex 0. A contact point whose number changes
/// from one step to the next is not warm started.
fn dyn4j_edge_index(poly: &Polygon, e: usize, last_is_farther: bool) -> usize {
    if e + 1 < poly.count {
        e + 1
    } else if last_is_farther {
        poly.count
    } else {
        0
    }
}

/// Whether the polygon's last vertex lies farther along `dir` than vertex 0.
fn farther_last(poly: &Polygon, dir: Vec2) -> bool {
    dir.dot(poly.vertices[poly.count - 1]) > dir.dot(poly.vertices[0])
}

/// Whether dyn4j reaches the reference shape's closing edge from its last vertex. That edge is
/// perpendicular to the contact normal, so its ends lie equally far along it but for rounding:
/// dyn4j's normal comes out of the shapes' world coordinates, and which end wins changes at random
/// from step to step (in the original, half of the steps renumber such a point). The rounding of
/// our world coordinates decides it here: the edge as rounded, against its exact normal. An
/// exactly aligned edge gives vertex 0, as in dyn4j.
fn reference_tilts_to_last(poly: &Polygon) -> bool {
    let last = poly.count - 1;
    (poly.vertices[0] - poly.vertices[last]).dot(poly.normals[last]) > 0.0
}

/// One contact point between a circle and a polygon or another circle (B or A is the circle);
/// the normal points from A to B as for polygons.
fn collide_with_circle(a: &Polygon, b: &Polygon, margin: f64) -> Manifold {
    let mut out = Manifold::default();
    let (normal, separation, point_on_a) = match (a.is_circle(), b.is_circle()) {
        (true, true) => {
            let (ca, cb) = (a.vertices[0], b.vertices[0]);
            let d = cb - ca;
            let dist = d.length();
            let n = if dist > 1e-12 { d / dist } else { Vec2::new(0.0, 1.0) };
            (n, dist - a.radius - b.radius, ca + n * a.radius)
        }
        (false, true) => polygon_circle(a, b.vertices[0], b.radius),
        (true, false) => {
            let (n, sep, on_b) = polygon_circle(b, a.vertices[0], a.radius);
            (-n, sep, on_b + n * sep)
        }
        (false, false) => unreachable!("called only with a circle"),
    };
    if separation > margin {
        return out;
    }
    out.normal = normal;
    out.points[0] = ManifoldPoint {
        point: point_on_a + normal * (0.5 * separation),
        separation,
        id: 0,
    };
    out.count = 1;
    out
}

/// Normal from the polygon towards the circle's centre, the separation, and the closest point of
/// the polygon's surface (the centre's projection when the centre is inside).
fn polygon_circle(poly: &Polygon, centre: Vec2, radius: f64) -> (Vec2, f64, Vec2) {
    let mut best = f64::NEG_INFINITY;
    let mut edge = 0;
    for i in 0..poly.count {
        let s = poly.normals[i].dot(centre - poly.vertices[i]);
        if s > best {
            best = s;
            edge = i;
        }
    }
    let v1 = poly.vertices[edge];
    let v2 = poly.vertices[(edge + 1) % poly.count];
    let face = |n: Vec2| (n, best - radius, centre - n * best);
    if best <= 0.0 {
        return face(poly.normals[edge]);
    }
    for (v, w) in [(v1, v2), (v2, v1)] {
        if (centre - v).dot(w - v) <= 0.0 {
            let d = centre - v;
            let dist = d.length();
            let n = if dist > 1e-12 { d / dist } else { poly.normals[edge] };
            return (n, dist - radius, v);
        }
    }
    face(poly.normals[edge])
}

/// The incident edge's ends (point, vertex index) clipped to the slab of the reference edge r1–r2,
/// first at r1's side, then at r2's, each time listing the ends kept (in order) before the point
/// where the edge was cut, which takes the index of the end cut off; `None` when fewer than two
/// points remain.
fn clip_as_dyn4j(ends: [(Vec2, usize); 2], r1: Vec2, r2: Vec2) -> Option<[(Vec2, usize); 2]> {
    let edge = r2 - r1;
    let length = edge.length();
    if length <= f64::EPSILON {
        return None;
    }
    let along = edge * (1.0 / length);
    let first = clip_half_plane(ends, -along, -along.dot(r1))?;
    clip_half_plane(first, along, along.dot(r2))
}

/// Segment v1–v2 clipped to the half-plane n·p ≤ offset, as dyn4j lists the result.
fn clip_half_plane(ends: [(Vec2, usize); 2], n: Vec2, offset: f64) -> Option<[(Vec2, usize); 2]> {
    let [v1, v2] = ends;
    let (d1, d2) = (n.dot(v1.0) - offset, n.dot(v2.0) - offset);
    let mut out = [(Vec2::ZERO, 0); 2];
    let mut k = 0;
    for (v, d) in [(v1, d1), (v2, d2)] {
        if d <= 0.0 {
            out[k] = v;
            k += 1;
        }
    }
    if d1 * d2 < 0.0 && k < 2 {
        let u = d1 / (d1 - d2);
        let p = (v2.0 - v1.0) * u + v1.0;
        out[k] = (p, if d1 > 0.0 { v1.1 } else { v2.1 });
        k += 1;
    }
    (k == 2).then_some(out)
}

/// Clips segment p1–p2 (with tangent coordinates d1, d2) to [lower, upper]; false if nothing is left.
fn clip_segment(p1: &mut Vec2, p2: &mut Vec2, d1: f64, d2: f64, lower: f64, upper: f64) -> bool {
    let (a, b) = (*p1, *p2);
    let (lo_d, hi_d) = (d1.min(d2), d1.max(d2));
    if hi_d < lower || lo_d > upper {
        return false;
    }
    let lerp = |t: f64| a + (b - a) * t;
    let span = d2 - d1;
    if span.abs() < 1e-12 {
        return true;
    }
    let t_lower = (lower - d1) / span;
    let t_upper = (upper - d1) / span;
    let (t_min, t_max) = if span > 0.0 {
        (t_lower, t_upper)
    } else {
        (t_upper, t_lower)
    };
    let t0 = t_min.max(0.0);
    let t1 = t_max.min(1.0);
    if t0 > t1 {
        return false;
    }
    *p1 = lerp(t0);
    *p2 = lerp(t1);
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small box on a wide one, hanging over its left end: the incident (bottom) edge of the
    /// small box is cut at the wide box's left side. dyn4j lists the end it keeps first, then the
    /// cut point, which carries the index of the vertex cut off; the soft solver's clipping keeps
    /// the edge's own order.
    #[test]
    fn dyn4j_clipping_lists_the_kept_end_before_the_cut_point() {
        let wide = Polygon::rect(Vec2::new(0.0, -1.0), 2.0, 1.0);
        let small = Polygon::rect(Vec2::new(-2.0, 0.45), 0.5, 0.5);
        let soft = collide_polygons(&wide, &small, 0.0);
        let exact = collide_polygons_dyn4j(&wide, &small, 0.0);
        assert_eq!((soft.count, exact.count), (2, 2));
        // the small box's bottom edge runs from vertex 0 (x = −2.5, cut to −2) to vertex 1 (−1.5)
        assert!((soft.points[0].point.x + 2.0).abs() < 1e-12 && (soft.points[1].point.x + 1.5).abs() < 1e-12);
        assert!((exact.points[0].point.x + 1.5).abs() < 1e-12 && (exact.points[1].point.x + 2.0).abs() < 1e-12);
        let vertex = |id: u32| ((id - 1) >> 16) & 0xff;
        assert_eq!(vertex(exact.points[0].id), 1);
        assert_eq!(
            vertex(exact.points[1].id),
            0,
            "the cut point keeps the index of the vertex cut off"
        );
        for m in [soft, exact] {
            assert!((m.normal - Vec2::new(0.0, 1.0)).length() < 1e-12);
            assert!(m.points[..2].iter().all(|p| (p.separation + 0.05).abs() < 1e-12));
        }
    }

    fn edges_of(id: u32) -> (u32, u32) {
        ((id - 1) & 0xff, ((id - 1) >> 8) & 0xff)
    }

    /// A square standing on its left face (turned a quarter turn) on a wide box: its closing edge
    /// (vertex 3 to vertex 0) is the incident edge, numbered 4 when vertex 3 is the lower end and
    /// 0 when vertex 0 is, as dyn4j numbers it; other edges are numbered one past their index.
    #[test]
    fn dyn4j_numbers_the_closing_edge_by_the_end_it_is_reached_from() {
        use crate::math::Rot;
        let wide = Polygon::rect(Vec2::new(0.0, -1.0), 2.0, 1.0);
        let incident_edge = |turn: f64| {
            let small = Polygon::square(Vec2::ZERO, 0.5).transformed(Rot::new(turn), Vec2::new(0.0, 0.2));
            let m = collide_polygons_dyn4j(&wide, &small, 0.0);
            assert!(m.count >= 1);
            let (reference, incident) = edges_of(m.points[0].id);
            assert_eq!(reference, 3, "the wide box's top edge (2 to 3) is numbered 3");
            incident
        };
        let quarter = std::f64::consts::FRAC_PI_2;
        assert_eq!(incident_edge(quarter + 0.01), 4, "vertex 3 lower");
        assert_eq!(incident_edge(quarter - 0.01), 0, "vertex 0 lower");
        assert_eq!(incident_edge(0.01), 1, "the bottom edge (0 to 1)");
    }

    /// A diamond's corner pokes into a square's left face, the square's closing edge. Tilted and
    /// placed at arbitrary points, the square's reference edge is numbered 4 or 0 as the rounding
    /// of its world coordinates falls, about half of the time each (the original renumbers 49 % of
    /// such points from one step to the next); exactly aligned at round coordinates it is 0.
    #[test]
    fn a_reference_closing_edge_is_numbered_by_rounding() {
        use crate::math::Rot;
        let number = |tilt: f64, centre: Vec2| {
            let rot = Rot::new(tilt);
            let square = Polygon::square(Vec2::ZERO, 1.0).transformed(rot, centre);
            let face = centre + rot.apply(Vec2::new(-0.5, 0.0));
            let corner = face + rot.apply(Vec2::new(0.01, 0.0));
            let half_diagonal = 0.5 * std::f64::consts::SQRT_2;
            let diamond = Polygon::square(Vec2::ZERO, 1.0).transformed(
                Rot::new(std::f64::consts::FRAC_PI_4),
                corner - Vec2::new(half_diagonal, 0.0),
            );
            let m = collide_polygons_dyn4j(&diamond, &square, 0.0);
            assert!(
                m.count >= 1 && m.points[0].flipped(),
                "the square holds the reference edge"
            );
            edges_of(m.points[0].id).0
        };
        let trials = 400;
        let mut fours = 0;
        for k in 0..trials {
            let x = k as f64;
            let n = number(1e-3 * (0.37 * x).sin(), Vec2::new(10.3 + 0.0137 * x, 5.7 + 0.011 * x));
            assert!(n == 0 || n == 4, "{n}");
            fours += usize::from(n == 4);
        }
        let share = fours as f64 / trials as f64;
        println!("closing edge numbered 4 in {share} of the trials");
        assert!(
            (0.3..=0.7).contains(&share),
            "closing edge numbered 4 in {share} of the trials"
        );
        assert_eq!(number(0.0, Vec2::new(2.0, 3.0)), 0);
    }

    #[test]
    fn circle_on_box_touches_at_one_point_below_its_centre() {
        let ground = Polygon::rect(Vec2::new(0.0, -1.0), 10.0, 1.0);
        let ball = Polygon::circle(Vec2::new(0.3, 0.49), 0.5).unwrap();
        let m = collide_polygons(&ground, &ball, 0.05);
        assert_eq!(m.count, 1);
        assert!((m.normal - Vec2::new(0.0, 1.0)).length() < 1e-12);
        assert!((m.points[0].separation + 0.01).abs() < 1e-12);
        assert!((m.points[0].point - Vec2::new(0.3, -0.005)).length() < 1e-12);
        // same pair, other order: the normal flips, the point and separation stay
        let r = collide_polygons(&ball, &ground, 0.05);
        assert_eq!(r.count, 1);
        assert!((r.normal + m.normal).length() < 1e-12);
        assert!((r.points[0].point - m.points[0].point).length() < 1e-12);
        // lifted beyond the margin: no contact
        let high = Polygon::circle(Vec2::new(0.3, 0.6), 0.5).unwrap();
        assert_eq!(collide_polygons(&ground, &high, 0.05).count, 0);
    }

    #[test]
    fn circle_near_a_corner_is_pushed_away_from_the_corner() {
        let b = Polygon::square(Vec2::ZERO, 2.0);
        let ball = Polygon::circle(Vec2::new(1.3, 1.4), 0.6).unwrap();
        let m = collide_polygons(&b, &ball, 0.0);
        assert_eq!(m.count, 1);
        let expected = Vec2::new(0.3, 0.4) / 0.5;
        assert!((m.normal - expected).length() < 1e-12);
        assert!((m.points[0].separation + 0.1).abs() < 1e-12);
    }

    #[test]
    fn two_circles_collide_along_their_centres() {
        let a = Polygon::circle(Vec2::ZERO, 1.0).unwrap();
        let b = Polygon::circle(Vec2::new(1.5, 0.0), 1.0).unwrap();
        let m = collide_polygons(&a, &b, 0.0);
        assert_eq!(m.count, 1);
        assert_eq!(m.normal, Vec2::new(1.0, 0.0));
        assert!((m.points[0].separation + 0.5).abs() < 1e-12);
        assert!((m.points[0].point - Vec2::new(0.75, 0.0)).length() < 1e-12);
    }

    #[test]
    fn box_resting_on_box_gives_two_points_with_upward_normal() {
        let ground = Polygon::rect(Vec2::new(0.0, -1.0), 10.0, 1.0);
        let b = Polygon::square(Vec2::new(0.0, 0.49), 1.0);
        let m = collide_polygons(&ground, &b, 0.05);
        assert_eq!(m.count, 2);
        assert!((m.normal - Vec2::new(0.0, 1.0)).length() < 1e-12);
        for p in &m.points[..2] {
            assert!((p.separation + 0.01).abs() < 1e-12);
        }
    }

    #[test]
    fn normal_points_from_first_to_second_shape() {
        let a = Polygon::square(Vec2::new(0.0, 0.0), 1.0);
        let b = Polygon::square(Vec2::new(0.95, 0.2), 1.0);
        let m = collide_polygons(&a, &b, 0.0);
        assert!(m.count > 0);
        assert!(m.normal.x > 0.99);
        let m2 = collide_polygons(&b, &a, 0.0);
        assert!(m2.normal.x < -0.99);
    }

    #[test]
    fn distant_boxes_do_not_touch() {
        let a = Polygon::square(Vec2::new(0.0, 0.0), 1.0);
        let b = Polygon::square(Vec2::new(3.0, 0.0), 1.0);
        assert_eq!(collide_polygons(&a, &b, 0.1).count, 0);
    }
}
