//! Contacts of the sequential-impulse solver: rigid non-penetration with Coulomb friction and
//! restitution, warm started from the last step's impulses of the same points, two-point
//! manifolds solved as one block, and a position pass that removes overlap beyond `linear_slop`.
//!
//! A point sits on the incident shape (the vertex that entered the other shape) and carries its
//! depth, as dyn4j's clipping manifolds do; the normal points from body A to body B.

use super::{point_velocity, rotate_about, Params};
use crate::dynamics::contact::ContactConstraint;
use crate::dynamics::settings::Dyn4jVersion;
use crate::dynamics::world::Bodies;
use crate::geometry::collide::ManifoldPoint;
use crate::math::Vec2;

/// Two-point manifolds whose normal block is worse conditioned than this keep their deeper point.
const MAX_CONDITION: f64 = 1000.0;
/// Squared distance within which a point without feature ids (circles) counts as found again.
const WARM_START_DISTANCE_SQUARED: f64 = 1e-4;

#[derive(Debug, Clone, Copy, Default)]
struct Point {
    /// Where the point was found, in world coordinates.
    world: Vec2,
    /// The point relative to each body's centre of mass, in the body's frame.
    local_a: Vec2,
    local_b: Vec2,
    /// Overlap at detection (≥ 0).
    depth: f64,
    id: u32,
    ra: Vec2,
    rb: Vec2,
    mass_n: f64,
    mass_t: f64,
    /// Normal speed restitution asks for (0 below the restitution threshold).
    bounce: f64,
    jn: f64,
    jt: f64,
    jp: f64,
}

#[derive(Debug, Clone, Copy, Default)]
struct Contact {
    key: u64,
    /// When this pair of shapes came into contact (a sequence number; kept while they stay in
    /// contact from step to step).
    first_seen: u64,
    a: u32,
    b: u32,
    normal: Vec2,
    friction: f64,
    restitution: f64,
    points: [Point; 2],
    /// Points found (kept for warm starting the next step).
    count: usize,
    /// Points solved: `count`, or 1 when two points are nearly dependent.
    solved: usize,
    /// Normal block K = [[k00, k01], [k01, k11]] and its inverse, for two points.
    k: [f64; 3],
    inv_k: [f64; 3],
}

impl Contact {
    fn from_detected(d: &ContactConstraint, bodies: &Bodies) -> Contact {
        let (sa, sb) = (&bodies.state[d.a as usize], &bodies.state[d.b as usize]);
        let mut c = Contact {
            key: d.key,
            a: d.a,
            b: d.b,
            normal: d.normal,
            friction: d.friction,
            restitution: d.restitution,
            count: d.count,
            solved: d.count,
            ..Default::default()
        };
        for i in 0..d.count {
            let cp = &d.points[i];
            let id = d.ids[i];
            let separation = cp.base_separation;
            let midpoint = sa.pos + cp.ra;
            // back from the midpoint to the incident vertex, which lies −separation/2 beyond it
            // along the reference shape's normal
            let reference_normal = if id_flipped(id) { -d.normal } else { d.normal };
            let world = if id == 0 {
                midpoint
            } else {
                midpoint + reference_normal * (0.5 * separation)
            };
            c.points[i] = Point {
                world,
                local_a: sa.rot.apply_inv(world - sa.pos),
                local_b: sb.rot.apply_inv(world - sb.pos),
                depth: -separation,
                id,
                ..Default::default()
            };
        }
        c
    }

    /// Two nearly dependent points: only the deeper is solved. dyn4j 3.3.0 keeps the deeper (the
    /// second on a tie) and drops the other; 4.2.1 moves the deeper first (the first stays on a
    /// tie) and keeps the other, unsolved, so that its impulse can still warm start a point found
    /// again next step.
    fn solve_deeper_only(&mut self, version: Dyn4jVersion) {
        let [first, second] = [self.points[0].depth, self.points[1].depth];
        match version {
            Dyn4jVersion::V3_3_0 => {
                if first <= second {
                    self.points[0] = self.points[1];
                }
                self.count = 1;
            }
            Dyn4jVersion::V4_2_1 => {
                if first < second {
                    self.points.swap(0, 1);
                }
            }
        }
        self.solved = 1;
    }

