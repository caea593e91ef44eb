//! Contacts between quads: a point inside another quad is pushed out through the nearest
//! boundary side of that quad that its own sides cross, with a penalty force, damping of normal
//! velocities and regularised friction (EvoGym's point-against-edge model).

use super::bodies::Bodies;
use super::points::Points;
use super::quad_geometry::{line_distance, point_in_quad, segments_intersect, MIN_SIDE};
use super::settings::ContactSettings;

/// Recomputes the contact forces of this substep into `points.contact_fx/fy`; returns how many
/// point-in-quad contacts produced a force.
pub(crate) fn compute_contact_forces(bodies: &Bodies, points: &mut Points, c: &ContactSettings) -> usize {
    points.contact_fx.fill(0.0);
    points.contact_fy.fill(0.0);
    let mut contacts = 0;
    for i in 0..bodies.len() {
        for j in i..bodies.len() {
            contacts += body_pair(bodies, points, c, i, j);
        }
    }
    contacts
}

/// Contacts between the boundary quads of bodies `i` and `j` (the same body when `i == j`).
fn body_pair(bodies: &Bodies, points: &mut Points, c: &ContactSettings, i: usize, j: usize) -> usize {
    let same = i == j;
    if bodies.all_fixed[i] && bodies.all_fixed[j] {
        return 0;
    }
    if !same && !bodies.body_boxes[i].overlaps(&bodies.body_boxes[j]) {
        return 0;
    }
    // EvoGym visits each unordered pair of one body's quads twice, so self-contact counts double.
    let weight = if same { 2.0 } else { 1.0 };
    let mut contacts = 0;
    for sa in bodies.slots(i) {
        if !same && !bodies.boxes[sa].overlaps(&bodies.body_boxes[j]) {
            continue;
        }
        let first_b = if same { sa + 1 } else { bodies.slots(j).start };
        for sb in first_b..bodies.slots(j).end {
            if !bodies.boxes[sa].overlaps(&bodies.boxes[sb]) {
                continue;
            }
            let (qa, qb) = (bodies.boundary[sa] as usize, bodies.boundary[sb] as usize);
            contacts += quad_into_quad(bodies, points, c, qa, qb, weight);
            contacts += quad_into_quad(bodies, points, c, qb, qa, weight);
        }
    }
    contacts
}

/// Pushes each corner of quad `main` that lies inside quad `other` (and is not one of its
/// corners) out of `other`.
fn quad_into_quad(
    bodies: &Bodies,
    points: &mut Points,
    c: &ContactSettings,
    main: usize,
    other: usize,
    weight: f64,
) -> usize {
    let m = bodies.quad_points[main];
    let o = bodies.quad_points[other];
    let (ox, oy) = (o.map(|p| points.x[p as usize]), o.map(|p| points.y[p as usize]));
    let mut contacts = 0;
    for k in 0..4 {
        let p = m[k] as usize;
        if o.contains(&m[k]) || !point_in_quad(points.x[p], points.y[p], ox, oy) {
            continue;
        }
        let prev = m[(k + 3) % 4] as usize;
        let next = m[(k + 1) % 4] as usize;
        if let Some((a, b, depth)) = exit_side(bodies, points, other, p, prev, next) {
            push_out(points, c, p, a, b, depth, weight);
            contacts += 1;
        }
    }
    contacts
}

/// The boundary side of `other` nearest to point `p` (distance to its line) among those that one
/// of `p`'s own two sides (to `prev` and to `next`) crosses; first one wins ties.
fn exit_side(
    bodies: &Bodies,
    points: &Points,
    other: usize,
    p: usize,
    prev: usize,
    next: usize,
) -> Option<(usize, usize, f64)> {
    let at = |i: usize| (points.x[i], points.y[i]);
    let mut best: Option<(usize, usize, f64)> = None;
    for (a, b) in bodies.quad_sides[other].iter().flatten() {
        let (a, b) = (*a as usize, *b as usize);
        let crossed =
            segments_intersect(at(p), at(prev), at(a), at(b)) || segments_intersect(at(p), at(next), at(a), at(b));
        if !crossed {
            continue;
        }
        let d = line_distance(at(p), at(a), at(b));
        if best.is_none_or(|(_, _, bd)| d < bd) {
            best = Some((a, b, d));
        }
    }
    best
}

/// Adds the penalty, damping and friction forces of point `p` against side a→b at `depth`.
fn push_out(points: &mut Points, c: &ContactSettings, p: usize, a: usize, b: usize, depth: f64, weight: f64) {
    let (sx, sy) = (points.x[b] - points.x[a], points.y[b] - points.y[a]);
    let len = sx.hypot(sy);
    if len < MIN_SIDE {
        return;
    }
    let (nx, ny) = (-sy / len, sx / len);
    let push = c.stiffness * (c.offset + depth);
    let damp = |i: usize| (nx * points.moved_vx[i] + ny * points.moved_vy[i]) * c.damping;
    let (dp, da, db) = (damp(p), damp(a), damp(b));
    // Friction opposes p's own tangential velocity; saturates at gain × coefficient × push.
    let (tx, ty) = (-ny, nx);
    let vt = tx * points.moved_vx[p] + ty * points.moved_vy[p];
    let scale = c.friction * push;
    let friction = -c.friction_gain * scale * (vt.abs() / scale).tanh() * vt.signum();
    let (ffx, ffy) = (tx * friction, ty * friction);
    add(
        points,
        p,
        weight * (nx * (push - dp) + ffx),
        weight * (ny * (push - dp) + ffy),
    );
    add(
        points,
        a,
        -weight * (nx * (push + da) + ffx) / 2.0,
        -weight * (ny * (push + da) + ffy) / 2.0,
    );
    add(
        points,
        b,
        -weight * (nx * (push + db) + ffx) / 2.0,
        -weight * (ny * (push + db) + ffy) / 2.0,
    );
}

fn add(points: &mut Points, i: usize, fx: f64, fy: f64) {
    points.contact_fx[i] += fx;
    points.contact_fy[i] += fy;
}
