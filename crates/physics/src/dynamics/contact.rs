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
    /// The manifold's point ids (see [`crate::geometry::collide::ManifoldPoint::id`]).
    pub ids: [u32; 2],
    /// Which pair of shapes touches (static polygons included), to recognise it next step.
    pub key: u64,
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
            c.ids[i] = mp.id;
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

/// The order in which the contacts of a step are solved (see [`ContactSchedule::build`]);
/// reusable buffers, so nothing is allocated once warm.
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactSchedule {
    /// Per body: the wave after the last contact seen so far that touches it.
    body_wave: Vec<u32>,
    /// Per contact: its wave.
    wave: Vec<u32>,
    /// Per wave: where its contacts end in `order`.
    end: Vec<u32>,
    /// Contact indices, wave by wave.
    order: Vec<u32>,
}

impl ContactSchedule {
    /// Orders the contacts in waves: a contact's wave is one more than that of the last earlier
    /// contact sharing a moving body with it, and contacts are sorted by wave, stably. Every body
    /// therefore meets its contacts in the same order as in `contacts`, and the contacts of a wave
    /// touch different moving bodies, so a Gauss–Seidel sweep in this order gives bit-identical
    /// results while the contacts of a wave can be solved together. Body 0 (the static world)
    /// never moves and is shared freely.
    pub fn build(&mut self, contacts: &[ContactConstraint], n_bodies: usize) {
        self.body_wave.clear();
        self.body_wave.resize(n_bodies, 0);
        self.wave.clear();
        let mut waves = 0;
        for c in contacts {
            let (a, b) = (c.a as usize, c.b as usize);
            let w = self.body_wave[a].max(self.body_wave[b]);
            self.wave.push(w);
            for body in [a, b] {
                if body != 0 {
                    self.body_wave[body] = w + 1;
                }
            }
            waves = waves.max(w + 1);
        }
        // counting sort: `end[w]` first counts the contacts before wave w, then is advanced past
        // each of its contacts, ending at the end of wave w
        self.end.clear();
        self.end.resize(waves as usize + 1, 0);
        for &w in &self.wave {
            self.end[w as usize + 1] += 1;
        }
        for w in 0..waves as usize {
            self.end[w + 1] += self.end[w];
        }
        self.end.pop();
        self.order.clear();
        self.order.resize(contacts.len(), 0);
        for (i, &w) in self.wave.iter().enumerate() {
            let k = &mut self.end[w as usize];
            self.order[*k as usize] = i as u32;
            *k += 1;
        }
    }

    /// Contact indices, wave by wave.
    pub fn order(&self) -> &[u32] {
        &self.order
    }

    /// End (exclusive) of each wave in [`ContactSchedule::order`].
    pub fn wave_ends(&self) -> &[u32] {
        &self.end
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
