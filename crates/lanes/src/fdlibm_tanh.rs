//! Hyperbolic tangent with the bits of the GNU C library on x86-64 CPUs with FMA: fdlibm's
//! method (Sun, 1993) — tanh x = 1 − 2/(expm1(2|x|) + 2) for |x| ≥ 1, −t/(t + 2) with
//! t = expm1(−2|x|) below, and fdlibm's expm1 (reduction by ln 2 in two parts, a rational
//! correction) — evaluated in the order and with the fused multiply–adds of glibc's FMA build of
//! expm1 (glibc 2.28 to 2.36 at least: its `__expm1_fma`, which `tanh` calls on such CPUs).
//!
//! Why: the 2D networks, the PPO policies and the other MLP brains have always called the
//! platform's `tanh`, so every kept 2D and EvoGym result carries glibc's bits. Written over lanes,
//! the same bits come four or eight at a time, and on any machine: a CPU without FMA, another libm
//! (macOS, musl) or a later glibc no longer changes a result. The tests hold it to the platform's
//! `tanh` bit for bit where the platform is glibc on an FMA CPU, and to stored values everywhere.
//!
//! Only the expm1 branches tanh reaches are written: the argument is in [2, 44) or (−2, 0].

use crate::f64s::F64s;
use crate::lane::{LaneMask, Lanes};

/// Below 2⁻⁵⁵ tanh x is x·(1 + x).
const TINY: f64 = f64::from_bits(0x3c80_0000_0000_0000);
/// From 22 on, tanh rounds to ±1.
const SATURATED: f64 = 22.0;
/// expm1 reduces its argument from this magnitude on (high word above 0x3fd62e42, ≈ ln2/2) …
const REDUCE_FROM: f64 = f64::from_bits(0x3fd6_2e43_0000_0000);
/// … by one ln 2 exactly below this one (high word 0x3ff0a2b2, ≈ 3 ln2/2).
const ONE_LN2_BELOW: f64 = f64::from_bits(0x3ff0_a2b2_0000_0000);

/// ln 2 in two parts (the first with trailing zero bits) and 1/ln 2, fdlibm's (1/ln 2 is
/// `LOG2_E`).
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
const INV_LN2: f64 = std::f64::consts::LOG2_E;
/// fdlibm's expm1 coefficients.
const Q1: f64 = -3.333_333_333_333_313e-2;
const Q2: f64 = 1.587_301_587_254_814_6e-3;
const Q3: f64 = -7.936_507_578_674_88e-5;
const Q4: f64 = 4.008_217_827_329_362e-6;
const Q5: f64 = -2.010_992_181_836_243_7e-7;
/// 1.5 · 2^52: added to a whole number below 2^51 in magnitude, its low bits are the number.
const ROUNDING_BIAS: f64 = 6_755_399_441_055_744.0;

/// 2^k for whole k in lanes (−1022 ≤ k ≤ 1023): k + 1023 moved into the exponent field.
#[inline(always)]
fn pow2<L: Lanes>(k: L) -> L {
    (k + (1023.0 + ROUNDING_BIAS)).bits_shl::<52>()
}

/// expm1 a for a in [2, 44) or (−2, 0], glibc's FMA evaluation.
#[inline(always)]
fn expm1_lanes<L: Lanes>(a: L) -> L {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let size = a.abs();
    let negative = a.lt(zero);
    // k: 0 below the reduction, −1 for a negative argument within 3 ln2/2, else a/ln2 rounded
    // half away from zero (truncated after ±1/2); the reduction a − k·ln2 is then one formula
    let half = L::select(negative, L::splat(-0.5), L::splat(0.5));
    let general = (a * INV_LN2 + half).trunc();
    let near = L::select(negative, L::splat(-1.0), one);
    let k = L::select(
        size.ge(L::splat(REDUCE_FROM)),
        L::select(size.lt(L::splat(ONE_LN2_BELOW)), near, general),
        zero,
    );
    let hi = (-k).mul_add(L::splat(LN2_HI), a);
    let lo = k * LN2_LO;
    let x = hi - lo;
    let c = (hi - x) - lo;
    // the rational correction: r1 = 1 + h·Q1 + h²(Q2 + h·Q3) + h⁴(Q4 + h·Q5), h = x²/2
    let hfx = x * 0.5;
    let hxs = x * hfx;
    let r2 = hxs.mul_add(L::splat(Q3), L::splat(Q2));
    let r3 = hxs.mul_add(L::splat(Q5), L::splat(Q4));
    let h2 = hxs * hxs;
    let r1 = hxs.mul_add(L::splat(Q1), one);
    let h4 = h2 * h2;
    let r1 = h4.mul_add(r3, h2.mul_add(r2, r1));
    let t = (-r1).mul_add(hfx, L::splat(3.0));
    let e = (r1 - t) / (-x).mul_add(t, L::splat(6.0)) * hxs;
    // k = 0: x − (x·e − x²/2)
    let unreduced = x - e.mul_add(x, -hxs);
    // otherwise the correction of the reduction's error c first, then 2^k put back
    let e = (e - c).mul_add(x, -c) - hxs;
    let minus_one = (x - e).mul_add(L::splat(0.5), L::splat(-0.5));
    let scale = pow2(k);
    let far = (one - (e - x)) * scale - one;
    let mid = ((one - pow2(-k)) - (e - x)) * scale;
    let high = ((x - (e + pow2(-k))) + one) * scale;
    let k56 = k.gt(L::splat(56.0));
    let out = L::select(k.ge(L::splat(20.0)), high, mid);
    let out = L::select(k.le(L::splat(-2.0)).or(k56), far, out);
    let out = L::select(k.eq(L::splat(-1.0)), minus_one, out);
    L::select(k.eq(zero), unreduced, out)
}

