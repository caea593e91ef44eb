//! Soft distance constraints ("springs"), solved as implicit damped springs, one impulse per
//! sub-step, with stiffness k = M·ω² and damping c = 2·M·ζ·ω taken from the two parts' own masses.
//!
//! The hot data the solver reads every sub-step ([`Spring`], one cache line) is kept apart from
//! the data used once per step to recompute stiffness ([`SpringModel`]).

use super::settings::SpringMassModel;
use super::world::Bodies;
use crate::math::Vec2;

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
    /// The mass M from which stiffness and damping derive, given the current axis `n`.
    #[inline]
    fn mass(&self, bodies: &Bodies, s: &Spring, n: Vec2) -> f64 {
        match self.model {
            SpringMassModel::ReducedMass => self.reduced_mass,
            SpringMassModel::EffectiveMass => {
                let ra = bodies.state[s.a as usize].rot.apply(self.arm_a).cross(n);
                let rb = bodies.state[s.b as usize].rot.apply(self.arm_b).cross(n);
                let k = self.part_inv_mass_a
                    + ra * ra * self.part_inv_inertia_a
                    + self.part_inv_mass_b
                    + rb * rb * self.part_inv_inertia_b;
                1.0 / k
            }
        }
    }
}

/// Recomputes every spring's soft coefficients for sub-step `h` from the current geometry.
pub(crate) fn prepare_springs(springs: &mut [Spring], models: &[SpringModel], bodies: &Bodies, h: f64) {
    for (s, m) in springs.iter_mut().zip(models) {
        let (sa, sb) = (&bodies.state[s.a as usize], &bodies.state[s.b as usize]);
        let d = (sb.pos + sb.rot.apply(s.local_b)) - (sa.pos + sa.rot.apply(s.local_a));
        let n = d.normalize_or_zero();
        let model_mass = m.mass(bodies, s, n);
        let k = model_mass * m.omega * m.omega;
        let c = 2.0 * model_mass * m.zeta * m.omega;
        let denom = c + h * k;
        s.bias_coef = k / denom;
        let gamma = 1.0 / (h * denom);
        let (ra, rb) = (sa.rot.apply(s.local_a), sb.rot.apply(s.local_b));
        let (cra, crb) = (ra.cross(n), rb.cross(n));
        let eff = sa.inv_mass + sb.inv_mass + sa.inv_inertia * cra * cra + sb.inv_inertia * crb * crb;
        s.mass = 1.0 / (eff + gamma);
    }
}

/// Applies one implicit-spring impulse per spring, in order (Gauss–Seidel).
pub(crate) fn solve_springs(springs: &[Spring], bodies: &mut Bodies) {
    for s in springs {
        let (a, b) = (s.a as usize, s.b as usize);
        let (sa, sb) = (bodies.state[a], bodies.state[b]);
        let ra = sa.rot.apply(s.local_a);
        let rb = sb.rot.apply(s.local_b);
        let d = (sb.pos + rb) - (sa.pos + ra);
        let len = d.length();
        if len < 1e-9 {
            continue;
        }
        let n = d / len;
        let bias = (len - s.rest) * s.bias_coef;
        let va = sa.vel + Vec2::cross_scalar_left(sa.omega, ra);
        let vb = sb.vel + Vec2::cross_scalar_left(sb.omega, rb);
        let cdot = n.dot(vb - va);
        let lambda = -(cdot + bias) * s.mass;
        bodies.apply_impulse_pair(a, b, ra, rb, n * lambda);
    }
}