    /// Takes over the impulses of the points that `old` had too.
    fn carry_over(&mut self, old: &Contact) {
        for p in &mut self.points[..self.count] {
            let same = old.points[..old.count].iter().find(|q| {
                if p.id != 0 {
                    q.id == p.id
                } else {
                    (q.world - p.world).length_squared() <= WARM_START_DISTANCE_SQUARED
                }
            });
            if let Some(q) = same {
                p.jn = q.jn;
                p.jt = q.jt;
            }
        }
    }

    /// Applies normal impulses `d` (one per point) to both bodies.
    #[inline]
    fn apply_normal_pair(&self, bodies: &mut Bodies, d: [f64; 2]) {
        let (p1, p2) = (self.normal * d[0], self.normal * d[1]);
        let (q1, q2) = (&self.points[0], &self.points[1]);
        let sa = &mut bodies.state[self.a as usize];
        sa.vel -= (p1 + p2) * sa.inv_mass;
        sa.omega -= sa.inv_inertia * (q1.ra.cross(p1) + q2.ra.cross(p2));
        let sb = &mut bodies.state[self.b as usize];
        sb.vel += (p1 + p2) * sb.inv_mass;
        sb.omega += sb.inv_inertia * (q1.rb.cross(p1) + q2.rb.cross(p2));
    }

    /// Normal speed of B relative to A at point `i`.
    #[inline]
    fn normal_speed(&self, bodies: &Bodies, i: usize) -> f64 {
        let p = &self.points[i];
        let (sa, sb) = (&bodies.state[self.a as usize], &bodies.state[self.b as usize]);
        self.normal.dot(point_velocity(sb, p.rb) - point_velocity(sa, p.ra))
    }

    /// The two normal impulses at once: the four cases of the linear complementarity problem
    /// (both points pushing, only the first, only the second, neither), first that holds wins.
    fn solve_normal_block(&mut self, bodies: &mut Bodies) {
        let old = [self.points[0].jn, self.points[1].jn];
        let [k00, k01, k11] = self.k;
        let [i00, i01, i11] = self.inv_k;
        let v = [0, 1].map(|i| self.normal_speed(bodies, i) - self.points[i].bounce);
        let b = [
            v[0] - (k00 * old[0] + k01 * old[1]),
            v[1] - (k01 * old[0] + k11 * old[1]),
        ];
        let both = [-(i00 * b[0] + i01 * b[1]), -(i01 * b[0] + i11 * b[1])];
        let first = -self.points[0].mass_n * b[0];
        let second = -self.points[1].mass_n * b[1];
        let new = if both[0] >= 0.0 && both[1] >= 0.0 {
            both
        } else if first >= 0.0 && k01 * first + b[1] >= 0.0 {
            [first, 0.0]
        } else if second >= 0.0 && k01 * second + b[0] >= 0.0 {
            [0.0, second]
        } else if b[0] >= 0.0 && b[1] >= 0.0 {
            [0.0, 0.0]
        } else {
            return;
        };
        self.apply_normal_pair(bodies, [new[0] - old[0], new[1] - old[1]]);
        self.points[0].jn = new[0];
        self.points[1].jn = new[1];
    }
}

/// Whether the reference edge of a point's manifold belonged to the second shape.
fn id_flipped(id: u32) -> bool {
    ManifoldPoint {
        id,
        ..Default::default()
    }
    .flipped()
}

/// This step's contacts and the last step's, for warm starting.
#[derive(Debug, Clone, Default)]
pub(crate) struct Contacts {
    current: Vec<Contact>,
    previous: Vec<Contact>,
    /// (key, index into `previous`), sorted by key.
    previous_keys: Vec<(u64, u32)>,
    /// The next `first_seen` number.
    next_seen: u64,
}

