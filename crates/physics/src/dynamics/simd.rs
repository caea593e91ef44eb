//! Four f64 lanes for the spring solver: a portable implementation (plain arrays) and, on x86-64,
//! an AVX one selected at run time. Both perform the same IEEE-754 operations lane by lane (no
//! fused multiply–add, no approximations), so they give bit-identical results.

use super::world::BodyState;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Number of lanes.
pub(crate) const LANES: usize = 4;

/// Which compiled version of the vectorised solvers this CPU can run (detected at run time; every
/// version gives bit-identical results).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Level {
    /// Plain arrays, for any CPU.
    Portable,
    /// AVX, four f64 per instruction.
    Avx,
    /// The AVX code compiled with AVX-512F/VL available: the same four-lane operations, with
    /// twice the vector registers and mask registers for the selects.
    Avx512,
}

/// The best [`Level`] this CPU supports (the standard library caches the detection).
#[inline]
pub(crate) fn level() -> Level {
    #[cfg(test)]
    if FORCE_PORTABLE.with(|f| f.get()) {
        return Level::Portable;
    }
    #[cfg(target_arch = "x86_64")]
    {
        if is_x86_feature_detected!("avx512f") && is_x86_feature_detected!("avx512vl") {
            return Level::Avx512;
        }
        if is_x86_feature_detected!("avx") {
            return Level::Avx;
        }
    }
    Level::Portable
}

#[cfg(test)]
thread_local! {
    /// Tests set this to run the portable version on this thread and compare bits.
    pub(crate) static FORCE_PORTABLE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Four f64 values processed together.
pub(crate) trait F64x4:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    fn splat(x: f64) -> Self;
    fn load(x: &[f64; LANES]) -> Self;
    fn store(self, out: &mut [f64; LANES]);
    fn sqrt(self) -> Self;
    /// Lane by lane: `if self > other { then } else { otherwise }` (false when either is NaN).
    fn select_gt(self, other: Self, then: Self, otherwise: Self) -> Self;
    /// Lane by lane: `if self > other { self } else { other }` (`other` when either is NaN, and
    /// for two zeros).
    fn max(self, other: Self) -> Self;
    /// Lane by lane: `if self < other { self } else { other }` (`other` when either is NaN, and
    /// for two zeros).
    fn min(self, other: Self) -> Self;
    /// Position and rotation of bodies `index`.
    ///
    /// # Safety
    /// Every index must be `< state.len()`.
    unsafe fn gather_pose(state: &[BodyState], index: &[u32; LANES]) -> Pose<Self>;
    /// Velocity of bodies `index`.
    ///
    /// # Safety
    /// Every index must be `< state.len()`.
    unsafe fn gather_velocity(state: &[BodyState], index: &[u32; LANES]) -> Velocity<Self>;
    /// Writes the velocity of bodies `index` (no two equal unless they get equal values);
    /// `v.inv_mass` must be what [`F64x4::gather_velocity`] read.
    ///
    /// # Safety
    /// Every index must be `< state.len()`.
    unsafe fn scatter_velocity(state: &mut [BodyState], index: &[u32; LANES], v: Velocity<Self>);
}

/// Position and rotation of four bodies.
#[derive(Clone, Copy)]
pub(crate) struct Pose<V> {
    pub px: V,
    pub py: V,
    pub qc: V,
    pub qs: V,
}

/// Linear and angular velocity of four bodies, and their inverse mass (which sits next to the
/// angular velocity: writing both back as one 16-byte store lets a later load of the pair take
/// them straight from the store buffer).
#[derive(Clone, Copy)]
pub(crate) struct Velocity<V> {
    pub vx: V,
    pub vy: V,
    pub w: V,
    pub inv_mass: V,
}

/// Portable lanes: plain arrays, one scalar operation per lane.
#[derive(Clone, Copy)]
pub(crate) struct Portable([f64; LANES]);

macro_rules! portable_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for Portable {
            type Output = Portable;
            #[inline(always)]
            fn $f(self, o: Portable) -> Portable {
                Portable(std::array::from_fn(|l| self.0[l] $op o.0[l]))
            }
        }
    };
}
portable_op!(Add, add, +);
portable_op!(Sub, sub, -);
portable_op!(Mul, mul, *);
portable_op!(Div, div, /);

impl Neg for Portable {
    type Output = Portable;
    #[inline(always)]
    fn neg(self) -> Portable {
        Portable(self.0.map(|x| -x))
    }
}

