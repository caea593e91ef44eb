//! Minimum-distance ropes: an inequality constraint that only pushes the anchors apart.

use super::simd::{level, F64x4, Level, Portable, LANES};
use super::soft::Softness;
use super::world::{Bodies, BodyState};
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

/// Ropes of one colour (no two share a body), [`LANES`] at a time, for the slack test of the
/// first sub-step; padding lanes join the static world to itself (length 0).
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(32))]
pub(crate) struct RopeBatch {
    a: [u32; LANES],
    b: [u32; LANES],
    local_ax: [f64; LANES],
    local_ay: [f64; LANES],
    local_bx: [f64; LANES],
    local_by: [f64; LANES],
    min_length: [f64; LANES],
    /// Index of each lane's rope, or `u32::MAX` for padding.
    rope: [u32; LANES],
}

/// Batches `ropes` (grouped by colour; `ranges` gives each colour's index range).
pub(crate) fn rope_batches(ropes: &[Rope], ranges: &[(u32, u32)]) -> Vec<RopeBatch> {
    let mut out = Vec::new();
    for &(lo, hi) in ranges {
        for first in (lo..hi).step_by(LANES) {
            let mut b = RopeBatch {
                rope: [u32::MAX; LANES],
                ..Default::default()
            };
            for (l, i) in (first..hi.min(first + LANES as u32)).enumerate() {
                let r = &ropes[i as usize];
                b.rope[l] = i;
                (b.a[l], b.b[l]) = (r.a, r.b);
                (b.local_ax[l], b.local_ay[l]) = (r.local_a.x, r.local_a.y);
                (b.local_bx[l], b.local_by[l]) = (r.local_b.x, r.local_b.y);
                b.min_length[l] = r.min_length;
            }
            out.push(b);
        }
    }
    out
}

/// Result of the slack test of one rope.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Slack {
    /// Anchors (nearly) coincide: the rope is left alone this sub-step.
    Degenerate,
    /// Too slack to become taut this step.
    Loose,
    /// May act this step.
    Active,
}

/// The slack test of [`solve_ropes`] for the ropes of `b`, lane by lane, with the operations of
/// the one-rope version in the same order (so the same decisions).
///
/// # Safety
/// The batch's body indices must be `< state.len()`.
#[inline(always)]
unsafe fn slack_lanes<V: F64x4>(b: &RopeBatch, state: &[BodyState], dt: f64) -> [Slack; LANES] {
    let ld = V::load;
    // SAFETY: the caller's promise.
    let (pa, pb, va, vb) = unsafe {
        (
            V::gather_pose(state, &b.a),
            V::gather_pose(state, &b.b),
            V::gather_velocity(state, &b.a),
            V::gather_velocity(state, &b.b),
        )
    };
    let (lax, lay, lbx, lby) = (ld(&b.local_ax), ld(&b.local_ay), ld(&b.local_bx), ld(&b.local_by));
    let (rax, ray) = (pa.qc * lax - pa.qs * lay, pa.qs * lax + pa.qc * lay);
    let (rbx, rby) = (pb.qc * lbx - pb.qs * lby, pb.qs * lbx + pb.qc * lby);
    let (dx, dy) = ((pb.px + rbx) - (pa.px + rax), (pb.py + rby) - (pa.py + ray));
    let len = (dx * dx + dy * dy).sqrt();
    let c = len - ld(&b.min_length);
    let (dvx, dvy) = (
        (vb.vx - vb.w * rby) - (va.vx - va.w * ray),
        (vb.vy + vb.w * rbx) - (va.vy + va.w * rax),
    );
    let reach = V::splat(SLACK_MARGIN) + V::splat(2.0 * dt) * (dvx * dvx + dvy * dvy).sqrt();
    let (one, zero) = (V::splat(1.0), V::splat(0.0));
    let mut active = [0.0; LANES];
    reach.select_gt(c, one, zero).store(&mut active);
    let mut degenerate = [0.0; LANES];
    V::splat(1e-9).select_gt(len, one, zero).store(&mut degenerate);
    std::array::from_fn(|l| {
        if degenerate[l] != 0.0 {
            Slack::Degenerate
        } else if active[l] != 0.0 {
            Slack::Active
        } else {
            Slack::Loose
        }
    })
}