impl Contacts {
    /// Turns the detected manifolds into contacts, carrying over the impulses of the points found
    /// again (same two shapes, same features). With `oldest_first`, contacts are listed in the order
    /// their pairs came into contact (dyn4j 4.x keeps its collision pairs in insertion order), else
    /// in detection order.
    pub fn collect(
        &mut self,
        detected: &[ContactConstraint],
        bodies: &Bodies,
        warm_starting: bool,
        oldest_first: bool,
    ) {
        std::mem::swap(&mut self.current, &mut self.previous);
        self.previous_keys.clear();
        self.previous_keys
            .extend(self.previous.iter().enumerate().map(|(i, c)| (c.key, i as u32)));
        self.previous_keys.sort_unstable();
        self.current.clear();
        for d in detected {
            let mut c = Contact::from_detected(d, bodies);
            if let Ok(k) = self.previous_keys.binary_search_by_key(&c.key, |e| e.0) {
                let old = &self.previous[self.previous_keys[k].1 as usize];
                c.first_seen = old.first_seen;
                if warm_starting {
                    c.carry_over(old);
                }
            } else {
                c.first_seen = self.next_seen;
                self.next_seen += 1;
            }
            self.current.push(c);
        }
        if oldest_first {
            // first_seen numbers are distinct, so the unstable sort is deterministic
            self.current.sort_unstable_by_key(|c| c.first_seen);
        }
    }

