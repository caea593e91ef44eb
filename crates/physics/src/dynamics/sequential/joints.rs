//! Joints of the sequential-impulse solver: soft springs, minimum-length ropes and rigid welds,
//! each initialised once per step, swept in the velocity iterations and (ropes, welds) corrected
//! in the position iterations, as dyn4j's DistanceJoint, RopeJoint and WeldJoint are.

use super::island::Joint;
use super::{angle_of, point_velocity, rotate, rotate_about, wrap_angle, Params};
use crate::dynamics::settings::SpringMassModel;
use crate::dynamics::world::{Bodies, BodyState};
use crate::math::Vec2;

/// Below this a mass or a compliance counts as zero (dyn4j's epsilon).
const EPSILON: f64 = f64::EPSILON;

/// 1/x, or 0 where x is (nearly) zero.
#[inline]
fn invert(x: f64) -> f64 {
    if x <= EPSILON {
        0.0
    } else {
        1.0 / x
    }
}

/// Arms of two anchors (given in their bodies' frames) in world orientation, and the unit axis
/// from A's anchor to B's with the distance between them (a zero axis when they nearly coincide).
#[inline]
fn axis(a: &BodyState, b: &BodyState, local_a: Vec2, local_b: Vec2, slop: f64) -> (Vec2, Vec2, Vec2, f64) {
    let (ra, rb) = (a.rot.apply(local_a), b.rot.apply(local_b));
    let d = (b.pos + rb) - (a.pos + ra);
    let length = d.length();
    let n = if length < slop { Vec2::ZERO } else { d / length };
    (ra, rb, n, length)
}

/// Inverse effective mass of two bodies along axis `n` at arms `ra`, `rb`.
#[inline]
fn inverse_mass_along(a: &BodyState, b: &BodyState, ra: Vec2, rb: Vec2, n: Vec2) -> f64 {
    let (rna, rnb) = (ra.cross(n), rb.cross(n));
    a.inv_mass + a.inv_inertia * rna * rna + b.inv_mass + b.inv_inertia * rnb * rnb
}

/// A soft distance constraint between two anchors (a voxel's spring): stiffness and damping
/// follow from a natural frequency and a damping ratio, scaled by a mass chosen by `model`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spring {
    pub a: u32,
    pub b: u32,
    /// Anchors relative to each body's centre of mass, in the body's frame.
    pub local_a: Vec2,
    pub local_b: Vec2,
    pub rest: f64,
    pub omega: f64,
    pub zeta: f64,
    pub model: SpringMassModel,
    ra: Vec2,
    rb: Vec2,
    n: Vec2,
    soft_mass: f64,
    bias: f64,
    gamma: f64,
    impulse: f64,
}

