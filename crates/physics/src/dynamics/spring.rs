//! Soft distance constraints ("springs"), solved as implicit damped springs, one impulse per
//! sub-step, with stiffness k = M·ω² and damping c = 2·M·ζ·ω taken from the two parts' own masses.
//!
//! The hot data the solver reads every sub-step ([`Spring`], one cache line) is kept apart from
//! the data used once per step to recompute stiffness ([`SpringModel`]).

use super::settings::SpringMassModel;
use super::world::Bodies;
use crate::math::{Rot, Vec2};

/// Solver data of a spring between anchors on two simulated bodies.
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub(crate) struct Spring {
    pub a: u32,
    pub b: u32,
    /// Anchor relative to body A's centre of mass, in A's frame.
    pub local_a: Vec2,
    pub local_b: Vec2,
    pub rest: f64,
    /// k / (c + h·k), recomputed each step.
    pub bias_coef: f64,
    /// Soft effective mass 1 / (K + γ) with γ = 1 / (h·(c + h·k)), from the step's start geometry.
    pub mass: f64,
    /// γ = 1 / (h·(c + h·k)).
    pub gamma: f64,
    /// Impulse accumulated over the iterations of the current sub-step.
    pub acc: f64,
}

/// What turns a spring's (frequency, damping ratio) into (stiffness, damping).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpringModel {
    /// Anchor relative to the *part's* centre of mass, in body frame (for the effective mass).
    pub arm_a: Vec2,
    pub arm_b: Vec2,
    pub part_inv_mass_a: f64,
    pub part_inv_inertia_a: f64,
    pub part_inv_mass_b: f64,
    pub part_inv_inertia_b: f64,
    pub omega: f64,
    pub zeta: f64,
    pub model: SpringMassModel,
    pub reduced_mass: f64,
}

impl SpringModel {
    /// The mass M from which stiffness and damping derive, given the bodies' rotations and the
    /// current axis `n`.
    #[inline]
    fn mass(&self, rot_a: Rot, rot_b: Rot, n: Vec2) -> f64 {
        match self.model {
            SpringMassModel::ReducedMass => self.reduced_mass,
            SpringMassModel::EffectiveMass => {
                let ra = rot_a.apply(self.arm_a).cross(n);
                let rb = rot_b.apply(self.arm_b).cross(n);
                let k = self.part_inv_mass_a
                    + ra * ra * self.part_inv_inertia_a
                    + self.part_inv_mass_b
                    + rb * rb * self.part_inv_inertia_b;
                1.0 / k
            }
        }
    }
}

/// One Gauss–Seidel iteration over the springs. The first iteration of a sub-step (`first`) resets
/// each spring's accumulated impulse; later iterations include it (the γ·λ term), so that several
/// iterations converge to the implicit solution instead of over-applying the spring. On the first
/// iteration of a step (`prepare`), stiffness, damping and soft effective mass are recomputed from
/// the current geometry, in the same pass.
pub(crate) fn solve_springs(
    springs: &mut [Spring],
    models: &[SpringModel],
    bodies: &mut Bodies,
    h: f64,
    prepare: bool,
    first: bool,
) {
    for (s, m) in springs.iter_mut().zip(models) {
        let (a, b) = (s.a as usize, s.b as usize);
        let (sa, sb) = (bodies.state[a], bodies.state[b]);
        let ra = sa.rot.apply(s.local_a);
        let rb = sb.rot.apply(s.local_b);
        let d = (sb.pos + rb) - (sa.pos + ra);
        let len = d.length().max(1e-12);
        let n = d / len;
        if prepare {
            let model_mass = m.mass(sa.rot, sb.rot, n);
            let k = model_mass * m.omega * m.omega;
            let c = 2.0 * model_mass * m.zeta * m.omega;
            let denom = c + h * k;
            s.bias_coef = k / denom;
            let gamma = 1.0 / (h * denom);
            let (cra, crb) = (ra.cross(n), rb.cross(n));
            let eff = sa.inv_mass + sb.inv_mass + sa.inv_inertia * cra * cra + sb.inv_inertia * crb * crb;
            s.mass = 1.0 / (eff + gamma);
            s.gamma = gamma;
        }
        if first {
            s.acc = 0.0;
        }
        let bias = (len - s.rest) * s.bias_coef + s.gamma * s.acc;
        let va = sa.vel + Vec2::cross_scalar_left(sa.omega, ra);
        let vb = sb.vel + Vec2::cross_scalar_left(sb.omega, rb);
        let cdot = n.dot(vb - va);
        let lambda = -(cdot + bias) * s.mass;
        s.acc += lambda;
        bodies.apply_impulse_pair(a, b, ra, rb, n * lambda);
    }
}
