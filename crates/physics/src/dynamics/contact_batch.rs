//! The contact solver, [`LANES`] contacts at a time.
//!
//! [`schedule_contacts`](super::contact::schedule_contacts) orders the contacts in waves whose
//! contacts touch different moving bodies. Here each wave is cut into batches of [`LANES`]
//! contacts stored lane by lane (structure of arrays), and each batch is solved with vector
//! instructions: every lane performs exactly the operations a one-by-one sweep would perform for its
//! contact (normal impulses of its points, then friction), so the result is that of such a sweep.
//! Lanes past a contact's point count, and padding lanes, compute but keep their old values.

use super::contact::{ContactConstraint, ContactPass, ContactPoint, ContactSchedule};
use super::simd::{level, F64x4, Level, Portable, Pose, Velocity, LANES};
use super::world::{Bodies, BodyState};

type Lanes = [f64; LANES];

/// One contact point of [`LANES`] contacts (see [`super::contact::ContactPoint`]).
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(32))]
struct PointLanes {
    local_ax: Lanes,
    local_ay: Lanes,
    local_bx: Lanes,
    local_by: Lanes,
    rax: Lanes,
    ray: Lanes,
    rbx: Lanes,
    rby: Lanes,
    base_separation: Lanes,
    normal_mass: Lanes,
    tangent_mass: Lanes,
    normal_impulse: Lanes,
    tangent_impulse: Lanes,
    max_normal_impulse: Lanes,
    /// 1 where the contact has this point, else 0.
    active: Lanes,
}

impl PointLanes {
    /// Puts point `p` in lane `l`.
    #[inline]
    fn set_lane(&mut self, l: usize, p: &ContactPoint, active: bool) {
        (self.local_ax[l], self.local_ay[l]) = (p.local_a.x, p.local_a.y);
        (self.local_bx[l], self.local_by[l]) = (p.local_b.x, p.local_b.y);
        (self.rax[l], self.ray[l]) = (p.ra.x, p.ra.y);
        (self.rbx[l], self.rby[l]) = (p.rb.x, p.rb.y);
        self.base_separation[l] = p.base_separation;
        self.normal_mass[l] = p.normal_mass;
        self.tangent_mass[l] = p.tangent_mass;
        self.normal_impulse[l] = p.normal_impulse;
        self.tangent_impulse[l] = p.tangent_impulse;
        self.max_normal_impulse[l] = p.max_normal_impulse;
        self.active[l] = f64::from(active);
    }
}

/// [`LANES`] contacts of one wave.
#[derive(Debug, Clone, Copy, Default)]
#[repr(C, align(32))]
struct ContactLanes {
    a: [u32; LANES],
    b: [u32; LANES],
    nx: Lanes,
    ny: Lanes,
    friction: Lanes,
    /// 1 where the contact uses the static softness, else 0.
    static_soft: Lanes,
    inv_mass_a: Lanes,
    inv_mass_b: Lanes,
    inv_inertia_a: Lanes,
    inv_inertia_b: Lanes,
    points: [PointLanes; 2],
    /// Index of each lane's contact, or `u32::MAX` for padding.
    contact: [u32; LANES],
}

/// The contacts of a step, batched; reused from step to step (no allocation once warm).
#[derive(Debug, Clone, Default)]
pub(crate) struct ContactBatches {
    batches: Vec<ContactLanes>,
    /// Number of bodies the batches may index (all indices are below it).
    bodies: usize,
}