/// tanh x in every lane, glibc's bits (module documentation).
#[inline(always)]
pub(crate) fn tanh_lanes<L: Lanes>(x: L) -> L {
    let f = x.abs();
    let large = f.ge(L::splat(1.0));
    let t = expm1_lanes(L::select(large, f + f, f * -2.0));
    // one division for both forms: 1 − 2/(t + 2) and −t/(t + 2)
    let two = L::splat(2.0);
    let q = L::select(large, two, -t) / (t + two);
    let z = L::select(large, L::splat(1.0) - q, q);
    let z = L::select(f.ge(L::splat(SATURATED)), L::splat(1.0), z);
    let z = L::select(x.sign_mask(), -z, z);
    let z = L::select(f.lt(L::splat(TINY)), (L::splat(1.0) + x) * x, z);
    // NaN stays NaN (the comparisons above are all false for it)
    L::select(x.ne(x), x + x, z)
}

/// tanh x with the bits glibc gives on an x86-64 CPU with FMA, on any machine (module
/// documentation). One value, with branches as glibc has them; for many prefer
/// [`fdlibm_tanh_in_place`].
pub fn fdlibm_tanh(x: f64) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if crate::avx::available() {
        // SAFETY: the CPU has FMA (checked above)
        return unsafe { tanh_fma(x) };
    }
    tanh_one(x)
}

/// One value with the FMA instruction (rather than the library call `f64::mul_add` makes in a
/// build for baseline x86-64).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
unsafe fn tanh_fma(x: f64) -> f64 {
    tanh_one(x)
}

/// tanh of one value, branching where glibc does: the bits of [`tanh_lanes`].
#[inline(always)]
fn tanh_one(x: f64) -> f64 {
    let f = x.abs();
    if f.is_nan() {
        return x + x;
    }
    if f < TINY {
        return (1.0 + x) * x;
    }
    let z = if f >= SATURATED {
        1.0
    } else if f >= 1.0 {
        1.0 - 2.0 / (expm1_one(f + f) + 2.0)
    } else {
        let t = expm1_one(f * -2.0);
        -t / (t + 2.0)
    };
    if x.is_sign_negative() {
        -z
    } else {
        z
    }
}

/// expm1 a for a in [2, 44) or (−2, 0], branching where glibc does: the bits of [`expm1_lanes`].
#[inline(always)]
fn expm1_one(a: f64) -> f64 {
    let size = a.abs();
    let k = if size < REDUCE_FROM {
        0.0
    } else if size < ONE_LN2_BELOW {
        -1.0 // a > 0 is at least 2 here
    } else {
        (a * INV_LN2 + if a < 0.0 { -0.5 } else { 0.5 }).trunc()
    };
    let hi = (-k).mul_add(LN2_HI, a);
    let lo = k * LN2_LO;
    let x = hi - lo;
    let c = (hi - x) - lo;
    let hfx = x * 0.5;
    let hxs = x * hfx;
    let r2 = hxs.mul_add(Q3, Q2);
    let r3 = hxs.mul_add(Q5, Q4);
    let h2 = hxs * hxs;
    let r1 = hxs.mul_add(Q1, 1.0);
    let h4 = h2 * h2;
    let r1 = h4.mul_add(r3, h2.mul_add(r2, r1));
    let t = (-r1).mul_add(hfx, 3.0);
    let e = (r1 - t) / (-x).mul_add(t, 6.0) * hxs;
    if k == 0.0 {
        return x - e.mul_add(x, -hxs);
    }
    let e = (e - c).mul_add(x, -c) - hxs;
    if k == -1.0 {
        return (x - e).mul_add(0.5, -0.5);
    }
    let scale = f64::from_bits(((k as i64 + 1023) as u64) << 52);
    let below = f64::from_bits(((1023 - k as i64) as u64) << 52);
    if k <= -2.0 || k > 56.0 {
        (1.0 - (e - x)) * scale - 1.0
    } else if k < 20.0 {
        ((1.0 - below) - (e - x)) * scale
    } else {
        ((x - (e + below)) + 1.0) * scale
    }
}