impl F64x4 for Portable {
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Portable([x; LANES])
    }
    #[inline(always)]
    fn load(x: &[f64; LANES]) -> Self {
        Portable(*x)
    }
    #[inline(always)]
    fn store(self, out: &mut [f64; LANES]) {
        *out = self.0;
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        Portable(self.0.map(f64::sqrt))
    }
    #[inline(always)]
    fn select_gt(self, other: Self, then: Self, otherwise: Self) -> Self {
        Portable(std::array::from_fn(|l| {
            if self.0[l] > other.0[l] {
                then.0[l]
            } else {
                otherwise.0[l]
            }
        }))
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        Portable(std::array::from_fn(|l| {
            if self.0[l] > other.0[l] {
                self.0[l]
            } else {
                other.0[l]
            }
        }))
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        Portable(std::array::from_fn(|l| {
            if self.0[l] < other.0[l] {
                self.0[l]
            } else {
                other.0[l]
            }
        }))
    }
    #[inline(always)]
    unsafe fn gather_pose(state: &[BodyState], index: &[u32; LANES]) -> Pose<Self> {
        let s = index.map(|i| &state[i as usize]);
        Pose {
            px: Portable(s.map(|b| b.pos.x)),
            py: Portable(s.map(|b| b.pos.y)),
            qc: Portable(s.map(|b| b.rot.c)),
            qs: Portable(s.map(|b| b.rot.s)),
        }
    }
    #[inline(always)]
    unsafe fn gather_velocity(state: &[BodyState], index: &[u32; LANES]) -> Velocity<Self> {
        let s = index.map(|i| &state[i as usize]);
        Velocity {
            vx: Portable(s.map(|b| b.vel.x)),
            vy: Portable(s.map(|b| b.vel.y)),
            w: Portable(s.map(|b| b.omega)),
            inv_mass: Portable(s.map(|b| b.inv_mass)),
        }
    }
    #[inline(always)]
    unsafe fn scatter_velocity(state: &mut [BodyState], index: &[u32; LANES], v: Velocity<Self>) {
        for l in 0..LANES {
            let s = &mut state[index[l] as usize];
            s.vel.x = v.vx.0[l];
            s.vel.y = v.vy.0[l];
            s.omega = v.w.0[l];
        }
    }
}

#[cfg(target_arch = "x86_64")]
pub(crate) use avx::Avx;

#[cfg(target_arch = "x86_64")]
mod avx {
    //! AVX lanes. A value of [`Avx`] only exists inside code that runs after
    //! `is_x86_feature_detected!("avx")` said yes (the spring solver's AVX entry point), and all
    //! of its methods are inlined into that `#[target_feature(enable = "avx")]` function.

    use super::{F64x4, Pose, Velocity, LANES};
    use crate::dynamics::world::BodyState;
    use std::arch::x86_64::*;
    use std::ops::{Add, Div, Mul, Neg, Sub};

    #[derive(Clone, Copy)]
    pub(crate) struct Avx(__m256d);

    macro_rules! avx_op {
        ($tr:ident, $f:ident, $intr:ident) => {
            impl $tr for Avx {
                type Output = Avx;
                #[inline(always)]
                fn $f(self, o: Avx) -> Avx {
                    // SAFETY: `Avx` values exist only where AVX is available (module docs).
                    Avx(unsafe { $intr(self.0, o.0) })
                }
            }
        };
    }
    avx_op!(Add, add, _mm256_add_pd);
    avx_op!(Sub, sub, _mm256_sub_pd);
    avx_op!(Mul, mul, _mm256_mul_pd);
    avx_op!(Div, div, _mm256_div_pd);

    impl Neg for Avx {
        type Output = Avx;
        #[inline(always)]
        fn neg(self) -> Avx {
            // flipping the sign bit is exactly IEEE negation
            // SAFETY: as above.
            Avx(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
        }
    }

    /// Pointer to f64 number `k` of body `i` (`repr(C)`: pos.x, pos.y, rot.c, rot.s, vel.x,
    /// vel.y, omega, inv_mass, inv_inertia).
    #[inline(always)]
    fn field(state: *const BodyState, i: u32, k: usize) -> *const f64 {
        state.wrapping_add(i as usize).cast::<f64>().wrapping_add(k)
    }