    /// Bodies (a, b) of each contact, in the order they are listed.
    pub fn pairs(&self) -> impl Iterator<Item = (u32, u32)> + Clone + '_ {
        self.current.iter().map(|c| (c.a, c.b))
    }

    /// Arms, effective masses, restitution targets and the two-point block from the positions
    /// and velocities at the start of the solve, then (once all contacts are set up, as dyn4j
    /// does) the carried-over impulses applied again.
    pub fn initialize(&mut self, bodies: &mut Bodies, p: &Params, order: &[u32]) {
        for &k in order {
            let c = &mut self.current[k as usize];
            let (sa, sb) = (&bodies.state[c.a as usize], &bodies.state[c.b as usize]);
            let n = c.normal;
            let t = n.perp();
            let mass_along = |ra: Vec2, rb: Vec2, axis: Vec2| {
                let (rna, rnb) = (ra.cross(axis), rb.cross(axis));
                1.0 / (sa.inv_mass + sb.inv_mass + sa.inv_inertia * rna * rna + sb.inv_inertia * rnb * rnb)
            };
            for q in &mut c.points[..c.count] {
                q.ra = q.world - sa.pos;
                q.rb = q.world - sb.pos;
                q.mass_n = mass_along(q.ra, q.rb, n);
                q.mass_t = mass_along(q.ra, q.rb, t);
                let vn = n.dot(point_velocity(sb, q.rb) - point_velocity(sa, q.ra));
                q.bounce = if vn < -p.restitution_threshold {
                    -c.restitution * vn
                } else {
                    0.0
                };
            }
            if c.count == 2 {
                let (q1, q2) = (&c.points[0], &c.points[1]);
                let (r1a, r1b, r2a, r2b) = (q1.ra.cross(n), q1.rb.cross(n), q2.ra.cross(n), q2.rb.cross(n));
                let m = sa.inv_mass + sb.inv_mass;
                let k00 = m + sa.inv_inertia * r1a * r1a + sb.inv_inertia * r1b * r1b;
                let k01 = m + sa.inv_inertia * r1a * r2a + sb.inv_inertia * r1b * r2b;
                let k11 = m + sa.inv_inertia * r2a * r2a + sb.inv_inertia * r2b * r2b;
                let det = k00 * k11 - k01 * k01;
                if k00 * k00 < MAX_CONDITION * det {
                    c.k = [k00, k01, k11];
                    let inv = if det != 0.0 { 1.0 / det } else { 0.0 };
                    c.inv_k = [inv * k11, -inv * k01, inv * k00];
                } else {
                    c.solve_deeper_only(p.version);
                }
            }
        }
        for &k in order {
            let c = &self.current[k as usize];
            let t = c.normal.perp();
            for q in &c.points[..c.solved] {
                let impulse = c.normal * q.jn + t * q.jt;
                bodies.apply_impulse_pair(c.a as usize, c.b as usize, q.ra, q.rb, impulse);
            }
        }
    }

    /// One velocity sweep: friction at each point (bounded by μ times its normal impulse), then
    /// the normal impulses.
    pub fn solve_velocities(&mut self, bodies: &mut Bodies, order: &[u32]) {
        for &k in order {
            let c = &mut self.current[k as usize];
            let (a, b) = (c.a as usize, c.b as usize);
            let t = c.normal.perp();
            for q in &mut c.points[..c.solved] {
                let vt = t.dot(point_velocity(&bodies.state[b], q.rb) - point_velocity(&bodies.state[a], q.ra));
                let limit = c.friction * q.jn;
                let new = (q.jt - q.mass_t * vt).clamp(-limit, limit);
                let d = new - q.jt;
                q.jt = new;
                bodies.apply_impulse_pair(a, b, q.ra, q.rb, t * d);
            }
            if c.solved == 1 {
                let vn = c.normal_speed(bodies, 0);
                let q = &mut c.points[0];
                let new = (q.jn - q.mass_n * (vn - q.bounce)).max(0.0);
                let d = new - q.jn;
                q.jn = new;
                bodies.apply_impulse_pair(a, b, q.ra, q.rb, c.normal * d);
            } else if c.solved == 2 {
                c.solve_normal_block(bodies);
            }
        }
    }

    /// One position sweep: each point's remaining overlap beyond `linear_slop`, times
    /// `baumgarte` and at most `max_linear_correction`, pushed apart along the normal. True when
    /// no point overlaps by more than three times the slop.
    pub fn solve_positions(&mut self, bodies: &mut Bodies, p: &Params, order: &[u32]) -> bool {
        let mut min_separation: f64 = 0.0;
        for &k in order {
            let c = &mut self.current[k as usize];
            let (a, b) = (c.a as usize, c.b as usize);
            let n = c.normal;
            let weight = |i: usize| {
                let s = &bodies.state[i];
                if p.unit_position_mass {
                    (bodies.mass[i] * s.inv_mass, bodies.mass[i] * s.inv_inertia)
                } else {
                    (s.inv_mass, s.inv_inertia)
                }
            };
            let ((ma, ia), (mb, ib)) = (weight(a), weight(b));
            for q in &mut c.points[..c.solved] {
                let (sa, sb) = (&bodies.state[a], &bodies.state[b]);
                let (ra, rb) = (sa.rot.apply(q.local_a), sb.rot.apply(q.local_b));
                let separation = n.dot((sb.pos + rb) - (sa.pos + ra)) - q.depth;
                min_separation = min_separation.min(separation);
                let correction = p.baumgarte * (separation + p.linear_slop).clamp(-p.max_linear_correction, 0.0);
                let (rna, rnb) = (ra.cross(n), rb.cross(n));
                let k = ma + mb + ia * rna * rna + ib * rnb * rnb;
                let impulse = if k > f64::EPSILON { -correction / k } else { 0.0 };
                let new = (q.jp + impulse).max(0.0);
                let push = n * (new - q.jp);
                q.jp = new;
                let sa = &mut bodies.state[a];
                let pivot = sa.pos;
                sa.pos -= push * ma;
                rotate_about(sa, -ia * ra.cross(push), pivot);
                let sb = &mut bodies.state[b];
                let pivot = sb.pos;
                sb.pos += push * mb;
                rotate_about(sb, ib * rb.cross(push), pivot);
            }
        }
        min_separation >= -3.0 * p.linear_slop
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::settings::{Solver, WorldSettings};
    use crate::dynamics::world::BodyState;
    use crate::math::Rot;

    fn params(version: Dyn4jVersion) -> Params {
        Params::of(&WorldSettings {
            solver: Solver::SequentialImpulses,
            dyn4j: Some(version),
            ..WorldSettings::default()
        })
    }

    /// The static world (body 0) and unit bodies at `positions`, moving at `velocities`.
    fn bodies(positions: &[Vec2], velocities: &[Vec2]) -> Bodies {
        let mut b = Bodies::default();
        let body = |pos, vel, inv| BodyState {
            pos,
            rot: Rot::IDENTITY,
            vel,
            omega: 0.0,
            inv_mass: inv,
            inv_inertia: inv,
        };
        b.state.push(body(Vec2::ZERO, Vec2::ZERO, 0.0));
        b.mass.push(0.0);
        for (&p, &v) in positions.iter().zip(velocities) {
            b.state.push(body(p, v, 1.0));
            b.mass.push(1.0);
        }
        b
    }

    /// A contact between bodies a and b with normal +y and one point per (x, y, depth, id).
    fn contact(a: u32, b: u32, points: &[(f64, f64, f64, u32)]) -> Contact {
        let mut c = Contact {
            a,
            b,
            normal: Vec2::new(0.0, 1.0),
            friction: 1.0,
            restitution: 0.5,
            count: points.len(),
            solved: points.len(),
            ..Default::default()
        };
        for (q, &(x, y, depth, id)) in c.points.iter_mut().zip(points) {
            *q = Point {
                world: Vec2::new(x, y),
                depth,
                id,
                ..Default::default()
            };
        }
        c
    }

    /// Two nearly coincident points: 3.3.0 keeps the deeper only (the second on a tie); 4.2.1
    /// solves the deeper (the first on a tie) and keeps the other for next step's warm start.
    #[test]
    fn nearly_dependent_points_keep_the_deeper_as_each_version_does() {
        let kept = |version, d0: f64, d1: f64| {
            let mut c = contact(1, 2, &[(0.0, 0.0, d0, 1), (1e-7, 0.0, d1, 2)]);
            c.solve_deeper_only(version);
            (c.solved, c.count, c.points[0].id)
        };
        assert_eq!(kept(Dyn4jVersion::V3_3_0, 0.2, 0.1), (1, 1, 1));
        assert_eq!(kept(Dyn4jVersion::V3_3_0, 0.1, 0.2), (1, 1, 2));
        assert_eq!(kept(Dyn4jVersion::V3_3_0, 0.1, 0.1), (1, 1, 2));
        assert_eq!(kept(Dyn4jVersion::V4_2_1, 0.2, 0.1), (1, 2, 1));
        assert_eq!(kept(Dyn4jVersion::V4_2_1, 0.1, 0.2), (1, 2, 2));
        assert_eq!(kept(Dyn4jVersion::V4_2_1, 0.1, 0.1), (1, 2, 1));
        // and through initialize: two points 10⁻⁷ apart make an ill-conditioned block
        let mut b = bodies(&[Vec2::new(0.0, -0.5), Vec2::new(0.0, 0.5)], &[Vec2::ZERO; 2]);
        let mut contacts = Contacts {
            current: vec![contact(1, 2, &[(0.0, 0.0, 0.1, 1), (1e-7, 0.0, 0.2, 2)])],
            ..Default::default()
        };
        contacts.initialize(&mut b, &params(Dyn4jVersion::V4_2_1), &[0]);
        let c = &contacts.current[0];
        assert_eq!((c.solved, c.count, c.points[0].id), (1, 2, 2));
    }

    /// dyn4j sets up every contact (restitution targets from the velocities at the start of the
    /// solve) before it warm starts any: a warm-started neighbour must not change another contact's
    /// bounce.
    #[test]
    fn restitution_targets_are_read_before_any_warm_start() {
        // body 2 rests on body 1; body 3 falls onto body 2 at 2 (above the 1.0 threshold)
        let positions = [Vec2::new(0.0, 0.0), Vec2::new(0.0, 1.0), Vec2::new(0.0, 2.0)];
        let mut b = bodies(&positions, &[Vec2::ZERO, Vec2::ZERO, Vec2::new(0.0, -2.0)]);
        let mut below = contact(1, 2, &[(0.0, 0.5, 0.01, 1)]);
        below.points[0].jn = 5.0;
        let above = contact(2, 3, &[(0.0, 1.5, 0.01, 1)]);
        let mut contacts = Contacts {
            current: vec![below, above],
            ..Default::default()
        };
        contacts.initialize(&mut b, &params(Dyn4jVersion::V4_2_1), &[0, 1]);
        let bounce = contacts.current[1].points[0].bounce;
        assert!((bounce - 0.5 * 2.0).abs() < 1e-12, "bounce {bounce}");
        // the warm start itself was applied: body 2 was pushed up by 5
        assert!((b.state[2].vel.y - 5.0).abs() < 1e-12);
    }
}
