//! Soft distance constraints ("springs"), solved as implicit damped springs, one impulse per
//! sub-step, with stiffness k = M·ω² and damping c = 2·M·ζ·ω taken from the two parts' own masses.
//!
//! Springs are solved Gauss–Seidel in a fixed order, grouped by colour: within a colour no two
//! springs share a body, so the springs of a colour are independent and are solved [`LANES`] at a
//! time, each quantity stored as an array of [`LANES`] values (structure of arrays) in vector
//! registers. Every lane does exactly the arithmetic of a spring solved alone, so the result is
//! that of solving the springs one by one in order.
//!
//! A sub-step works in two passes. Positions do not change while springs are solved, so
//! [`SpringSet::prepare`] first computes every spring's axis, arms and position error (and, once
//! per step, its stiffness and soft mass): no spring depends on another there. Then
//! [`SpringSet::solve`] runs the Gauss–Seidel sweep over velocities only, a short chain of
//! dependent operations from one colour to the next.

use super::settings::SpringMassModel;
use super::simd::{level, F64x4, Level, Portable, Velocity, LANES};
use super::world::{Bodies, BodyState};
use crate::math::Vec2;

/// A spring between anchors on two simulated bodies, as built (before batching).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spring {
    pub a: u32,
    pub b: u32,
    /// Anchor relative to body A's centre of mass, in A's frame.
    pub local_a: Vec2,
    pub local_b: Vec2,
    pub rest: f64,
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

type Lanes = [f64; LANES];

/// What [`SpringSet::prepare`] reads of [`LANES`] springs of one colour (no two share a body). An
/// inert lane joins the static world to itself with zero mass: it applies a zero impulse to a
/// body that cannot move.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(32))]
pub(crate) struct GeometryBatch {
    a: [u32; LANES],
    b: [u32; LANES],
    /// Anchors relative to the bodies' centres of mass, in body frame.
    local_ax: Lanes,
    local_ay: Lanes,
    local_bx: Lanes,
    local_by: Lanes,
    rest: Lanes,
    /// k / (c + h·k), recomputed each step.
    bias_coef: Lanes,
}

/// What [`SpringSet::solve`] reads and writes of the same springs.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(32))]
pub(crate) struct RowBatch {
    a: [u32; LANES],
    b: [u32; LANES],
    /// Unit axis from anchor A to anchor B, this sub-step.
    nx: Lanes,
    ny: Lanes,
    /// Anchors relative to the bodies' centres of mass, in world orientation, this sub-step.
    rax: Lanes,
    ray: Lanes,
    rbx: Lanes,
    rby: Lanes,
    /// (length − rest)·k/(c + h·k), this sub-step.
    bias: Lanes,
    /// Soft effective mass 1 / (K + γ) with γ = 1 / (h·(c + h·k)), from the step's start geometry.
    mass: Lanes,
    /// γ = 1 / (h·(c + h·k)).
    gamma: Lanes,
    /// Impulse accumulated over the iterations of the current sub-step.
    acc: Lanes,
    /// Inverse masses and inertias of the two bodies (constant).
    inv_mass_a: Lanes,
    inv_mass_b: Lanes,
    inv_inertia_a: Lanes,
    inv_inertia_b: Lanes,
}

/// [`SpringModel`]s of one batch, lane by lane.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(32))]
pub(crate) struct ModelBatch {
    arm_ax: Lanes,
    arm_ay: Lanes,
    arm_bx: Lanes,
    arm_by: Lanes,
    part_inv_mass_a: Lanes,
    part_inv_inertia_a: Lanes,
    part_inv_mass_b: Lanes,
    part_inv_inertia_b: Lanes,
    omega: Lanes,
    zeta: Lanes,
    reduced_mass: Lanes,
    /// 1 where the model is [`SpringMassModel::ReducedMass`], else 0.
    use_reduced: Lanes,
    /// 1 for a spring, 0 for an inert lane.
    active: Lanes,
}

/// The springs of a world, batched by colour (the three vectors are parallel).
#[derive(Debug, Clone, Default)]
pub(crate) struct SpringSet {
    geometry: Vec<GeometryBatch>,
    rows: Vec<RowBatch>,
    models: Vec<ModelBatch>,
    count: usize,
    /// Number of bodies the springs may index (all indices are below it).
    bodies: usize,
}

