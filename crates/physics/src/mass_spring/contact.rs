//! Contacts between quads: a point inside another quad is pushed out through the nearest
//! boundary side of that quad that its own sides cross, with a penalty force, damping of normal
//! velocities and regularised friction (EvoGym's point-against-edge model).

use super::bodies::Bodies;
use super::broad_phase::BroadPhase;
use super::points::Points;
use super::quad_geometry::{line_distance, norm, point_in_quad, segments_intersect, MIN_SIDE};
use super::settings::ContactSettings;
use vsrlab_lanes::fdlibm_tanh;

/// Recomputes the contact forces of this substep into `points.contact_fx/fy` for the candidate
/// pairs of `broad`; returns how many point-in-quad contacts produced a force.
pub(crate) fn compute_contact_forces(
    bodies: &Bodies,
    broad: &mut BroadPhase,
    points: &mut Points,
    c: &ContactSettings,
) -> usize {
    points.contact_fx.fill(0.0);
    points.contact_fy.fill(0.0);
    let mut contacts = 0;
    broad.update(bodies);
    for &(sa, sb) in broad.pairs() {
        // EvoGym visits each unordered pair of one body's quads twice, so self-contact counts double.
        let weight = if broad.same_body(sa, sb) { 2.0 } else { 1.0 };
        let (sa, sb) = (sa as usize, sb as usize);
        contacts += quad_into_quad(bodies, points, c, sa, sb, weight);
        contacts += quad_into_quad(bodies, points, c, sb, sa, weight);
    }
    contacts
}

/// Pushes each corner of the quad in slot `main` that lies inside the quad in slot `other` (and
/// is not one of its corners) out of it. The other quad's box (current, from the end of the last
/// substep) rejects most corners before the exact test.
fn quad_into_quad(
    bodies: &Bodies,
    points: &mut Points,
    c: &ContactSettings,
    main: usize,
    other_slot: usize,
    weight: f64,
) -> usize {
    let other = bodies.boundary[other_slot] as usize;
    let main_quad = bodies.boundary[main] as usize;
    let m = bodies.quad_points[main_quad];
    let o = bodies.quad_points[other];
    let other_box = bodies.boxes[other_slot];
    let mut contacts = 0;
    for (k, &corner) in m.iter().enumerate() {
        let p = corner as usize;
        if o.contains(&corner) || !other_box.contains(points.x[p], points.y[p]) {
            continue;
        }
        if let Some(forces) = corner_contact(bodies, points, c, main_quad, other, k, weight) {
            forces.add_to(points);
            contacts += 1;
        }
    }
    contacts
}

/// The contact of corner `k` of quad `main_quad` with quad `other` (a corner inside its box and
/// not one of its corners): the forces on the corner and on the ends of the side it is pushed out
/// through, `None` when it is outside the quad or crosses no boundary side. The forces are
/// returned, not added, so that lanes can add them in their own world's order.
pub(crate) fn corner_contact(
    bodies: &Bodies,
    points: &Points,
    c: &ContactSettings,
    main_quad: usize,
    other: usize,
    k: usize,
    weight: f64,
) -> Option<ContactForces> {
    let p = bodies.quad_points[main_quad][k] as usize;
    let o = bodies.quad_points[other];
    let (ox, oy) = (o.map(|q| points.x[q as usize]), o.map(|q| points.y[q as usize]));
    if !point_in_quad(points.x[p], points.y[p], ox, oy) {
        return None;
    }
    let own = [(k + 3) % 4, k].map(|s| bodies.walked_sides[main_quad][s]);
    let (a, b, depth) = exit_side(bodies, points, other, p, own)?;
    Some(push_out(points, c, p, a, b, depth, weight))
}

/// The forces of one contact: on the point pushed out, then on the two ends of the side, added in
/// that order; `None` for a side shorter than [`MIN_SIDE`], which pushes nothing (the contact
/// still counts).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactForces(Option<[(u32, f64, f64); 3]>);

impl ContactForces {
    /// Adds the forces to the points' contact forces, in order.
    pub fn add_to(&self, points: &mut Points) {
        for &(i, fx, fy) in self.0.iter().flatten() {
            points.contact_fx[i as usize] += fx;
            points.contact_fy[i as usize] += fy;
        }
    }
}

/// The boundary side of `other` nearest to point `p` (distance to its line) among those that one
/// of `p`'s own two sides (`own`, as walked) crosses; first one wins ties.
fn exit_side(
    bodies: &Bodies,
    points: &Points,
    other: usize,
    p: usize,
    own: [(u32, u32); 2],
) -> Option<(usize, usize, f64)> {
    let at = |i: u32| (points.x[i as usize], points.y[i as usize]);
    let mut best: Option<(usize, usize, f64)> = None;
    for &(a, b) in bodies.quad_sides[other].iter().flatten() {
        let crossed = own.iter().any(|&(s, e)| segments_intersect(at(s), at(e), at(a), at(b)));
        let (a, b) = (a as usize, b as usize);
        if !crossed {
            continue;
        }
        let d = line_distance(at(p as u32), at(a as u32), at(b as u32));
        if best.is_none_or(|(_, _, bd)| d < bd) {
            best = Some((a, b, d));
        }
    }
    best
}

/// The penalty, damping and friction forces of point `p` against side a→b at `depth`.
fn push_out(
    points: &Points,
    c: &ContactSettings,
    p: usize,
    a: usize,
    b: usize,
    depth: f64,
    weight: f64,
) -> ContactForces {
    let (sx, sy) = (points.x[b] - points.x[a], points.y[b] - points.y[a]);
    let len = norm(sx, sy);
    if len < MIN_SIDE {
        return ContactForces(None);
    }
    let (nx, ny) = (-sy / len, sx / len);
    let push = c.stiffness * (c.offset + depth);
    let damp = |i: usize| (nx * points.moved_vx[i] + ny * points.moved_vy[i]) * c.damping;
    let (dp, da, db) = (damp(p), damp(a), damp(b));
    // Friction opposes p's own tangential velocity; saturates at gain × coefficient × push.
    let (tx, ty) = (-ny, nx);
    let vt = tx * points.moved_vx[p] + ty * points.moved_vy[p];
    let scale = c.friction * push;
    let friction = -c.friction_gain * scale * fdlibm_tanh(vt.abs() / scale) * vt.signum();
    let (ffx, ffy) = (tx * friction, ty * friction);
    let side = |i: usize, d: f64| {
        (
            i as u32,
            -weight * (nx * (push + d) + ffx) / 2.0,
            -weight * (ny * (push + d) + ffy) / 2.0,
        )
    };
    ContactForces(Some([
        (
            p as u32,
            weight * (nx * (push - dp) + ffx),
            weight * (ny * (push - dp) + ffy),
        ),
        side(a, da),
        side(b, db),
    ]))
}