    /// f64 numbers `k` and `k + 1` (k + 1 < 9) of the four bodies `index`, as lanes.
    ///
    /// # Safety
    /// Every index must be `< state.len()`.
    #[inline(always)]
    unsafe fn pairs(state: &[BodyState], index: &[u32; LANES], k: usize) -> (Avx, Avx) {
        debug_assert!(index.iter().all(|&i| (i as usize) < state.len()) && k < 8);
        let p = state.as_ptr();
        // SAFETY: every index is in bounds (the caller's promise) and k + 1 < 9, so each 16-byte
        // load reads two f64 fields of one body; AVX as in the module docs.
        unsafe {
            // [a0 b0 | a2 b2] and [a1 b1 | a3 b3], interleaved into [a0 a1 | a2 a3], [b0 b1 | b2 b3]
            let r02 = _mm256_insertf128_pd::<1>(
                _mm256_castpd128_pd256(_mm_loadu_pd(field(p, index[0], k))),
                _mm_loadu_pd(field(p, index[2], k)),
            );
            let r13 = _mm256_insertf128_pd::<1>(
                _mm256_castpd128_pd256(_mm_loadu_pd(field(p, index[1], k))),
                _mm_loadu_pd(field(p, index[3], k)),
            );
            (Avx(_mm256_unpacklo_pd(r02, r13)), Avx(_mm256_unpackhi_pd(r02, r13)))
        }
    }

    impl F64x4 for Avx {
        #[inline(always)]
        fn splat(x: f64) -> Self {
            // SAFETY: as above.
            Avx(unsafe { _mm256_set1_pd(x) })
        }
        #[inline(always)]
        fn load(x: &[f64; LANES]) -> Self {
            // SAFETY: `x` is 4 readable f64; AVX as above.
            Avx(unsafe { _mm256_loadu_pd(x.as_ptr()) })
        }
        #[inline(always)]
        fn store(self, out: &mut [f64; LANES]) {
            // SAFETY: `out` is 4 writable f64; AVX as above.
            unsafe { _mm256_storeu_pd(out.as_mut_ptr(), self.0) }
        }
        #[inline(always)]
        fn sqrt(self) -> Self {
            // SAFETY: as above.
            Avx(unsafe { _mm256_sqrt_pd(self.0) })
        }
        #[inline(always)]
        fn select_gt(self, other: Self, then: Self, otherwise: Self) -> Self {
            // SAFETY: as above.
            unsafe {
                let mask = _mm256_cmp_pd::<_CMP_GT_OQ>(self.0, other.0);
                Avx(_mm256_blendv_pd(otherwise.0, then.0, mask))
            }
        }
        #[inline(always)]
        fn max(self, other: Self) -> Self {
            // MAXPD returns its first operand where it is greater, else the second (also for NaN
            // and two zeros): exactly `if self > other { self } else { other }`
            // SAFETY: as above.
            Avx(unsafe { _mm256_max_pd(self.0, other.0) })
        }
        #[inline(always)]
        fn min(self, other: Self) -> Self {
            // likewise MINPD: `if self < other { self } else { other }`
            // SAFETY: as above.
            Avx(unsafe { _mm256_min_pd(self.0, other.0) })
        }
        #[inline(always)]
        unsafe fn gather_pose(state: &[BodyState], index: &[u32; LANES]) -> Pose<Self> {
            // SAFETY: the caller's promise.
            let ((px, py), (qc, qs)) = unsafe { (pairs(state, index, 0), pairs(state, index, 2)) };
            Pose { px, py, qc, qs }
        }
        #[inline(always)]
        unsafe fn gather_velocity(state: &[BodyState], index: &[u32; LANES]) -> Velocity<Self> {
            // SAFETY: the caller's promise.
            let ((vx, vy), (w, inv_mass)) = unsafe { (pairs(state, index, 4), pairs(state, index, 6)) };
            Velocity { vx, vy, w, inv_mass }
        }
        #[inline(always)]
        unsafe fn scatter_velocity(state: &mut [BodyState], index: &[u32; LANES], v: Velocity<Self>) {
            debug_assert!(index.iter().all(|&i| (i as usize) < state.len()));
            let p = state.as_mut_ptr();
            let at = |i: u32, k: usize| field(p, i, k).cast_mut();
            // SAFETY: every index is in bounds (the caller's promise), so each store writes fields 4..8
            // (velocity, angular velocity and the unchanged inverse mass) of one body; AVX as
            // above.
            unsafe {
                for (k, x, y) in [(4, v.vx.0, v.vy.0), (6, v.w.0, v.inv_mass.0)] {
                    let r02 = _mm256_unpacklo_pd(x, y); // [x0 y0 | x2 y2]
                    let r13 = _mm256_unpackhi_pd(x, y); // [x1 y1 | x3 y3]
                    _mm_storeu_pd(at(index[0], k), _mm256_castpd256_pd128(r02));
                    _mm_storeu_pd(at(index[1], k), _mm256_castpd256_pd128(r13));
                    _mm_storeu_pd(at(index[2], k), _mm256_extractf128_pd::<1>(r02));
                    _mm_storeu_pd(at(index[3], k), _mm256_extractf128_pd::<1>(r13));
                }
            }
        }
    }
}

#[cfg(test)]
mod equivalence_tests {
    //! The vector versions of the solvers must give the bits of the portable one: a world of soft
    //! cells (springs, ropes, contacts with friction and restitution) is stepped both ways.

