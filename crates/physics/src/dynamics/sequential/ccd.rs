//! Continuous collision detection of the sequential-impulse solver: dyn4j's pass after the
//! position iterations (mode ALL), which stops a body that would have passed into static geometry
//! during the step at the time of impact.
//!
//! For every dynamic body and every static polygon it is not already in contact with, whose
//! boxes overlap: conservative advancement from the body's pose at the start of the step along
//! its end-of-step velocity finds the first time of impact t ∈ [0, 1]. The earliest over all
//! polygons moves the body back to the pose t of the way from its start to its end pose, then
//! nudges it towards the polygon (or, in 3.3.0, away from it) so that the next detection finds a
//! contact. Velocities are left as they are. Both versions' details are kept (docs/physics.md):
//!
//! - 3.3.0: a static polygon's box is its centre ± its farthest vertex (large for long ground
//!   quads); an impact at time 0 (distance below tolerance at the start, or negative, see
//!   [`super::distance`]) counts; the nudge is a position correction of the remaining distance
//!   minus the slop, with unit masses and a turn.
//! - 4.2.1: a static polygon's box is tight; an impact at time 0 cancels the pass for that body;
//!   the nudge moves the body by the distance plus the slop, without turning it.

use super::distance::{distance, Separation};
use super::{rotate_about, wrap_angle, Params};
use crate::dynamics::contact::ContactConstraint;
use crate::dynamics::settings::Dyn4jVersion;
use crate::dynamics::world::{Bodies, BodyState};
use crate::geometry::aabb::Aabb;
use crate::geometry::shape::{Polygon, MAX_POLYGON_VERTICES};
use crate::math::{Rot, Vec2};

/// Most steps of conservative advancement (dyn4j's default).
const MAX_ITERATIONS: usize = 30;
/// Conservative advancement's distance tolerance, ∛ε (dyn4j's); a literal, as `cbrt` is not a
/// `const fn` and cost 2 % of a step computed per call (a test checks it is the same number).
const TOLERANCE: f64 = 6.0554544523933395e-6;

/// A static polygon as the pass sees it.
#[derive(Debug, Clone, Copy)]
struct StaticShape {
    polygon: Polygon,
    centre: Vec2,
    /// The box dyn4j 3.3.0 gives it: centre ± distance to the farthest vertex.
    disc: Aabb,
    /// Its tight box (dyn4j 4.x).
    aabb: Aabb,
}

/// A dynamic polygon, relative to its body's centre of mass in the body's frame.
#[derive(Debug, Clone, Copy)]
struct DynamicShape {
    local: Polygon,
    centre: Vec2,
    /// Distance from the polygon's own centre to its farthest vertex.
    radius: f64,
}

/// Where a polygon is at one pose: its world vertices and centre.
struct Placed {
    vertices: [Vec2; MAX_POLYGON_VERTICES],
    count: usize,
    centre: Vec2,
}

impl Placed {
    fn of(shape: &DynamicShape, pos: Vec2, rot: Rot) -> Placed {
        let mut vertices = [Vec2::ZERO; MAX_POLYGON_VERTICES];
        for (v, l) in vertices.iter_mut().zip(shape.local.verts()) {
            *v = pos + rot.apply(*l);
        }
        Placed {
            vertices,
            count: shape.local.count,
            centre: pos + rot.apply(shape.centre),
        }
    }
    fn verts(&self) -> &[Vec2] {
        &self.vertices[..self.count]
    }
}

/// The static geometry, the dynamic polygons and the start-of-step poses the pass needs.
#[derive(Debug, Clone, Default)]
pub(crate) struct Ccd {
    statics: Vec<StaticShape>,
    shapes: Vec<DynamicShape>,
    /// Per body: the range of its polygons in `shapes`.
    body_shapes: Vec<(u32, u32)>,
    /// Per body: the farthest polygon vertex from its centre of mass.
    body_radius: Vec<f64>,
    /// Per body: position and rotation at the start of the step.
    start: Vec<(Vec2, Rot)>,
    /// (body, static polygon) pairs in contact at the start of the step, sorted.
    touching: Vec<(u32, u32)>,
}