impl SpringSet {
    /// Batches `springs` (already grouped by colour; `ranges` gives each colour's index range).
    /// Returns the set and, for each spring, its slot (batch · [`LANES`] + lane).
    pub fn new(
        springs: &[Spring],
        models: &[SpringModel],
        ranges: &[(u32, u32)],
        bodies: &Bodies,
    ) -> (SpringSet, Vec<u32>) {
        let mut set = SpringSet {
            count: springs.len(),
            bodies: bodies.len(),
            ..Default::default()
        };
        let mut slots = vec![0u32; springs.len()];
        let inert_spring = Spring {
            a: 0,
            b: 0,
            local_a: Vec2::ZERO,
            local_b: Vec2::ZERO,
            rest: 0.0,
        };
        let inert_model = SpringModel {
            arm_a: Vec2::ZERO,
            arm_b: Vec2::ZERO,
            part_inv_mass_a: 0.0,
            part_inv_inertia_a: 0.0,
            part_inv_mass_b: 0.0,
            part_inv_inertia_b: 0.0,
            omega: 0.0,
            zeta: 0.0,
            model: SpringMassModel::ReducedMass,
            reduced_mass: 0.0,
        };
        for &(lo, hi) in ranges {
            for start in (lo as usize..hi as usize).step_by(LANES) {
                let mut g = GeometryBatch::default();
                let mut r = RowBatch::default();
                let mut mb = ModelBatch::default();
                for l in 0..LANES {
                    let i = start + l;
                    let active = i < hi as usize;
                    let (s, m) = if active {
                        slots[i] = (set.geometry.len() * LANES + l) as u32;
                        (springs[i], models[i])
                    } else {
                        (inert_spring, inert_model)
                    };
                    let (ba, bb) = (&bodies.state[s.a as usize], &bodies.state[s.b as usize]);
                    (g.a[l], g.b[l]) = (s.a, s.b);
                    (g.local_ax[l], g.local_ay[l]) = (s.local_a.x, s.local_a.y);
                    (g.local_bx[l], g.local_by[l]) = (s.local_b.x, s.local_b.y);
                    g.rest[l] = s.rest;
                    (r.a[l], r.b[l]) = (s.a, s.b);
                    (r.inv_mass_a[l], r.inv_inertia_a[l]) = (ba.inv_mass, ba.inv_inertia);
                    (r.inv_mass_b[l], r.inv_inertia_b[l]) = (bb.inv_mass, bb.inv_inertia);
                    (mb.arm_ax[l], mb.arm_ay[l]) = (m.arm_a.x, m.arm_a.y);
                    (mb.arm_bx[l], mb.arm_by[l]) = (m.arm_b.x, m.arm_b.y);
                    mb.part_inv_mass_a[l] = m.part_inv_mass_a;
                    mb.part_inv_inertia_a[l] = m.part_inv_inertia_a;
                    mb.part_inv_mass_b[l] = m.part_inv_mass_b;
                    mb.part_inv_inertia_b[l] = m.part_inv_inertia_b;
                    mb.omega[l] = m.omega;
                    mb.zeta[l] = m.zeta;
                    mb.reduced_mass[l] = m.reduced_mass;
                    mb.use_reduced[l] = f64::from(m.model == SpringMassModel::ReducedMass);
                    mb.active[l] = f64::from(active);
                }
                set.geometry.push(g);
                set.rows.push(r);
                set.models.push(mb);
            }
        }
        (set, slots)
    }

    /// Number of springs (inert lanes excluded).
    pub fn len(&self) -> usize {
        self.count
    }

    /// Rest length of the spring in `slot`.
    pub fn rest(&self, slot: u32) -> f64 {
        self.geometry[slot as usize / LANES].rest[slot as usize % LANES]
    }

    /// Sets the rest length of the spring in `slot`.
    #[inline]
    pub fn set_rest(&mut self, slot: u32, rest: f64) {
        self.geometry[slot as usize / LANES].rest[slot as usize % LANES] = rest;
    }

    /// Computes every spring's axis, arms and position error from the current positions, and
    /// resets its accumulated impulse; on the first sub-step of a step (`step_start`), also
    /// recomputes stiffness, damping and soft effective mass from the current geometry.
    pub fn prepare(&mut self, bodies: &Bodies, h: f64, step_start: bool) {
        // (the AVX-512 build of this code measured slower than the AVX one)
        match level() {
            // SAFETY: `level` checked that the CPU supports AVX.
            #[cfg(target_arch = "x86_64")]
            Level::Avx | Level::Avx512 => unsafe { self.prepare_avx(bodies, h, step_start) },
            _ => self.prepare_with::<Portable>(bodies, h, step_start),
        }
    }