impl Spring {
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        a: u32,
        b: u32,
        local_a: Vec2,
        local_b: Vec2,
        rest: f64,
        frequency: f64,
        zeta: f64,
        model: SpringMassModel,
    ) -> Spring {
        Spring {
            a,
            b,
            local_a,
            local_b,
            rest,
            omega: 2.0 * std::f64::consts::PI * frequency,
            zeta,
            model,
            ra: Vec2::ZERO,
            rb: Vec2::ZERO,
            n: Vec2::ZERO,
            soft_mass: 0.0,
            bias: 0.0,
            gamma: 0.0,
            impulse: 0.0,
        }
    }

    /// k = M·ω², c = 2·M·ζ·ω; γ = 1/(dt·(c + dt·k)); bias = (length − rest)·k/(c + dt·k)
    /// (vsr-model.md §1.4); then last step's impulse is applied again (warm starting).
    fn initialize(&mut self, bodies: &mut Bodies, p: &Params) {
        let (a, b) = (self.a as usize, self.b as usize);
        let (sa, sb) = (&bodies.state[a], &bodies.state[b]);
        let (ra, rb, n, length) = axis(sa, sb, self.local_a, self.local_b, p.linear_slop);
        let inv_mass = inverse_mass_along(sa, sb, ra, rb, n);
        let mass = match self.model {
            SpringMassModel::EffectiveMass => invert(inv_mass),
            SpringMassModel::ReducedMass => reduced_mass(bodies.mass[a], bodies.mass[b]),
        };
        let k = mass * self.omega * self.omega;
        let c = 2.0 * mass * self.zeta * self.omega;
        let dt = p.dt;
        self.gamma = invert(dt * (c + dt * k));
        self.bias = (length - self.rest) * dt * k * self.gamma;
        self.soft_mass = invert(inv_mass + self.gamma);
        (self.ra, self.rb, self.n) = (ra, rb, n);
        if p.warm_starting {
            bodies.apply_impulse_pair(a, b, ra, rb, n * self.impulse);
        } else {
            self.impulse = 0.0;
        }
    }

    fn solve_velocity(&mut self, bodies: &mut Bodies) {
        let (a, b) = (self.a as usize, self.b as usize);
        let rel = point_velocity(&bodies.state[b], self.rb) - point_velocity(&bodies.state[a], self.ra);
        let j = -self.soft_mass * (self.n.dot(rel) + self.bias + self.gamma * self.impulse);
        self.impulse += j;
        bodies.apply_impulse_pair(a, b, self.ra, self.rb, self.n * j);
    }
}

/// m₁·m₂/(m₁+m₂), or the one finite mass when the other body is static.
fn reduced_mass(m1: f64, m2: f64) -> f64 {
    if m1 > 0.0 && m2 > 0.0 {
        m1 * m2 / (m1 + m2)
    } else if m1 > 0.0 {
        m1
    } else {
        m2
    }
}

/// A rope: its anchors may not come closer than `min_length` (the 2021 preset's limit on how far
/// a voxel contracts). Active in a step when the anchors start it closer than that; then rigid,
/// and not clamped to pushing only (as dyn4j 3.3.0's RopeJoint).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rope {
    pub a: u32,
    pub b: u32,
    pub local_a: Vec2,
    pub local_b: Vec2,
    pub min_length: f64,
    active: bool,
    ra: Vec2,
    rb: Vec2,
    n: Vec2,
    mass: f64,
    impulse: f64,
}

impl Rope {
    pub fn new(a: u32, b: u32, local_a: Vec2, local_b: Vec2, min_length: f64) -> Rope {
        Rope {
            a,
            b,
            local_a,
            local_b,
            min_length,
            active: false,
            ra: Vec2::ZERO,
            rb: Vec2::ZERO,
            n: Vec2::ZERO,
            mass: 0.0,
            impulse: 0.0,
        }
    }

    fn initialize(&mut self, bodies: &mut Bodies, p: &Params) {
        let (a, b) = (self.a as usize, self.b as usize);
        let (sa, sb) = (&bodies.state[a], &bodies.state[b]);
        let (ra, rb, n, length) = axis(sa, sb, self.local_a, self.local_b, p.linear_slop);
        self.active = length < self.min_length;
        if !self.active {
            self.impulse = 0.0;
            return;
        }
        self.mass = invert(inverse_mass_along(sa, sb, ra, rb, n));
        (self.ra, self.rb, self.n) = (ra, rb, n);
        if p.warm_starting {
            bodies.apply_impulse_pair(a, b, ra, rb, n * self.impulse);
        } else {
            self.impulse = 0.0;
        }
    }

    fn solve_velocity(&mut self, bodies: &mut Bodies) {
        if !self.active {
            return;
        }
        let (a, b) = (self.a as usize, self.b as usize);
        let rel = point_velocity(&bodies.state[b], self.rb) - point_velocity(&bodies.state[a], self.ra);
        let j = -self.mass * self.n.dot(rel);
        self.impulse += j;
        bodies.apply_impulse_pair(a, b, self.ra, self.rb, self.n * j);
    }

