//! Contact constraints: soft non-penetration with Coulomb friction and restitution.
//!
//! Contacts are detected once per step; within the step's sub-steps the separation of each point
//! is updated from the bodies' motion, so the solver stays consistent without re-detecting.

use super::soft::Softness;
use super::world::Bodies;
use crate::geometry::collide::Manifold;
use crate::math::Vec2;

/// One point of a contact constraint.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ContactPoint {
    /// Anchor relative to body A's centre of mass, in A's frame.
    pub local_a: Vec2,
    /// Anchor relative to body B's centre of mass, in B's frame.
    pub local_b: Vec2,
    /// Anchors in world orientation at detection time (fixed Jacobian for the step).
    pub ra: Vec2,
    pub rb: Vec2,
    /// Separation at detection, minus the anchors' gap then (so it can be updated cheaply).
    pub base_separation: f64,
    pub normal_mass: f64,
    pub tangent_mass: f64,
    pub normal_impulse: f64,
    pub tangent_impulse: f64,
    pub max_normal_impulse: f64,
    /// Normal relative velocity before solving (for restitution).
    pub relative_velocity: f64,
}

/// A manifold turned into a constraint between shapes `shape_a` (body `a`) and `shape_b`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct ContactConstraint {
    pub shape_a: u32,
    /// Shape B index, or `u32::MAX` for static geometry.
    pub shape_b: u32,
    pub a: u32,
    pub b: u32,
    pub normal: Vec2,
    pub friction: f64,
    pub restitution: f64,
    pub points: [ContactPoint; 2],
    pub count: usize,
}

impl ContactConstraint {
    /// Builds a constraint from a world-space manifold and precomputes effective masses.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        bodies: &Bodies,
        manifold: &Manifold,
        shape_a: u32,
        shape_b: u32,
        a: u32,
        b: u32,
        friction: f64,
        restitution: f64,
    ) -> ContactConstraint {
        let (ai, bi) = (a as usize, b as usize);
        let n = manifold.normal;
        let t = n.perp();
        let mut c = ContactConstraint {
            shape_a,
            shape_b,
            a,
            b,
            normal: n,
            friction,
            restitution,
            count: manifold.count,
            ..Default::default()
        };
        for (i, mp) in manifold.points[..manifold.count].iter().enumerate() {
            let ra = mp.point - bodies.state[ai].pos;
            let rb = mp.point - bodies.state[bi].pos;
            let (rna, rnb) = (ra.cross(n), rb.cross(n));
            let (rta, rtb) = (ra.cross(t), rb.cross(t));
            let (ma, mb, ia, ib) = (
                bodies.state[ai].inv_mass,
                bodies.state[bi].inv_mass,
                bodies.state[ai].inv_inertia,
                bodies.state[bi].inv_inertia,
            );
            let kn = ma + mb + ia * rna * rna + ib * rnb * rnb;
            let kt = ma + mb + ia * rta * rta + ib * rtb * rtb;
            let va = bodies.state[ai].vel + Vec2::cross_scalar_left(bodies.state[ai].omega, ra);
            let vb = bodies.state[bi].vel + Vec2::cross_scalar_left(bodies.state[bi].omega, rb);
            c.points[i] = ContactPoint {
                local_a: bodies.state[ai].rot.apply_inv(ra),
                local_b: bodies.state[bi].rot.apply_inv(rb),
                ra,
                rb,
                base_separation: mp.separation,
                normal_mass: if kn > 0.0 { 1.0 / kn } else { 0.0 },
                tangent_mass: if kt > 0.0 { 1.0 / kt } else { 0.0 },
                relative_velocity: n.dot(vb - va),
                ..Default::default()
            };
        }
        c
    }

    /// Current separation of point `p` given the bodies' present positions.
    #[inline]
    pub fn separation(&self, bodies: &Bodies, p: &ContactPoint) -> f64 {
        let (a, b) = (self.a as usize, self.b as usize);
        let pa = bodies.state[a].pos + bodies.state[a].rot.apply(p.local_a);
        let pb = bodies.state[b].pos + bodies.state[b].rot.apply(p.local_b);
        p.base_separation + self.normal.dot(pb - pa)
    }
}