/// Below this many values one at a time is as fast: a lone vector waits on its chain of two
/// divisions (measured on AVX-512, docs/performance.md).
const LANES_FROM: usize = 16;

/// Every value replaced by [`fdlibm_tanh`] of it: eight at a time in AVX-512, four in AVX2, the
/// same bits as one at a time.
pub fn fdlibm_tanh_in_place(values: &mut [f64]) {
    if values.len() < LANES_FROM {
        values.iter_mut().for_each(|v| *v = fdlibm_tanh(*v));
        return;
    }
    #[cfg(target_arch = "x86_64")]
    {
        if crate::avx512::available() {
            // SAFETY: the CPU has AVX-512F (checked above)
            return unsafe { in_place_avx512(values) };
        }
        if crate::avx::available() {
            // SAFETY: the CPU has AVX2 and FMA (checked above)
            return unsafe { in_place_avx2(values) };
        }
    }
    in_place::<F64s<4>>(values);
}

/// `values` through [`tanh_lanes`], `L::LANES` (at most 8) at a time, the last group padded with
/// zeros.
#[inline(always)]
fn in_place<L: Lanes>(values: &mut [f64]) {
    let mut groups = values.chunks_exact_mut(L::LANES);
    for group in &mut groups {
        through_tanh::<L>(group);
    }
    let rest = groups.into_remainder();
    if !rest.is_empty() {
        let mut padded = [0.0; 8];
        padded[..rest.len()].copy_from_slice(rest);
        through_tanh::<L>(&mut padded[..L::LANES]);
        rest.copy_from_slice(&padded[..rest.len()]);
    }
}