    /// Moves the anchors back towards `min_length` (at most `max_linear_correction`); true when
    /// within `linear_slop`.
    fn solve_position(&mut self, bodies: &mut Bodies, p: &Params) -> bool {
        if !self.active {
            return true;
        }
        let (a, b) = (self.a as usize, self.b as usize);
        let (ra, rb, n, length) = axis(&bodies.state[a], &bodies.state[b], self.local_a, self.local_b, EPSILON);
        let c = (length - self.min_length).clamp(-p.max_linear_correction, p.max_linear_correction);
        let push = n * (-self.mass * c);
        move_apart(bodies, a, b, ra, rb, push);
        self.n = n;
        c.abs() < p.linear_slop
    }
}

/// Position correction `push` applied at arms `ra`, `rb`: B moves by +push/m, A by −push/m, each
/// turned about its centre as it was before the move (dyn4j's order).
#[inline]
fn move_apart(bodies: &mut Bodies, a: usize, b: usize, ra: Vec2, rb: Vec2, push: Vec2) {
    let sa = &mut bodies.state[a];
    let pivot = sa.pos;
    sa.pos -= push * sa.inv_mass;
    let turn = -sa.inv_inertia * ra.cross(push);
    rotate_about(sa, turn, pivot);
    let sb = &mut bodies.state[b];
    let pivot = sb.pos;
    sb.pos += push * sb.inv_mass;
    let turn = sb.inv_inertia * rb.cross(push);
    rotate_about(sb, turn, pivot);
}

/// A rigid weld: B's anchor stays on A's anchor and their relative angle stays at
/// `reference_angle` (solved as one 3×3 block, with full position correction).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Weld {
    pub a: u32,
    pub b: u32,
    pub local_a: Vec2,
    pub local_b: Vec2,
    pub reference_angle: f64,
    ra: Vec2,
    rb: Vec2,
    /// The inverse of the weld's effective-mass matrix at the start of the step (the velocity
    /// sweeps solve with the same matrix every time).
    inv_k: [[f64; 3]; 3],
    impulse: [f64; 3],
}

impl Weld {
    pub fn new(a: u32, b: u32, local_a: Vec2, local_b: Vec2, reference_angle: f64) -> Weld {
        Weld {
            a,
            b,
            local_a,
            local_b,
            reference_angle,
            ra: Vec2::ZERO,
            rb: Vec2::ZERO,
            inv_k: [[0.0; 3]; 3],
            impulse: [0.0; 3],
        }
    }

    fn initialize(&mut self, bodies: &mut Bodies, p: &Params) {
        let (a, b) = (self.a as usize, self.b as usize);
        let (sa, sb) = (&bodies.state[a], &bodies.state[b]);
        self.ra = sa.rot.apply(self.local_a);
        self.rb = sb.rot.apply(self.local_b);
        self.inv_k = block_inverse(&weld_matrix(sa, sb, self.ra, self.rb));
        if p.warm_starting {
            self.apply(bodies, self.impulse);
        } else {
            self.impulse = [0.0; 3];
        }
    }

    /// Adds impulse (x, y) and angular impulse z to A at its anchor, and their opposite to B.
    #[inline]
    fn apply(&self, bodies: &mut Bodies, imp: [f64; 3]) {
        let (a, b) = (self.a as usize, self.b as usize);
        let linear = Vec2::new(imp[0], imp[1]);
        let sa = &mut bodies.state[a];
        sa.vel += linear * sa.inv_mass;
        sa.omega += sa.inv_inertia * (self.ra.cross(linear) + imp[2]);
        let sb = &mut bodies.state[b];
        sb.vel -= linear * sb.inv_mass;
        sb.omega -= sb.inv_inertia * (self.rb.cross(linear) + imp[2]);
    }