/// Parameters of one solver pass over the contacts.
pub(crate) struct ContactPass {
    pub soft: Softness,
    pub static_soft: Softness,
    pub inv_h: f64,
    pub push_max: f64,
    pub use_bias: bool,
}

/// Solves every contact once (normal then friction per point).
pub(crate) fn solve_contacts(contacts: &mut [ContactConstraint], bodies: &mut Bodies, pass: &ContactPass) {
    for c in contacts.iter_mut() {
        let (a, b) = (c.a as usize, c.b as usize);
        let n = c.normal;
        let t = n.perp();
        let soft = if c.shape_b == u32::MAX {
            pass.static_soft
        } else {
            pass.soft
        };
        for i in 0..c.count {
            let p = c.points[i];
            let s = c.separation(bodies, &p);
            let (bias, mass_scale, impulse_scale) = if s > 0.0 {
                (s * pass.inv_h, 1.0, 0.0)
            } else if pass.use_bias {
                (
                    (soft.bias_rate * s).max(-pass.push_max),
                    soft.mass_scale,
                    soft.impulse_scale,
                )
            } else {
                (0.0, 1.0, 0.0)
            };
            let va = bodies.state[a].vel + Vec2::cross_scalar_left(bodies.state[a].omega, p.ra);
            let vb = bodies.state[b].vel + Vec2::cross_scalar_left(bodies.state[b].omega, p.rb);
            let vn = n.dot(vb - va);
            let delta = -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
            let new = (p.normal_impulse + delta).max(0.0);
            let applied = new - p.normal_impulse;
            let cp = &mut c.points[i];
            cp.normal_impulse = new;
            cp.max_normal_impulse = cp.max_normal_impulse.max(applied);
            bodies.apply_impulse_pair(a, b, p.ra, p.rb, n * applied);
        }
        for i in 0..c.count {
            let p = c.points[i];
            let va = bodies.state[a].vel + Vec2::cross_scalar_left(bodies.state[a].omega, p.ra);
            let vb = bodies.state[b].vel + Vec2::cross_scalar_left(bodies.state[b].omega, p.rb);
            let vt = t.dot(vb - va);
            let max_f = c.friction * p.normal_impulse;
            let new = (p.tangent_impulse - p.tangent_mass * vt).clamp(-max_f, max_f);
            let applied = new - p.tangent_impulse;
            c.points[i].tangent_impulse = new;
            bodies.apply_impulse_pair(a, b, p.ra, p.rb, t * applied);
        }
    }
}

/// Makes fast-approaching contacts bounce: target normal speed −e·v_before.
pub(crate) fn apply_restitution(contacts: &mut [ContactConstraint], bodies: &mut Bodies, threshold: f64) {
    for c in contacts.iter_mut() {
        if c.restitution == 0.0 {
            continue;
        }
        let (a, b) = (c.a as usize, c.b as usize);
        let n = c.normal;
        for i in 0..c.count {
            let p = c.points[i];
            if p.relative_velocity > -threshold || p.max_normal_impulse == 0.0 {
                continue;
            }
            let va = bodies.state[a].vel + Vec2::cross_scalar_left(bodies.state[a].omega, p.ra);
            let vb = bodies.state[b].vel + Vec2::cross_scalar_left(bodies.state[b].omega, p.rb);
            let vn = n.dot(vb - va);
            let delta = -p.normal_mass * (vn + c.restitution * p.relative_velocity);
            let new = (p.normal_impulse + delta).max(0.0);
            let applied = new - p.normal_impulse;
            c.points[i].normal_impulse = new;
            bodies.apply_impulse_pair(a, b, p.ra, p.rb, n * applied);
        }
    }
}
