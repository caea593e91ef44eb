//! Sine and cosine over lanes: the argument reduced by multiples of π/2 (three-part Cody–Waite
//! constants, exact for |k| < 2^20; none for |x| ≤ π/4), then minimax polynomials on [−π/4, π/4]
//! (fdlibm's coefficients), the quadrant chosen by bit operations. Arguments beyond 2^19·π/2 fall
//! back to
//! the standard library lane by lane (the same call in scalar and vector form); the engines never
//! get there.

use crate::f64s::F64s;
use crate::lane::{LaneMask, Lanes};

/// π/2 in three parts: the first two have trailing zero bits, so `k · part` is exact.
const PIO2_1: f64 = 1.5707963267341256;
const PIO2_2: f64 = 6.077100506303966e-11;
const PIO2_3: f64 = 2.0222662487111665e-21;
const TWO_OVER_PI: f64 = std::f64::consts::FRAC_2_PI;
/// Beyond this |x| the reduction is not exact.
const REDUCTION_LIMIT: f64 = 823549.6;
/// 2^−27: below it, sin x rounds to x.
const TINY: f64 = 7.450580596923828e-09;
/// 1.5 · 2^52: added to a whole number below 2^51 in magnitude, its low bits are the number.
const ROUNDING_BIAS: f64 = 6755399441055744.0;

const S1: f64 = -0.16666666666666632;
const S2: f64 = 0.00833333333332249;
const S3: f64 = -0.0001984126982985795;
const S4: f64 = 2.7557313707070068e-06;
const S5: f64 = -2.5050760253406863e-08;
const S6: f64 = 1.58969099521155e-10;

const C1: f64 = 0.0416666666666666;
const C2: f64 = -0.001388888888887411;
const C3: f64 = 2.480158728947673e-05;
const C4: f64 = -2.7557314351390663e-07;
const C5: f64 = 2.087572321298175e-09;
const C6: f64 = -1.1359647557788195e-11;

/// sin(r) for |r| ≤ π/4.
#[inline(always)]
fn kernel_sin<L: Lanes>(r: L) -> L {
    let z = r * r;
    let p = (z * ((z * ((z * ((z * S6) + S5)) + S4)) + S3)) + S2;
    r + r * z * ((z * p) + S1)
}

/// cos(r) for |r| ≤ π/4: `1 − r²/2` formed so that its rounding error is recovered.
#[inline(always)]
fn kernel_cos<L: Lanes>(r: L) -> L {
    let z = r * r;
    let p = z * ((z * ((z * ((z * ((z * ((z * C6) + C5)) + C4)) + C3)) + C2)) + C1);
    let half = z * 0.5;
    let one = L::splat(1.0);
    let w = one - half;
    w + (((one - w) - half) + z * p)
}

/// `(sin x, cos x)` in every lane.
#[inline(always)]
pub(crate) fn sin_cos_lanes<L: Lanes>(x: L) -> (L, L) {
    let near = x.abs().le(L::splat(std::f64::consts::FRAC_PI_4));
    let k = L::select(near, L::splat(0.0), (x * TWO_OVER_PI + ROUNDING_BIAS) - ROUNDING_BIAS);
    let r = L::select(near, x, ((x - k * PIO2_1) - k * PIO2_2) - k * PIO2_3);
    let (s, c) = (kernel_sin(r), kernel_cos(r));
    // k is a whole number below 2^51 in magnitude: its low bits are those of k + 1.5 · 2^52; the
    // quadrant's bit 0 swaps sine and cosine, the sine's sign is bit 1, the cosine's bit 0 xor 1
    let quadrant = k + ROUNDING_BIAS;
    let bit0 = quadrant.bits_and(1).bits_shl::<63>();
    let bit1 = quadrant.bits_and(2).bits_shl::<62>();
    let odd = bit0.sign_mask();
    let mut sin = L::select(odd, c, s).bits_xor(bit1);
    let mut cos = L::select(odd, s, c).bits_xor(bit1.bits_xor(bit0));
    // sin x rounds to x below 2^−27 (and keeps the sign of zero)
    sin = L::select(x.abs().lt(L::splat(TINY)), x, sin);
    let far = x.abs().gt(L::splat(REDUCTION_LIMIT));
    if far.any() {
        for l in (0..L::LANES).filter(|&l| far.get(l)) {
            let x = x.get(l);
            sin.set(l, x.sin());
            cos.set(l, x.cos());
        }
    }
    (sin, cos)
}

/// `(sin x, cos x)`, the bits of every lane of [`Lanes::sin_cos`].
pub fn sin_cos(x: f64) -> (f64, f64) {
    let (s, c) = sin_cos_lanes(F64s([x]));
    (s.0[0], c.0[0])
}

/// sin x, the bits of every lane of [`Lanes::sin`].
pub fn sin(x: f64) -> f64 {
    sin_cos(x).0
}

/// cos x, the bits of every lane of [`Lanes::cos`].
pub fn cos(x: f64) -> f64 {
    sin_cos(x).1
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::f64s::tests::{random_values, ulps};

    #[test]
    fn sine_and_cosine_are_within_one_ulp_of_libm() {
        let mut worst = (0u64, 0u64);
        for x in random_values(200_000, 40.0) {
            let (s, c) = sin_cos(x);
            worst.0 = worst.0.max(ulps(s, x.sin()));
            worst.1 = worst.1.max(ulps(c, x.cos()));
        }
        assert!(worst.0 <= 1 && worst.1 <= 1, "{worst:?}");
    }

    #[test]
    fn sine_and_cosine_keep_their_exact_values_and_symmetries() {
        assert_eq!(sin(0.0).to_bits(), 0.0f64.to_bits());
        assert_eq!(sin(-0.0).to_bits(), (-0.0f64).to_bits());
        assert_eq!(cos(0.0), 1.0);
        assert_eq!(sin(1e-300), 1e-300);
        for x in [0.3, 1.0, 2.5, 7.0, 100.0, 1e5] {
            assert_eq!(sin(-x), -sin(x), "{x}");
            assert_eq!(cos(-x), cos(x), "{x}");
        }
        assert!(sin(f64::INFINITY).is_nan() && cos(f64::NAN).is_nan());
        // far arguments take the standard library's values
        assert_eq!(sin(1e7), 1e7f64.sin());
    }

    #[test]
    fn every_lane_gives_the_scalar_bits() {
        let xs: Vec<f64> = random_values(4_096, 1e3).collect();
        for chunk in xs.chunks(8) {
            let lanes = F64s::<8>(std::array::from_fn(|l| chunk[l]));
            let (s, c) = lanes.sin_cos();
            for (l, &x) in chunk.iter().enumerate() {
                assert_eq!(s.0[l].to_bits(), sin(x).to_bits());
                assert_eq!(c.0[l].to_bits(), cos(x).to_bits());
            }
        }
    }
}