    fn solve_velocity(&mut self, bodies: &mut Bodies) {
        let (sa, sb) = (&bodies.state[self.a as usize], &bodies.state[self.b as usize]);
        let rel = point_velocity(sa, self.ra) - point_velocity(sb, self.rb);
        let rhs = [-rel.x, -rel.y, -(sa.omega - sb.omega)];
        let imp = [0, 1, 2].map(|i| self.inv_k[i][0] * rhs[0] + self.inv_k[i][1] * rhs[1] + self.inv_k[i][2] * rhs[2]);
        for (acc, d) in self.impulse.iter_mut().zip(imp) {
            *acc += d;
        }
        self.apply(bodies, imp);
    }

    /// Removes the whole anchor gap and angle drift at once; true when both are within slop.
    fn solve_position(&mut self, bodies: &mut Bodies, p: &Params) -> bool {
        let (a, b) = (self.a as usize, self.b as usize);
        let (sa, sb) = (&bodies.state[a], &bodies.state[b]);
        let (ra, rb) = (sa.rot.apply(self.local_a), sb.rot.apply(self.local_b));
        let gap = (sa.pos + ra) - (sb.pos + rb);
        let drift = wrap_angle(angle_of(sa) - angle_of(sb) - self.reference_angle);
        let k = weld_matrix(sa, sb, ra, rb);
        let imp = block_solve(&k, [-gap.x, -gap.y, -drift]);
        let linear = Vec2::new(imp[0], imp[1]);
        let sa = &mut bodies.state[a];
        sa.pos += linear * sa.inv_mass;
        let turn = sa.inv_inertia * (ra.cross(linear) + imp[2]);
        rotate(sa, turn);
        let sb = &mut bodies.state[b];
        sb.pos -= linear * sb.inv_mass;
        let turn = -sb.inv_inertia * (rb.cross(linear) + imp[2]);
        rotate(sb, turn);
        gap.length() <= p.linear_slop && drift.abs() <= p.angular_slop
    }
}

/// The weld's effective-mass matrix (point constraint in x, y, angle constraint in z).
fn weld_matrix(a: &BodyState, b: &BodyState, ra: Vec2, rb: Vec2) -> [[f64; 3]; 3] {
    let (ma, mb, ia, ib) = (a.inv_mass, b.inv_mass, a.inv_inertia, b.inv_inertia);
    let m00 = ma + mb + ra.y * ra.y * ia + rb.y * rb.y * ib;
    let m01 = -ra.y * ra.x * ia - rb.y * rb.x * ib;
    let m02 = -ra.y * ia - rb.y * ib;
    let m11 = ma + mb + ra.x * ra.x * ia + rb.x * rb.x * ib;
    let m12 = ra.x * ia + rb.x * ib;
    let m22 = ia + ib;
    [[m00, m01, m02], [m01, m11, m12], [m02, m12, m22]]
}

/// Solves K·x = rhs for the weld: all three rows, or only the point rows when neither body
/// can turn (K₂₂ = 0).
fn block_solve(k: &[[f64; 3]; 3], rhs: [f64; 3]) -> [f64; 3] {
    if k[2][2] > 0.0 {
        solve3(k, rhs)
    } else {
        let det = k[0][0] * k[1][1] - k[0][1] * k[1][0];
        let inv = if det != 0.0 { 1.0 / det } else { 0.0 };
        [
            inv * (k[1][1] * rhs[0] - k[0][1] * rhs[1]),
            inv * (k[0][0] * rhs[1] - k[1][0] * rhs[0]),
            0.0,
        ]
    }
}

/// The matrix that [`block_solve`] applies: K⁻¹, or the inverse of its point block when K₂₂ = 0.
fn block_inverse(k: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let columns = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]].map(|e| block_solve(k, e));
    [0, 1, 2].map(|i| [columns[0][i], columns[1][i], columns[2][i]])
}