impl Ccd {
    /// `statics` in the world's order; `shapes` as (body, polygon relative to the body's centre of
    /// mass), grouped by body; circles are left out (the pass handles polygons only).
    pub fn new(statics: &[Polygon], shapes: &[(u32, Polygon)], n_bodies: usize) -> Ccd {
        let statics = statics
            .iter()
            .map(|p| {
                let centre = p.mass_properties().1;
                StaticShape {
                    polygon: *p,
                    centre,
                    disc: Aabb::of_points(&[centre]).inflated(farthest_vertex(p, centre)),
                    aabb: Aabb::of_points(p.verts()),
                }
            })
            .collect();
        let mut body_shapes = vec![(0u32, 0u32); n_bodies];
        let mut body_radius = vec![0.0f64; n_bodies];
        let mut list = Vec::new();
        for &(body, local) in shapes.iter().filter(|(_, p)| !p.is_circle()) {
            let centre = local.mass_properties().1;
            let r = &mut body_shapes[body as usize];
            if r.1 == 0 {
                r.0 = list.len() as u32;
            }
            r.1 = list.len() as u32 + 1;
            body_radius[body as usize] = body_radius[body as usize].max(farthest_vertex(&local, Vec2::ZERO));
            list.push(DynamicShape {
                local,
                centre,
                radius: farthest_vertex(&local, centre),
            });
        }
        Ccd {
            statics,
            shapes: list,
            body_shapes,
            body_radius,
            start: vec![(Vec2::ZERO, Rot::IDENTITY); n_bodies],
            touching: Vec::new(),
        }
    }

    /// Remembers every body's pose at the start of the step.
    pub fn remember_start(&mut self, bodies: &Bodies) {
        for (s, b) in self.start.iter_mut().zip(&bodies.state) {
            *s = (b.pos, b.rot);
        }
    }

    /// Runs the pass over every dynamic body (after the position iterations). `contacts` are the
    /// contacts this step was solved with; `static_of` gives a static contact's polygon index.
    pub fn solve(
        &mut self,
        bodies: &mut Bodies,
        contacts: &[ContactConstraint],
        static_of: impl Fn(u64) -> u32,
        p: &Params,
    ) {
        self.touching.clear();
        for c in contacts.iter().filter(|c| c.a == 0) {
            self.touching.push((c.b, static_of(c.key)));
        }
        self.touching.sort_unstable();
        for body in 1..bodies.len() {
            if self.body_shapes[body].1 > self.body_shapes[body].0 {
                self.solve_body(bodies, body, p);
            }
        }
    }

    fn solve_body(&self, bodies: &mut Bodies, body: usize, p: &Params) {
        let (pos0, rot0) = self.start[body];
        let s = bodies.state[body];
        let swept = self.swept_box(body, &s, p.version);
        let (dp, da) = (s.vel * p.dt, s.omega * p.dt);
        let mut earliest: Option<(f64, Separation)> = None;
        for (k, st) in self.statics.iter().enumerate() {
            let box2 = match p.version {
                Dyn4jVersion::V3_3_0 => &st.disc,
                Dyn4jVersion::V4_2_1 => &st.aabb,
            };
            if !swept.overlaps(box2) || self.touching.binary_search(&(body as u32, k as u32)).is_ok() {
                continue;
            }
            let (lo, hi) = self.body_shapes[body];
            for shape in &self.shapes[lo as usize..hi as usize] {
                let Some((t, sep)) = advance(shape, pos0, rot0, dp, da, st, p.version) else {
                    continue;
                };
                if t == 0.0 && p.version == Dyn4jVersion::V4_2_1 {
                    return;
                }
                if earliest.is_none_or(|(t2, _)| t < t2) {
                    earliest = Some((t, sep));
                }
            }
        }
        let Some((t, sep)) = earliest else {
            return;
        };
        let b = &mut bodies.state[body];
        b.pos = pos0 * (1.0 - t) + s.pos * t;
        let (rs, re) = (rot0.s.atan2(rot0.c), s.rot.s.atan2(s.rot.c));
        let diff = wrap_angle(re - rs);
        b.rot = Rot::new(diff * t + rs);
        let (mass, im, ii) = (bodies.mass[body], b.inv_mass, b.inv_inertia);
        match p.version {
            Dyn4jVersion::V3_3_0 => {
                let (im, ii) = (mass * im, mass * ii);
                let pivot = b.pos;
                let r1 = sep.point1 - pivot;
                let c = (sep.distance - p.linear_slop).clamp(-p.max_linear_correction, 0.0);
                let rn = r1.cross(sep.normal);
                let k = im + ii * rn * rn;
                let impulse = if k > 0.0 { -c / k } else { 0.0 };
                let j = sep.normal * impulse;
                b.pos += j * im;
                rotate_about(b, ii * r1.cross(j), pivot);
            }
            Dyn4jVersion::V4_2_1 => {
                if sep.distance <= 0.0 {
                    return;
                }
                let im = mass * im;
                let c = (sep.distance + p.linear_slop).clamp(0.0, p.max_linear_correction);
                let impulse = if im > 0.0 { c / im } else { 0.0 };
                b.pos += sep.normal * (impulse * im);
            }
        }
    }