impl ContactBatches {
    /// Batches `contacts` in the order of `schedule`.
    pub fn build(&mut self, contacts: &[ContactConstraint], schedule: &ContactSchedule, bodies: &Bodies) {
        self.bodies = bodies.len();
        let order = schedule.order();
        let mut n = 0;
        let mut start = 0;
        for &end in schedule.wave_ends() {
            n += (end as usize - start).div_ceil(LANES);
            start = end as usize;
        }
        // reuse the batches of earlier steps: every lane is overwritten below
        self.batches.resize(n, ContactLanes::default());
        let mut batches = self.batches.iter_mut();
        let mut start = 0;
        for &end in schedule.wave_ends() {
            for first in (start..end as usize).step_by(LANES) {
                let b = batches.next().expect("batch count computed above");
                for l in 0..LANES {
                    let i = first + l;
                    let c = (i < end as usize).then(|| &contacts[order[i] as usize]);
                    let Some(c) = c else {
                        // padding: the static world with itself, no points, all zero
                        b.contact[l] = u32::MAX;
                        (b.a[l], b.b[l]) = (0, 0);
                        for x in [
                            &mut b.nx,
                            &mut b.ny,
                            &mut b.friction,
                            &mut b.static_soft,
                            &mut b.inv_mass_a,
                            &mut b.inv_mass_b,
                            &mut b.inv_inertia_a,
                            &mut b.inv_inertia_b,
                        ] {
                            x[l] = 0.0;
                        }
                        for q in &mut b.points {
                            q.set_lane(l, &ContactPoint::default(), false);
                        }
                        continue;
                    };
                    let (sa, sb) = (&bodies.state[c.a as usize], &bodies.state[c.b as usize]);
                    b.contact[l] = order[i];
                    (b.a[l], b.b[l]) = (c.a, c.b);
                    (b.nx[l], b.ny[l]) = (c.normal.x, c.normal.y);
                    b.friction[l] = c.friction;
                    b.static_soft[l] = f64::from(c.shape_b == u32::MAX);
                    (b.inv_mass_a[l], b.inv_inertia_a[l]) = (sa.inv_mass, sa.inv_inertia);
                    (b.inv_mass_b[l], b.inv_inertia_b[l]) = (sb.inv_mass, sb.inv_inertia);
                    for (k, q) in b.points.iter_mut().enumerate() {
                        q.set_lane(l, &c.points[k], k < c.count);
                    }
                }
            }
            start = end as usize;
        }
    }

    /// Copies the accumulated impulses back into `contacts` (for restitution).
    pub fn write_back(&self, contacts: &mut [ContactConstraint]) {
        for b in &self.batches {
            for l in 0..LANES {
                let Some(c) = contacts.get_mut(b.contact[l] as usize) else {
                    continue;
                };
                for (k, q) in b.points.iter().enumerate() {
                    let p = &mut c.points[k];
                    p.normal_impulse = q.normal_impulse[l];
                    p.tangent_impulse = q.tangent_impulse[l];
                    p.max_normal_impulse = q.max_normal_impulse[l];
                }
            }
        }
    }

    /// Solves every contact once (normal then friction per point), wave by wave.
    pub fn solve(&mut self, bodies: &mut Bodies, pass: &ContactPass) {
        match level() {
            // SAFETY: `level` checked that the CPU supports these features.
            #[cfg(target_arch = "x86_64")]
            Level::Avx512 => unsafe { self.solve_avx512(bodies, pass) },
            #[cfg(target_arch = "x86_64")]
            Level::Avx => unsafe { self.solve_avx(bodies, pass) },
            _ => self.solve_with::<Portable>(bodies, pass),
        }
    }

    /// [`ContactBatches::solve_avx`] compiled with AVX-512 available (see
    /// [`Level::Avx512`](super::simd::Level::Avx512)).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,avx512f,avx512vl")]
    #[inline(never)]
    unsafe fn solve_avx512(&mut self, bodies: &mut Bodies, pass: &ContactPass) {
        self.solve_with::<super::simd::Avx>(bodies, pass);
    }

    /// [`ContactBatches::solve`] with AVX vectors: the same IEEE operations in the same order (no
    /// fused multiply–add), so bit-identical to the portable version.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx")]
    #[inline(never)]
    unsafe fn solve_avx(&mut self, bodies: &mut Bodies, pass: &ContactPass) {
        self.solve_with::<super::simd::Avx>(bodies, pass);
    }

