//! Hyperbolic tangent over lanes, Cody and Waite's method (Software Manual for the Elementary
//! Functions, 1980, ch. 13): for |x| ≤ ln(3)/2 the rational form f + f·g·P(g)/Q(g) with g = f²,
//! beyond it 1 − 2/(e^{2f} + 1) from an exponential of our own (fdlibm's reduction by ln 2 in two
//! parts and its polynomial), 1 beyond the point where tanh rounds to 1; the sign put back last.
//! Both ranges are computed where lanes need them and each lane keeps its own, so the scalar form
//! (one lane) and every lane give the same bits on every machine.

use crate::f64s::F64s;
use crate::lane::{LaneMask, Lanes};

/// ln(3)/2: below it the rational form.
const LN3_OVER_2: f64 = 0.549_306_144_334_054_8;
/// Beyond (ln 2 + 54 ln 2)/2 tanh rounds to 1.
const BIG: f64 = 19.061_547_465_398_5;

/// Cody and Waite's coefficients for 53-bit precision.
const P0: f64 = -0.161_341_190_239_962_28e4;
const P1: f64 = -99.225_929_672_236_08;
const P2: f64 = -0.964_374_927_772_254_7;
const Q0: f64 = 4_840.235_707_198_869;
const Q1: f64 = 0.223_377_207_189_623_13e4;
const Q2: f64 = 0.112_744_743_805_349_49e3;

/// ln 2 in two parts (the first with trailing zero bits, so `k · LN2_HI` is exact), and 1/ln 2.
const LN2_HI: f64 = 6.931_471_803_691_238e-1;
const LN2_LO: f64 = 1.908_214_929_270_587_7e-10;
const INV_LN2: f64 = std::f64::consts::LOG2_E;
/// fdlibm's polynomial for the exponential on [−ln2/2, ln2/2].
const E1: f64 = 1.666_666_666_666_660_2e-1;
const E2: f64 = -2.777_777_777_701_559_3e-3;
const E3: f64 = 6.613_756_321_437_934e-5;
const E4: f64 = -1.653_390_220_546_525_2e-6;
const E5: f64 = 4.138_136_797_057_238_5e-8;
/// 1.5 · 2^52: added to a whole number below 2^51 in magnitude, its low bits are the number.
const ROUNDING_BIAS: f64 = 6_755_399_441_055_744.0;

/// e^x for 1 ≤ x ≤ 2·BIG (the exponents stay far from overflow and underflow).
#[inline(always)]
fn exp_lanes<L: Lanes>(x: L) -> L {
    let k = (x * INV_LN2 + ROUNDING_BIAS) - ROUNDING_BIAS;
    let hi = x - k * LN2_HI;
    let lo = k * LN2_LO;
    let r = hi - lo;
    let t = r * r;
    let c = r - t * ((t * ((t * ((t * ((t * E5) + E4)) + E3)) + E2)) + E1);
    let y = L::splat(1.0) - ((lo - (r * c) / (L::splat(2.0) - c)) - hi);
    // 2^k: k + 1023 in the low bits of a number near 1.5 · 2^52, moved into the exponent field
    let scale = (k + (1023.0 + ROUNDING_BIAS)).bits_shl::<52>();
    y * scale
}

/// tanh x in every lane.
#[inline(always)]
pub(crate) fn tanh_lanes<L: Lanes>(x: L) -> L {
    let f = x.abs();
    let beyond = f.gt(L::splat(LN3_OVER_2));
    let mut r = L::splat(0.0);
    if beyond.not().any() {
        let g = f * f;
        let p = ((g * P2 + P1) * g + P0) * g;
        let q = ((g + Q2) * g + Q1) * g + Q0;
        r = f + f * (p / q);
    }
    if beyond.any() {
        let e = exp_lanes(f + f);
        let half = L::splat(0.5) - L::splat(1.0) / (e + 1.0);
        r = L::select(beyond, half + half, r);
    }
    let r = L::select(f.gt(L::splat(BIG)), L::splat(1.0), r);
    L::select(x.sign_mask(), -r, r)
}

/// tanh x, the bits of every lane of [`Lanes::tanh`]: within 2 ulp of the correctly rounded
/// value (the test below measures it against the platform's).
pub fn tanh(x: f64) -> f64 {
    tanh_lanes(F64s([x])).0[0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::f64s::tests::{random_values, ulps};

    #[test]
    fn tanh_is_within_two_ulp_of_libm() {
        let mut worst = 0;
        for x in random_values(200_000, 25.0) {
            worst = worst.max(ulps(tanh(x), x.tanh()));
        }
        for x in [0.5, LN3_OVER_2, 0.5494, 1.0, 5.0, 18.0, BIG, 19.1, 40.0] {
            worst = worst.max(ulps(tanh(x), x.tanh()));
            worst = worst.max(ulps(tanh(-x), (-x).tanh()));
        }
        assert!(worst <= 2, "{worst}");
    }

    #[test]
    fn tanh_keeps_its_exact_values_and_symmetry() {
        assert_eq!(tanh(0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(tanh(-0.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(tanh(1e-300), 1e-300);
        assert_eq!(tanh(f64::INFINITY), 1.0);
        assert_eq!(tanh(f64::NEG_INFINITY), -1.0);
        assert_eq!(tanh(30.0), 1.0);
        assert!(tanh(f64::NAN).is_nan());
        for x in [0.1, 0.6, 3.0, 10.0] {
            assert_eq!(tanh(-x), -tanh(x));
        }
    }

    #[test]
    fn every_lane_gives_the_scalar_bits() {
        let xs: Vec<f64> = random_values(4_096, 8.0).collect();
        for chunk in xs.chunks(4) {
            let lanes = F64s::<4>(std::array::from_fn(|l| chunk[l]));
            for (l, &x) in chunk.iter().enumerate() {
                assert_eq!(lanes.tanh().0[l].to_bits(), tanh(x).to_bits());
            }
        }
    }
}