    /// The box a body sweeps through in the step, as the version computes it.
    fn swept_box(&self, body: usize, s: &BodyState, version: Dyn4jVersion) -> Aabb {
        let (pos0, rot0) = self.start[body];
        let r = self.body_radius[body];
        let centres = Aabb::of_points(&[pos0, s.pos]);
        let (lo, hi) = self.body_shapes[body];
        let single = hi - lo == 1;
        match version {
            Dyn4jVersion::V3_3_0 => centres.inflated(r),
            Dyn4jVersion::V4_2_1 if rot0 != s.rot || s.omega != 0.0 || !single => centres.inflated(r),
            Dyn4jVersion::V4_2_1 => {
                let placed = Placed::of(&self.shapes[lo as usize], pos0, rot0);
                let start = Aabb::of_points(placed.verts());
                let shift = s.pos - pos0;
                Aabb {
                    min: start.min.min(start.min + shift),
                    max: start.max.max(start.max + shift),
                }
            }
        }
    }
}

/// Conservative advancement of a moving polygon towards a static one: the first time t ∈ [0, 1]
/// at which they come within tolerance, with their separation then; `None` when they do not meet
/// within the step, or overlap from its start.
fn advance(
    shape: &DynamicShape,
    pos0: Vec2,
    rot0: Rot,
    dp: Vec2,
    da: f64,
    st: &StaticShape,
    version: Dyn4jVersion,
) -> Option<(f64, Separation)> {
    let tolerance = TOLERANCE;
    let at = |l: f64| {
        let rot = super::turned(rot0, Rot::new(da * l));
        Placed::of(shape, pos0 + dp * l, rot)
    };
    let measure = |placed: &Placed| distance(placed.verts(), placed.centre, st.polygon.verts(), st.centre, version);
    let mut sep = measure(&at(0.0))?;
    let mut d = sep.distance;
    if d < tolerance {
        return match version {
            Dyn4jVersion::V3_3_0 => Some((0.0, sep)),
            Dyn4jVersion::V4_2_1 => None,
        };
    }
    let mut n = sep.normal;
    let amax = shape.radius * da.abs();
    if dp.length() + amax == 0.0 {
        return None;
    }
    let (mut l, mut l0) = (0.0f64, 0.0f64);
    let mut iterations = 0;
    while d > tolerance && iterations < MAX_ITERATIONS {
        let drel = dp.dot(n) + amax;
        if drel <= f64::EPSILON {
            return None;
        }
        l += d / drel;
        if !(0.0..=1.0).contains(&l) {
            return None;
        }
        if l <= l0 {
            break;
        }
        l0 = l;
        iterations += 1;
        match measure(&at(l)) {
            Some(s) => {
                sep = s;
                n = s.normal;
                d = s.distance;
            }
            None => {
                match version {
                    Dyn4jVersion::V3_3_0 => {
                        // back off half the tolerance and measure again (keeping the last
                        // separation when they still overlap)
                        l -= 0.5 * tolerance / drel;
                        if let Some(s) = measure(&at(l)) {
                            sep = s;
                        }
                    }
                    Dyn4jVersion::V4_2_1 => sep = Separation::default(),
                }
                break;
            }
        }
    }
    Some((l, sep))
}

fn farthest_vertex(p: &Polygon, from: Vec2) -> f64 {
    p.verts().iter().map(|v| (*v - from).length()).fold(0.0, f64::max) + p.radius
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_tolerance_literal_is_the_cube_root_of_epsilon() {
        assert_eq!(super::TOLERANCE.to_bits(), f64::EPSILON.cbrt().to_bits());
    }
}