    use super::FORCE_PORTABLE;
    use crate::{PartDesc, Polygon, RopeDesc, SpringDesc, Vec2, World, WorldBuilder, WorldSettings};

    /// A row of `n` soft cells (4 corner squares, 6 springs, 4 ropes) dropped on a slanted floor.
    fn soft_cells(n: usize) -> (World, Vec<crate::SpringHandle>) {
        let mut b = WorldBuilder::new(WorldSettings::default());
        let floor = Polygon::convex(&[
            Vec2::new(-50.0, -10.0),
            Vec2::new(50.0, -10.0),
            Vec2::new(50.0, -3.0),
            Vec2::new(-50.0, -1.0),
        ])
        .unwrap();
        b.add_static_polygon(floor, 1.0, 0.1);
        let mut springs = Vec::new();
        for cell in 0..n {
            let x0 = cell as f64 * 3.1 + 0.05 * cell as f64;
            let y0 = 2.0 + 0.7 * cell as f64;
            let corners: Vec<_> = [(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (0.0, 2.0)]
                .iter()
                .map(|&(dx, dy)| {
                    let shape = Polygon::square(Vec2::new(0.0, 0.0), 0.6);
                    let part = PartDesc::new(Vec2::new(x0 + dx, y0 + dy), shape)
                        .friction(1.0)
                        .restitution(0.2);
                    b.add_part(part.damping(0.1, 0.1))
                })
                .collect();
            for i in 0..4 {
                for j in i + 1..4 {
                    let rest = if (i + j) % 2 == 0 { 2.0 * 2f64.sqrt() } else { 2.0 };
                    springs.push(b.add_spring(SpringDesc {
                        part_a: corners[i],
                        anchor_a: Vec2::new(0.0, 0.0),
                        part_b: corners[j],
                        anchor_b: Vec2::new(0.0, 0.0),
                        rest_length: rest,
                        frequency: 8.0,
                        damping_ratio: 0.3,
                        mass_model: Default::default(),
                        collide_connected: false,
                    }));
                }
                b.add_rope(RopeDesc {
                    part_a: corners[i],
                    anchor_a: Vec2::new(0.0, 0.0),
                    part_b: corners[(i + 1) % 4],
                    anchor_b: Vec2::new(0.0, 0.0),
                    min_length: 1.0,
                    collide_connected: false,
                });
            }
        }
        (b.build().unwrap(), springs)
    }

    /// Steps the world with changing rest lengths and returns every part's pose, as bits.
    fn trajectory(portable: bool) -> Vec<u64> {
        FORCE_PORTABLE.with(|f| f.set(portable));
        let (mut world, springs) = soft_cells(7);
        let mut bits = Vec::new();
        for step in 0..400 {
            for (k, &s) in springs.iter().enumerate() {
                let base = world.spring_rest_length(s).unwrap();
                let wobble = 1.0 + 0.002 * ((step as f64 * 0.3 + k as f64).sin());
                world.set_spring_rest_length(s, base * wobble);
            }
            world.step().unwrap();
        }
        for part in 0..28 {
            let h = crate::PartHandle(part);
            let p = world.part_position(h);
            bits.extend([p.x.to_bits(), p.y.to_bits(), world.part_angle(h).to_bits()]);
        }
        FORCE_PORTABLE.with(|f| f.set(false));
        bits
    }

    #[test]
    fn vector_solvers_give_the_bits_of_the_portable_ones() {
        let (world, _) = soft_cells(7);
        assert!(world.body_count() >= 28);
        let fast = trajectory(false);
        let portable = trajectory(true);
        assert_eq!(fast.len(), portable.len());
        assert!(fast == portable, "the vector solvers diverged from the portable ones");
        // the scene really moved and touched the ground (so contacts and ropes were exercised)
        assert!(fast.iter().any(|&b| f64::from_bits(b) < 0.0));
    }
}