/// One group of exactly `L::LANES` values through [`tanh_lanes`].
#[inline(always)]
fn through_tanh<L: Lanes>(group: &mut [f64]) {
    let mut lanes = L::splat(0.0);
    for (l, &v) in group.iter().enumerate() {
        lanes.set(l, v);
    }
    let out = tanh_lanes(lanes);
    for (l, v) in group.iter_mut().enumerate() {
        *v = out.get(l);
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn in_place_avx2(values: &mut [f64]) {
    in_place::<crate::avx::Avx<4>>(values);
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f")]
unsafe fn in_place_avx512(values: &mut [f64]) {
    in_place::<crate::avx512::Avx512<8>>(values);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::f64s::tests::random_values;

    /// Whether the platform's `tanh` is glibc's on a CPU with FMA, the bits this module gives.
    fn platform_is_glibc_with_fma() -> bool {
        cfg!(all(target_arch = "x86_64", target_os = "linux", target_env = "gnu")) && crate::avx::available()
    }

    /// Arguments over every branch: tiny, below and above each expm1 threshold, to saturation.
    fn arguments() -> Vec<f64> {
        let mut xs: Vec<f64> = random_values(400_000, 3.0).collect();
        xs.extend(random_values(200_000, 25.0));
        xs.extend(random_values(50_000, 1e-3));
        xs.extend(random_values(20_000, 1e-15));
        for edge in [
            TINY,
            REDUCE_FROM / 2.0,
            ONE_LN2_BELOW / 2.0,
            0.5,
            1.0,
            9.7,
            10.0,
            19.5,
            22.0,
        ] {
            let mut x = edge;
            for _ in 0..40 {
                xs.extend([x, -x]);
                x = f64::from_bits(x.to_bits() - 1);
            }
        }
        xs
    }

    #[test]
    fn gives_the_platform_bits_on_glibc_with_fma() {
        if !platform_is_glibc_with_fma() {
            eprintln!("not glibc on an FMA CPU: compared with stored values only");
            return;
        }
        let mut differ = 0;
        for x in arguments() {
            if fdlibm_tanh(x).to_bits() != x.tanh().to_bits() {
                differ += 1;
                eprintln!(
                    "tanh({x:e}): {:e} against the platform's {:e}",
                    fdlibm_tanh(x),
                    x.tanh()
                );
            }
        }
        assert_eq!(differ, 0);
    }

    /// glibc 2.36's values (x86-64, FMA) for arguments on every branch, as bits: the check that
    /// holds on any machine.
    #[test]
    fn gives_stored_glibc_values() {
        for (x, bits) in STORED {
            assert_eq!(fdlibm_tanh(x).to_bits(), bits, "tanh({x:e})");
        }
    }

    #[test]
    fn branches_and_lanes_give_the_same_bits() {
        for x in arguments() {
            let lanes = tanh_lanes(F64s([x])).0[0];
            assert_eq!(tanh_one(x).to_bits(), lanes.to_bits(), "tanh({x:e})");
        }
    }

    #[test]
    fn keeps_the_special_values() {
        assert_eq!(fdlibm_tanh(0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(fdlibm_tanh(-0.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(fdlibm_tanh(1e-300), 1e-300);
        assert_eq!(fdlibm_tanh(f64::INFINITY), 1.0);
        assert_eq!(fdlibm_tanh(f64::NEG_INFINITY), -1.0);
        assert_eq!(fdlibm_tanh(30.0), 1.0);
        assert!(fdlibm_tanh(f64::NAN).is_nan());
    }

    #[test]
    fn in_place_gives_the_bits_of_one_at_a_time_for_every_length() {
        let xs: Vec<f64> = random_values(1_000, 6.0).collect();
        for len in [0, 1, 3, 4, 5, 8, 9, 17, 1_000] {
            let mut v = xs[..len].to_vec();
            fdlibm_tanh_in_place(&mut v);
            for (x, y) in xs[..len].iter().zip(&v) {
                assert_eq!(y.to_bits(), fdlibm_tanh(*x).to_bits(), "length {len}, tanh({x:e})");
            }
            let mut portable = xs[..len].to_vec();
            in_place::<F64s<4>>(&mut portable);
            assert_eq!(portable, v, "length {len}");
        }
    }

    /// (x, glibc's tanh x as bits), printed by a C program against glibc 2.36 on an FMA CPU.
    const STORED: [(f64, u64); 33] = [
        (1e-17, 0x3c67_0ef5_4646_d497),
        (-3e-17, 0xbc81_4b37_f4b5_1f71),
        (2.7e-16, 0x3cb3_749e_f34b_c35f),
        (0.0001, 0x3f1a_36e2_e9a4_f663),
        (-0.01, 0xbf84_7ab4_8ae4_595e),
        (0.1, 0x3fb9_83d7_795f_413a),
        (-0.17, 0xbfc5_8d82_96a4_05bc),
        (0.173, 0x3fc5_ecfa_7cd2_7c20),
        (0.25, 0x3fcf_597e_a69a_1c86),
        (-0.3, 0xbfd2_a4dd_a7d9_14fa),
        (0.4, 0x3fd8_5115_73c2_42d6),
        (0.5, 0x3fdd_9353_d756_8af3),
        (-0.52, 0xbfde_92a3_1264_0003),
        (0.6, 0x3fe1_2f82_92d2_ccfc),
        (0.75, 0x3fe4_5323_e552_f228),
        (-0.9, 0xbfe6_ebe9_82d6_605d),
        (0.999, 0x3fe8_5b89_494c_dea1),
        (1.0, 0x3fe8_5efa_b514_f394),
        (-1.0000001, 0xbfe8_5efa_cba1_08d2),
        (1.3, 0x3feb_933c_726e_9b3a),
        (2.0, 0x3fee_d950_5e1b_c3d4),
        (-2.5, 0xbfef_9258_260a_71c2),
        (3.7, 0x3fef_f5fd_c948_488c),
        (5.0, 0x3fef_ff41_9668_df11),
        (-7.5, 0xbfef_fffe_b78a_3c73),
        (9.8, 0x3fef_ffff_fcb2_c891),
        (10.5, 0x3fef_ffff_ff2f_9279),
        (-12.0, 0xbfef_ffff_fff5_9f7c),
        (15.0, 0x3fef_ffff_ffff_f96a),
        (18.9, 0x3fef_ffff_ffff_ffff),
        (-19.6, 0xbff0_0000_0000_0000),
        (21.99, 0x3ff0_0000_0000_0000),
        (22.0, 0x3ff0_0000_0000_0000),
    ];
}
