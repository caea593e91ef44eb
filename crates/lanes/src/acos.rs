//! Arc cosine over lanes: fdlibm's rational approximation of asin on [0, 1/2] in its three ranges
//! (|x| < 1/2, x ≤ −1/2, x ≥ 1/2, the last with the square root split in two parts for accuracy),
//! every range computed and each lane keeping its own.

use crate::f64s::F64s;
use crate::lane::Lanes;

const PI: f64 = std::f64::consts::PI;
const PIO2_HI: f64 = std::f64::consts::FRAC_PI_2;
const PIO2_LO: f64 = 6.123233995736766e-17;

const P_S0: f64 = 0.16666666666666666;
const P_S1: f64 = -0.3255658186224009;
const P_S2: f64 = 0.20121253213486293;
const P_S3: f64 = -0.04005553450067941;
const P_S4: f64 = 0.0007915349942898145;
const P_S5: f64 = 3.479331075960212e-05;
const Q_S1: f64 = -2.403394911734414;
const Q_S2: f64 = 2.0209457602335057;
const Q_S3: f64 = -0.6882839716054533;
const Q_S4: f64 = 0.07703815055590194;

/// asin(√z)/√z − 1, over z = x², for 0 ≤ z ≤ 1/4 (the rational part of asin).
#[inline(always)]
fn ratio<L: Lanes>(z: L) -> L {
    let p = z * ((z * ((z * ((z * ((z * ((z * P_S5) + P_S4)) + P_S3)) + P_S2)) + P_S1)) + P_S0);
    let q = (z * ((z * ((z * ((z * Q_S4) + Q_S3)) + Q_S2)) + Q_S1)) + 1.0;
    p / q
}

/// acos x for |x| < 1/2.
#[inline(always)]
fn middle<L: Lanes>(x: L) -> L {
    L::splat(PIO2_HI) - (x - (L::splat(PIO2_LO) - x * ratio(x * x)))
}

/// acos x for x ≤ −1/2: π − 2 asin √((1 + x)/2).
#[inline(always)]
fn negative<L: Lanes>(x: L) -> L {
    let z = (x + 1.0) * 0.5;
    let s = z.sqrt();
    L::splat(PI) - (s + (ratio(z) * s - PIO2_LO)) * 2.0
}

/// acos x for x ≥ 1/2: 2 asin √((1 − x)/2), the root split into a head with 32 zero bits and a
/// tail.
#[inline(always)]
fn positive<L: Lanes>(x: L) -> L {
    let z = (L::splat(1.0) - x) * 0.5;
    let s = z.sqrt();
    let head = s.bits_and(0xffff_ffff_0000_0000);
    let tail = (z - head * head) / (s + head);
    (head + (ratio(z) * s + tail)) * 2.0
}

/// acos x in every lane: each range computed when some lane is in it (one lane: a branch).
#[inline(always)]
pub(crate) fn acos_lanes<L: Lanes>(x: L) -> L {
    let below = x.lt(L::splat(-0.5));
    let above = x.gt(L::splat(0.5));
    let inside = crate::not(crate::or(below, above));
    let nan = L::splat(f64::NAN);
    let mut value = if crate::any(inside) { middle(x) } else { nan };
    if crate::any(below) {
        value = L::select(below, negative(x), value);
    }
    if crate::any(above) {
        value = L::select(above, positive(x), value);
    }
    // the ends exactly, and NaN outside [−1, 1]
    let value = L::select(x.eq(L::splat(1.0)), L::splat(0.0), value);
    let value = L::select(x.eq(L::splat(-1.0)), L::splat(PI), value);
    let outside = crate::or(x.gt(L::splat(1.0)), x.lt(L::splat(-1.0)));
    L::select(outside, nan, value)
}

/// acos x, the bits of every lane of [`Lanes::acos`]; NaN outside [−1, 1].
pub fn acos(x: f64) -> f64 {
    acos_lanes(F64s([x])).0[0]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::f64s::tests::{random_values, ulps};

    #[test]
    fn arc_cosine_is_within_one_ulp_of_libm() {
        let mut worst = 0;
        for x in random_values(200_000, 1.0) {
            worst = worst.max(ulps(acos(x), x.acos()));
        }
        for x in [-1.0, -0.5, -0.4999999, 0.0, 0.5, 0.5000001, 1.0 - 1e-12, 1.0] {
            worst = worst.max(ulps(acos(x), x.acos()));
        }
        assert!(worst <= 1, "{worst}");
        assert_eq!(acos(1.0), 0.0);
        assert_eq!(acos(-1.0), std::f64::consts::PI);
        assert!(acos(1.0 + 1e-15).is_nan() && acos(f64::NAN).is_nan() && acos(-2.0).is_nan());
    }

    #[test]
    fn every_lane_gives_the_scalar_bits() {
        let xs: Vec<f64> = random_values(4_096, 1.0).collect();
        for chunk in xs.chunks(4) {
            let lanes = F64s::<4>(std::array::from_fn(|l| chunk[l]));
            for (l, &x) in chunk.iter().enumerate() {
                assert_eq!(lanes.acos().0[l].to_bits(), acos(x).to_bits());
            }
        }
    }
}