    /// One Gauss–Seidel iteration over the springs (after [`SpringSet::prepare`]). Later
    /// iterations of a sub-step include the accumulated impulse (the γ·λ term), so that several
    /// iterations converge to the implicit solution instead of over-applying the spring.
    pub fn solve(&mut self, bodies: &mut Bodies) {
        match level() {
            // SAFETY: `level` checked that the CPU supports AVX.
            #[cfg(target_arch = "x86_64")]
            Level::Avx | Level::Avx512 => unsafe { self.solve_avx(bodies) },
            _ => self.solve_with::<Portable>(bodies),
        }
    }

    /// [`SpringSet::prepare`] with AVX vectors: the same IEEE operations in the same order (no
    /// fused multiply–add), so bit-identical to the portable version.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    unsafe fn prepare_avx(&mut self, bodies: &Bodies, h: f64, step_start: bool) {
        self.prepare_with::<super::simd::Avx>(bodies, h, step_start);
    }

    /// [`SpringSet::solve`] with AVX vectors (bit-identical, as above).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    unsafe fn solve_avx(&mut self, bodies: &mut Bodies) {
        self.solve_with::<super::simd::Avx>(bodies);
    }

    #[inline(always)]
    fn prepare_with<V: F64x4>(&mut self, bodies: &Bodies, h: f64, step_start: bool) {
        let state = &bodies.state[..];
        // every body index of the batches is below `self.bodies` (and 0 for inert lanes)
        assert!(state.len() >= self.bodies.max(1), "springs built for another world");
        let batches = self.geometry.iter_mut().zip(self.rows.iter_mut());
        // SAFETY (both loops): the batches' body indices are in bounds, asserted above.
        if step_start {
            for ((g, r), m) in batches.zip(&self.models) {
                unsafe { prepare_batch::<V>(g, r, Some(m), state, h) };
            }
        } else {
            for (g, r) in batches {
                unsafe { prepare_batch::<V>(g, r, None, state, h) };
            }
        }
    }

    #[inline(always)]
    fn solve_with<V: F64x4>(&mut self, bodies: &mut Bodies) {
        let state = &mut bodies.state[..];
        assert!(state.len() >= self.bodies.max(1), "springs built for another world");
        for r in &mut self.rows {
            // SAFETY: the batch's body indices are in bounds, asserted above.
            unsafe { solve_batch::<V>(r, state) };
        }
    }
}