/// Cramer's rule for a 3×3 system (0 where the matrix is singular).
fn solve3(k: &[[f64; 3]; 3], r: [f64; 3]) -> [f64; 3] {
    let det3 = |c0: [f64; 3], c1: [f64; 3], c2: [f64; 3]| {
        c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c1[0] * (c0[1] * c2[2] - c0[2] * c2[1])
            + c2[0] * (c0[1] * c1[2] - c0[2] * c1[1])
    };
    let col = |j: usize| [k[0][j], k[1][j], k[2][j]];
    let det = det3(col(0), col(1), col(2));
    let inv = if det != 0.0 { 1.0 / det } else { 0.0 };
    [
        inv * det3(r, col(1), col(2)),
        inv * det3(col(0), r, col(2)),
        inv * det3(col(0), col(1), r),
    ]
}

/// Every joint of a world, solved in the order of the step's island walk.
#[derive(Debug, Clone, Default)]
pub(crate) struct Joints {
    pub springs: Vec<Spring>,
    pub ropes: Vec<Rope>,
    pub welds: Vec<Weld>,
}

impl Joints {
    pub fn initialize(&mut self, bodies: &mut Bodies, p: &Params, order: &[Joint]) {
        for &j in order {
            match j {
                Joint::Spring(i) => self.springs[i as usize].initialize(bodies, p),
                Joint::Rope(i) => self.ropes[i as usize].initialize(bodies, p),
                Joint::Weld(i) => self.welds[i as usize].initialize(bodies, p),
            }
        }
    }

    pub fn solve_velocities(&mut self, bodies: &mut Bodies, order: &[Joint]) {
        for &j in order {
            match j {
                Joint::Spring(i) => self.springs[i as usize].solve_velocity(bodies),
                Joint::Rope(i) => self.ropes[i as usize].solve_velocity(bodies),
                Joint::Weld(i) => self.welds[i as usize].solve_velocity(bodies),
            }
        }
    }

    /// One position sweep over ropes and welds (springs have none); true when all are solved.
    pub fn solve_positions(&mut self, bodies: &mut Bodies, p: &Params, order: &[Joint]) -> bool {
        let mut done = true;
        for &j in order {
            match j {
                Joint::Spring(_) => {}
                Joint::Rope(i) => done &= self.ropes[i as usize].solve_position(bodies, p),
                Joint::Weld(i) => done &= self.welds[i as usize].solve_position(bodies, p),
            }
        }
        done
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cramer_solves_a_symmetric_system() {
        let k = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 2.0]];
        let x = [0.3, -1.2, 2.5];
        let r = [0, 1, 2].map(|i| k[i][0] * x[0] + k[i][1] * x[1] + k[i][2] * x[2]);
        let got = solve3(&k, r);
        for i in 0..3 {
            assert!((got[i] - x[i]).abs() < 1e-12, "{got:?} vs {x:?}");
        }
    }

    #[test]
    fn the_block_inverse_solves_like_the_block_solve() {
        let k = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.25], [0.5, 0.25, 2.0]];
        let inv = block_inverse(&k);
        let r = [0.3, -1.2, 2.5];
        let x = block_solve(&k, r);
        for i in 0..3 {
            let y = inv[i][0] * r[0] + inv[i][1] * r[1] + inv[i][2] * r[2];
            assert!((y - x[i]).abs() < 1e-12);
        }
        let flat = [[2.0, 0.5, 0.0], [0.5, 1.0, 0.0], [0.0, 0.0, 0.0]];
        let inv = block_inverse(&flat);
        assert_eq!(inv[2], [0.0, 0.0, 0.0]);
        let x = block_solve(&flat, r);
        assert!((inv[0][0] * r[0] + inv[0][1] * r[1] - x[0]).abs() < 1e-12);
    }

    #[test]
    fn angles_wrap_by_one_turn() {
        use super::super::wrap_angle;
        assert!((wrap_angle(3.5) - (3.5 - std::f64::consts::TAU)).abs() < 1e-15);
        assert!((wrap_angle(-3.5) - (-3.5 + std::f64::consts::TAU)).abs() < 1e-15);
        assert_eq!(wrap_angle(1.0), 1.0);
    }
}
