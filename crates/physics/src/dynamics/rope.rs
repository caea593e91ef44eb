//! Minimum-distance ropes: an inequality constraint that only pushes the anchors apart.

use super::soft::Softness;
use super::world::Bodies;
use crate::math::Vec2;

/// A rope between anchors on two simulated bodies.
#[derive(Debug, Clone)]
pub(crate) struct Rope {
    pub a: u32,
    pub b: u32,
    pub local_a: Vec2,
    pub local_b: Vec2,
    pub min_length: f64,
    /// Impulse accumulated within the current step (≥ 0).
    pub impulse: f64,
    /// Whether the rope may act during the current step (decided on its first sub-step).
    pub active: bool,
}

/// A rope is skipped for a step when its slack exceeds this plus twice the distance its anchors
/// could close in one step at their current relative speed: it cannot become taut within the step.
const SLACK_MARGIN: f64 = 0.05;

/// Solves every rope once; `use_bias` false gives a relaxation pass without position correction.
/// On the first sub-step of a step (`prepare`), ropes far from taut are marked inactive and
/// skipped for the rest of the step.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_ropes(
    ropes: &mut [Rope],
    bodies: &mut Bodies,
    soft: Softness,
    h: f64,
    dt: f64,
    push_max: f64,
    use_bias: bool,
    prepare: bool,
) {
    for r in ropes {
        if !prepare && !r.active {
            continue;
        }
        let (a, b) = (r.a as usize, r.b as usize);
        let ra = bodies.state[a].rot.apply(r.local_a);
        let rb = bodies.state[b].rot.apply(r.local_b);
        let d = (bodies.state[b].pos + rb) - (bodies.state[a].pos + ra);
        let len = d.length();
        if len < 1e-9 {
            continue;
        }
        let n = d / len;
        let c = len - r.min_length;
        let (bias, mass_scale, impulse_scale) = if c > 0.0 {
            (c / h, 1.0, 0.0)
        } else if use_bias {
            ((soft.bias_rate * c).max(-push_max), soft.mass_scale, soft.impulse_scale)
        } else {
            (0.0, 1.0, 0.0)
        };
        let (cra, crb) = (ra.cross(n), rb.cross(n));
        let eff = bodies.state[a].inv_mass
            + bodies.state[b].inv_mass
            + bodies.state[a].inv_inertia * cra * cra
            + bodies.state[b].inv_inertia * crb * crb;
        let va = bodies.state[a].vel + Vec2::cross_scalar_left(bodies.state[a].omega, ra);
        let vb = bodies.state[b].vel + Vec2::cross_scalar_left(bodies.state[b].omega, rb);
        if prepare {
            r.impulse = 0.0;
            r.active = c < SLACK_MARGIN + 2.0 * dt * (vb - va).length();
            if !r.active {
                continue;
            }
        }
        let cdot = n.dot(vb - va);
        let delta = -mass_scale * (cdot + bias) / eff - impulse_scale * r.impulse;
        let new = (r.impulse + delta).max(0.0);
        let applied = new - r.impulse;
        r.impulse = new;
        bodies.apply_impulse_pair(a, b, ra, rb, n * applied);
    }
}