/// [`SpringSet::prepare`] for one batch. Every lane performs the operations of `Rot::apply`,
/// `Vec2::length` and the spring model for one spring, in the same order.
///
/// # Safety
/// The batch's body indices must be `< state.len()`.
#[inline(always)]
unsafe fn prepare_batch<V: F64x4>(
    g: &mut GeometryBatch,
    r: &mut RowBatch,
    model: Option<&ModelBatch>,
    state: &[BodyState],
    h: f64,
) {
    // SAFETY: the caller's promise.
    let (sa, sb) = unsafe { (V::gather_pose(state, &g.a), V::gather_pose(state, &g.b)) };
    let ld = V::load;
    let (lax, lay, lbx, lby) = (ld(&g.local_ax), ld(&g.local_ay), ld(&g.local_bx), ld(&g.local_by));
    let rax = sa.qc * lax - sa.qs * lay;
    let ray = sa.qs * lax + sa.qc * lay;
    let rbx = sb.qc * lbx - sb.qs * lby;
    let rby = sb.qs * lbx + sb.qc * lby;
    let dx = (sb.px + rbx) - (sa.px + rax);
    let dy = (sb.py + rby) - (sa.py + ray);
    let len = (dx * dx + dy * dy).sqrt();
    // len.max(1e-12) (NaN gives 1e-12 either way)
    let tiny = V::splat(1e-12);
    let len = len.max(tiny);
    let (nx, ny) = (dx / len, dy / len);
    if let Some(m) = model {
        // model mass M (effective mass of the two parts along n, or their reduced mass), then
        // k = M·ω², c = 2·M·ζ·ω and the soft coefficients
        let (arm_ax, arm_ay, arm_bx, arm_by) = (ld(&m.arm_ax), ld(&m.arm_ay), ld(&m.arm_bx), ld(&m.arm_by));
        let (ax, ay) = (sa.qc * arm_ax - sa.qs * arm_ay, sa.qs * arm_ax + sa.qc * arm_ay);
        let (bx, by) = (sb.qc * arm_bx - sb.qs * arm_by, sb.qs * arm_bx + sb.qc * arm_by);
        let ca = ax * ny - ay * nx;
        let cb = bx * ny - by * nx;
        let inv_k = ld(&m.part_inv_mass_a)
            + ca * ca * ld(&m.part_inv_inertia_a)
            + ld(&m.part_inv_mass_b)
            + cb * cb * ld(&m.part_inv_inertia_b);
        let (one, half, zero) = (V::splat(1.0), V::splat(0.5), V::splat(0.0));
        let effective = one / inv_k;
        let model_mass = ld(&m.use_reduced).select_gt(half, ld(&m.reduced_mass), effective);
        let (omega, hv) = (ld(&m.omega), V::splat(h));
        let k = model_mass * omega * omega;
        let c = V::splat(2.0) * model_mass * ld(&m.zeta) * omega;
        let denom = c + hv * k;
        let cra = rax * ny - ray * nx;
        let crb = rbx * ny - rby * nx;
        let (ima, imb) = (ld(&r.inv_mass_a), ld(&r.inv_mass_b));
        let (iia, iib) = (ld(&r.inv_inertia_a), ld(&r.inv_inertia_b));
        let eff = ima + imb + iia * cra * cra + iib * crb * crb;
        let bias_coef = k / denom;
        let gamma = one / (hv * denom);
        let mass = one / (eff + gamma);
        let active = ld(&m.active);
        active.select_gt(half, bias_coef, zero).store(&mut g.bias_coef);
        active.select_gt(half, gamma, zero).store(&mut r.gamma);
        active.select_gt(half, mass, zero).store(&mut r.mass);
    }
    nx.store(&mut r.nx);
    ny.store(&mut r.ny);
    rax.store(&mut r.rax);
    ray.store(&mut r.ray);
    rbx.store(&mut r.rbx);
    rby.store(&mut r.rby);
    ((len - ld(&g.rest)) * ld(&g.bias_coef)).store(&mut r.bias);
    r.acc = [0.0; LANES];
}

/// [`SpringSet::solve`] for one batch. Every lane performs the operations of
/// `Vec2::cross_scalar_left` and `Bodies::apply_impulse_pair` for one spring, in the same order
/// (a + (−x·y) is written a − x·y, which is the same number).
///
/// # Safety
/// The batch's body indices must be `< state.len()`.
#[inline(always)]
unsafe fn solve_batch<V: F64x4>(r: &mut RowBatch, state: &mut [BodyState]) {
    // SAFETY: the caller's promise.
    let (sa, sb) = unsafe { (V::gather_velocity(state, &r.a), V::gather_velocity(state, &r.b)) };
    let ld = V::load;
    let (nx, ny) = (ld(&r.nx), ld(&r.ny));
    let (rax, ray, rbx, rby) = (ld(&r.rax), ld(&r.ray), ld(&r.rbx), ld(&r.rby));
    let acc = ld(&r.acc);
    let bias = ld(&r.bias) + ld(&r.gamma) * acc;
    let (va_x, va_y) = (sa.vx - sa.w * ray, sa.vy + sa.w * rax);
    let (vb_x, vb_y) = (sb.vx - sb.w * rby, sb.vy + sb.w * rbx);
    let cdot = nx * (vb_x - va_x) + ny * (vb_y - va_y);
    let lambda = -(cdot + bias) * ld(&r.mass);
    (acc + lambda).store(&mut r.acc);
    let (px, py) = (nx * lambda, ny * lambda);
    let (ima, iia) = (ld(&r.inv_mass_a), ld(&r.inv_inertia_a));
    let (imb, iib) = (ld(&r.inv_mass_b), ld(&r.inv_inertia_b));
    let va = Velocity {
        vx: sa.vx - px * ima,
        vy: sa.vy - py * ima,
        w: sa.w - iia * (rax * py - ray * px),
        ..sa
    };
    let vb = Velocity {
        vx: sb.vx + px * imb,
        vy: sb.vy + py * imb,
        w: sb.w + iib * (rbx * py - rby * px),
        ..sb
    };
    // SAFETY: the caller's promise.
    unsafe {
        V::scatter_velocity(state, &r.a, va);
        V::scatter_velocity(state, &r.b, vb);
    }
}