/// Solves every rope once; `use_bias` false gives a relaxation pass without position correction.
/// On the first sub-step of a step (`prepare`), ropes far from taut are marked inactive and
/// skipped for the rest of the step; that test runs on `batches` (the same ropes, by colour),
/// several ropes at a time, and only ropes that may act are then solved one by one.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_ropes(
    ropes: &mut [Rope],
    batches: &[RopeBatch],
    bodies: &mut Bodies,
    soft: Softness,
    h: f64,
    dt: f64,
    push_max: f64,
    use_bias: bool,
    prepare: bool,
) {
    if !prepare {
        for r in ropes.iter_mut().filter(|r| r.active) {
            solve_one(r, bodies, soft, h, dt, push_max, use_bias, false);
        }
        return;
    }
    let n = bodies.state.len();
    for batch in batches {
        assert!(batch.a.iter().chain(&batch.b).all(|&i| (i as usize) < n));
        // SAFETY: indices checked just above; `level` checked the CPU features.
        let slack = unsafe {
            match level() {
                #[cfg(target_arch = "x86_64")]
                Level::Avx | Level::Avx512 => slack_avx(batch, &bodies.state, dt),
                _ => slack_lanes::<Portable>(batch, &bodies.state, dt),
            }
        };
        // the ropes of a batch share no body, so solving one does not change another's test
        for (&i, s) in batch.rope.iter().zip(slack) {
            let Some(r) = ropes.get_mut(i as usize) else {
                continue;
            };
            match s {
                Slack::Degenerate => {}
                Slack::Loose => {
                    r.impulse = 0.0;
                    r.active = false;
                }
                Slack::Active => solve_one(r, bodies, soft, h, dt, push_max, use_bias, true),
            }
        }
    }
}

/// [`slack_lanes`] with AVX vectors (the same IEEE operations, so the same decisions).
///
/// # Safety
/// The CPU must support AVX, and the batch's body indices must be `< state.len()`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
unsafe fn slack_avx(b: &RopeBatch, state: &[BodyState], dt: f64) -> [Slack; LANES] {
    // SAFETY: the caller's promise.
    unsafe { slack_lanes::<super::simd::Avx>(b, state, dt) }
}

/// Solves one rope; on the first sub-step of a step (`prepare`), first decides whether it may act
/// during the step.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn solve_one(
    r: &mut Rope,
    bodies: &mut Bodies,
    soft: Softness,
    h: f64,
    dt: f64,
    push_max: f64,
    use_bias: bool,
    prepare: bool,
) {
    {
        let (a, b) = (r.a as usize, r.b as usize);
        let ra = bodies.state[a].rot.apply(r.local_a);
        let rb = bodies.state[b].rot.apply(r.local_b);
        let d = (bodies.state[b].pos + rb) - (bodies.state[a].pos + ra);
        let len = d.length();
        if len < 1e-9 {
            return;
        }
        let c = len - r.min_length;
        let va = bodies.state[a].vel + Vec2::cross_scalar_left(bodies.state[a].omega, ra);
        let vb = bodies.state[b].vel + Vec2::cross_scalar_left(bodies.state[b].omega, rb);
        if prepare {
            r.impulse = 0.0;
            r.active = c < SLACK_MARGIN + 2.0 * dt * (vb - va).length();
            if !r.active {
                return;
            }
        }
        let n = d / len;
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
        let cdot = n.dot(vb - va);
        let delta = -mass_scale * (cdot + bias) / eff - impulse_scale * r.impulse;
        let new = (r.impulse + delta).max(0.0);
        let applied = new - r.impulse;
        r.impulse = new;
        bodies.apply_impulse_pair(a, b, ra, rb, n * applied);
    }
}