    #[inline(always)]
    fn solve_with<V: F64x4>(&mut self, bodies: &mut Bodies, pass: &ContactPass) {
        let state = &mut bodies.state[..];
        // every body index of the batches is below `self.bodies` (and 0 for padding lanes)
        assert!(state.len() >= self.bodies.max(1), "contacts built for another world");
        // SAFETY (both loops): the batches' body indices are in bounds, asserted above.
        if pass.use_bias {
            for b in &mut self.batches {
                unsafe { solve_batch::<V, true>(b, state, pass) };
            }
        } else {
            for b in &mut self.batches {
                unsafe { solve_batch::<V, false>(b, state, pass) };
            }
        }
    }
}

/// Velocities of the two bodies of each lane, updated impulse by impulse.
struct Motion<V> {
    vax: V,
    vay: V,
    wa: V,
    vbx: V,
    vby: V,
    wb: V,
}

impl<V: F64x4> Motion<V> {
    /// Relative velocity of anchor B with respect to anchor A (`vb − va` with
    /// `v = vel + ω × r`; `x + (−w·y)` is written `x − w·y`, the same number).
    #[inline(always)]
    fn relative(&self, q: &PointLanes) -> (V, V) {
        let ld = V::load;
        let (rax, ray, rbx, rby) = (ld(&q.rax), ld(&q.ray), ld(&q.rbx), ld(&q.rby));
        let (va_x, va_y) = (self.vax - self.wa * ray, self.vay + self.wa * rax);
        let (vb_x, vb_y) = (self.vbx - self.wb * rby, self.vby + self.wb * rbx);
        (vb_x - va_x, vb_y - va_y)
    }

    /// Applies impulse (px, py) at the anchors of point `q` (as `Bodies::apply_impulse_pair`), in
    /// the lanes where `active` > 0.5 only; `inv` holds the inverse masses and inertias of A and B.
    #[inline(always)]
    fn apply(&mut self, inv: [V; 4], q: &PointLanes, px: V, py: V, active: V) {
        let ld = V::load;
        let half = V::splat(0.5);
        let (rax, ray, rbx, rby) = (ld(&q.rax), ld(&q.ray), ld(&q.rbx), ld(&q.rby));
        let [ima, iia, imb, iib] = inv;
        self.vax = active.select_gt(half, self.vax - px * ima, self.vax);
        self.vay = active.select_gt(half, self.vay - py * ima, self.vay);
        self.wa = active.select_gt(half, self.wa - iia * (rax * py - ray * px), self.wa);
        self.vbx = active.select_gt(half, self.vbx + px * imb, self.vbx);
        self.vby = active.select_gt(half, self.vby + py * imb, self.vby);
        self.wb = active.select_gt(half, self.wb + iib * (rbx * py - rby * px), self.wb);
    }
}

/// Current separation of point `q` (as `ContactConstraint::separation`).
#[inline(always)]
fn separation<V: F64x4>(q: &PointLanes, pa: &Pose<V>, pb: &Pose<V>, nx: V, ny: V) -> V {
    let ld = V::load;
    let (lax, lay, lbx, lby) = (ld(&q.local_ax), ld(&q.local_ay), ld(&q.local_bx), ld(&q.local_by));
    let (ax, ay) = (pa.px + (pa.qc * lax - pa.qs * lay), pa.py + (pa.qs * lax + pa.qc * lay));
    let (bx, by) = (pb.px + (pb.qc * lbx - pb.qs * lby), pb.py + (pb.qs * lbx + pb.qc * lby));
    ld(&q.base_separation) + (nx * (bx - ax) + ny * (by - ay))
}

/// One pass over the contacts of a batch (normal impulses, then friction).
///
/// # Safety
/// The batch's body indices must be `< state.len()`.
#[inline(always)]
unsafe fn solve_batch<V: F64x4, const USE_BIAS: bool>(
    b: &mut ContactLanes,
    state: &mut [BodyState],
    pass: &ContactPass,
) {
    let ld = V::load;
    let (ia, ib) = (b.a, b.b);
    let (half, zero, one) = (V::splat(0.5), V::splat(0.0), V::splat(1.0));
    let (nx, ny) = (ld(&b.nx), ld(&b.ny));
    // separations from the current positions, which this pass does not change
    // SAFETY: the caller's promise.
    let (pa, pb) = unsafe { (V::gather_pose(state, &ia), V::gather_pose(state, &ib)) };
    let sep = [
        separation(&b.points[0], &pa, &pb, nx, ny),
        separation(&b.points[1], &pa, &pb, nx, ny),
    ];
    let is_static = ld(&b.static_soft);
    let (st, dy) = (&pass.static_soft, &pass.soft);
    let bias_rate = is_static.select_gt(half, V::splat(st.bias_rate), V::splat(dy.bias_rate));
    let mass_scale = is_static.select_gt(half, V::splat(st.mass_scale), V::splat(dy.mass_scale));
    let impulse_scale = is_static.select_gt(half, V::splat(st.impulse_scale), V::splat(dy.impulse_scale));
    let (inv_h, neg_push_max) = (V::splat(pass.inv_h), V::splat(-pass.push_max));
    let inv = [
        ld(&b.inv_mass_a),
        ld(&b.inv_inertia_a),
        ld(&b.inv_mass_b),
        ld(&b.inv_inertia_b),
    ];
    // SAFETY: the caller's promise.
    let (va, vb) = unsafe { (V::gather_velocity(state, &ia), V::gather_velocity(state, &ib)) };
    let mut m = Motion {
        vax: va.vx,
        vay: va.vy,
        wa: va.w,
        vbx: vb.vx,
        vby: vb.vy,
        wb: vb.w,
    };
    for (q, &s) in b.points.iter_mut().zip(&sep) {
        let active = ld(&q.active);
        // speculative (s > 0): remove the gap in one sub-step; overlapping: soft push-out in the
        // biased pass, plain velocity constraint in the relax pass
        let (mut bias, mut ms, mut is) = (zero, one, zero);
        if USE_BIAS {
            let push = bias_rate * s;
            bias = push.max(neg_push_max);
            (ms, is) = (mass_scale, impulse_scale);
        }
        let bias = s.select_gt(zero, s * inv_h, bias);
        let ms = s.select_gt(zero, one, ms);
        let is = s.select_gt(zero, zero, is);
        let (dvx, dvy) = m.relative(q);
        let vn = nx * dvx + ny * dvy;
        let old = ld(&q.normal_impulse);
        let delta = -ld(&q.normal_mass) * ms * (vn + bias) - is * old;
        let sum = old + delta;
        let new = sum.max(zero);
        let applied = new - old;
        active.select_gt(half, new, old).store(&mut q.normal_impulse);
        let max_old = ld(&q.max_normal_impulse);
        let max_new = applied.max(max_old);
        active
            .select_gt(half, max_new, max_old)
            .store(&mut q.max_normal_impulse);
        m.apply(inv, q, nx * applied, ny * applied, active);
    }
    // friction along t = n.perp() = (−n.y, n.x), bounded by μ times the normal impulse
    let (tx, ty) = (-ny, nx);
    let friction = ld(&b.friction);
    for q in b.points.iter_mut() {
        let active = ld(&q.active);
        let (dvx, dvy) = m.relative(q);
        let vt = tx * dvx + ty * dvy;
        let max_f = friction * ld(&q.normal_impulse);
        let old = ld(&q.tangent_impulse);
        let x = old - ld(&q.tangent_mass) * vt;
        // x.clamp(−max_f, max_f)
        let min_f = -max_f;
        let new = max_f.min(min_f.max(x));
        let applied = new - old;
        active.select_gt(half, new, old).store(&mut q.tangent_impulse);
        m.apply(inv, q, tx * applied, ty * applied, active);
    }
    let va = Velocity {
        vx: m.vax,
        vy: m.vay,
        w: m.wa,
        ..va
    };
    let vb = Velocity {
        vx: m.vbx,
        vy: m.vby,
        w: m.wb,
        ..vb
    };
    // SAFETY: the caller's promise.
    unsafe {
        V::scatter_velocity(state, &ia, va);
        V::scatter_velocity(state, &ib, vb);
    }
}
