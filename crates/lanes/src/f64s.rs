//! N f64 lanes: one value per episode of a population that steps together (population lanes,
//! stored `[element][field][lane]`). Every operation is the scalar IEEE operation lane by
//! lane (no fused multiply–add but the explicit `mul_add`, no approximations), so lane `l` of a computation gives the bits of
//! the same computation in scalar f64. The arrays are plain, the portable form of [`Lanes`]: a
//! kernel compiled with AVX2 enabled has them vectorised by the compiler, only partly (the 3D
//! engine has its own AVX2 form for that, `physics3d/src/avx.rs`).
//! Branches that differ between lanes are computed both ways and chosen per lane ([`Lanes::select`]).

use crate::lane::{LaneMask, Lanes};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// One f64 per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct F64s<const N: usize>(pub [f64; N]);

/// One bool per lane.
pub type Mask<const N: usize> = [bool; N];

impl<const N: usize> Lanes for F64s<N> {
    type Mask = Mask<N>;
    const LANES: usize = N;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        F64s([x; N])
    }

    #[inline(always)]
    fn get(&self, lane: usize) -> f64 {
        self.0[lane]
    }

    #[inline(always)]
    fn set(&mut self, lane: usize, x: f64) {
        self.0[lane] = x;
    }

    #[inline(always)]
    fn sqrt(self) -> Self {
        F64s(self.0.map(f64::sqrt))
    }

    #[inline(always)]
    fn abs(self) -> Self {
        F64s(self.0.map(f64::abs))
    }

    #[inline(always)]
    fn lt(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] < other.0[l])
    }

    #[inline(always)]
    fn gt(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] > other.0[l])
    }

    #[inline(always)]
    fn ge(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] >= other.0[l])
    }

    #[inline(always)]
    fn le(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] <= other.0[l])
    }

    #[inline(always)]
    fn ne(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] != other.0[l])
    }

    #[inline(always)]
    fn eq(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] == other.0[l])
    }

    #[inline(always)]
    fn select(mask: Mask<N>, then: Self, otherwise: Self) -> Self {
        F64s(std::array::from_fn(
            |l| if mask[l] { then.0[l] } else { otherwise.0[l] },
        ))
    }

    #[inline(always)]
    fn bits_and(self, mask: u64) -> Self {
        F64s(self.0.map(|x| f64::from_bits(x.to_bits() & mask)))
    }

    #[inline(always)]
    fn bits_xor(self, other: Self) -> Self {
        F64s(std::array::from_fn(|l| {
            f64::from_bits(self.0[l].to_bits() ^ other.0[l].to_bits())
        }))
    }

    #[inline(always)]
    fn bits_shl<const S: i32>(self) -> Self {
        F64s(self.0.map(|x| f64::from_bits(x.to_bits() << S)))
    }

    #[inline(always)]
    fn sign_mask(self) -> Mask<N> {
        self.0.map(f64::is_sign_negative)
    }

    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        F64s(std::array::from_fn(|l| self.0[l].mul_add(a.0[l], b.0[l])))
    }

    #[inline(always)]
    fn trunc(self) -> Self {
        F64s(self.0.map(f64::trunc))
    }
}

impl<const N: usize> LaneMask for Mask<N> {
    #[inline(always)]
    fn splat(b: bool) -> Self {
        [b; N]
    }

    #[inline(always)]
    fn get(&self, lane: usize) -> bool {
        self[lane]
    }

    #[inline(always)]
    fn set(&mut self, lane: usize, b: bool) {
        self[lane] = b;
    }

    #[inline(always)]
    fn and(self, other: Self) -> Self {
        std::array::from_fn(|l| self[l] && other[l])
    }

    #[inline(always)]
    fn or(self, other: Self) -> Self {
        std::array::from_fn(|l| self[l] || other[l])
    }

    #[inline(always)]
    fn not(self) -> Self {
        self.map(|x| !x)
    }

    #[inline(always)]
    fn any(self) -> bool {
        self.iter().any(|&x| x)
    }
}

macro_rules! lane_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl<const N: usize> $tr for F64s<N> {
            type Output = F64s<N>;
            #[inline(always)]
            fn $f(self, o: F64s<N>) -> F64s<N> {
                F64s(std::array::from_fn(|l| self.0[l] $op o.0[l]))
            }
        }
        impl<const N: usize> $tr<f64> for F64s<N> {
            type Output = F64s<N>;
            #[inline(always)]
            fn $f(self, o: f64) -> F64s<N> {
                F64s(std::array::from_fn(|l| self.0[l] $op o))
            }
        }
        impl<const N: usize> $tr<F64s<N>> for f64 {
            type Output = F64s<N>;
            #[inline(always)]
            fn $f(self, o: F64s<N>) -> F64s<N> {
                F64s(std::array::from_fn(|l| self $op o.0[l]))
            }
        }
    };
}
lane_op!(Add, add, +);
lane_op!(Sub, sub, -);
lane_op!(Mul, mul, *);
lane_op!(Div, div, /);

impl<const N: usize> Neg for F64s<N> {
    type Output = F64s<N>;
    #[inline(always)]
    fn neg(self) -> F64s<N> {
        F64s(self.0.map(|x| -x))
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// `count` values spread over (−scale, scale): uniform ones, and as many with magnitudes
    /// spread over many binades (small arguments and their series).
    pub(crate) fn random_values(count: usize, scale: f64) -> impl Iterator<Item = f64> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(52);
        (0..count).map(move |i| {
            let sign = if rng.random::<bool>() { 1.0 } else { -1.0 };
            match i % 2 {
                0 => sign * scale * rng.random::<f64>(),
                _ => sign * scale * 2f64.powf(-40.0 * rng.random::<f64>()),
            }
        })
    }

    /// Units in the last place between `a` and `b` (same sign assumed, 0 when both are NaN).
    pub(crate) fn ulps(a: f64, b: f64) -> u64 {
        if a.is_nan() && b.is_nan() {
            return 0;
        }
        let key = |x: f64| {
            let bits = x.to_bits() as i64;
            if bits < 0 {
                i64::MIN - bits
            } else {
                bits
            }
        };
        key(a).abs_diff(key(b))
    }

    #[test]
    fn every_lane_gives_the_scalar_operations_bits() {
        let a = F64s([0.1, -3.0, 1e-300, f64::NAN]);
        let b = F64s([0.3, 7.0, 1e300, 1.0]);
        let expected = [0.1f64 + 0.3, -3.0 + 7.0, 1e-300 + 1e300, f64::NAN];
        for (l, expected) in expected.iter().enumerate() {
            assert_eq!((a + b).0[l].to_bits(), expected.to_bits());
            assert_eq!((a / b).0[l].to_bits(), (a.0[l] / b.0[l]).to_bits());
            assert_eq!((2.0 * a - b).0[l].to_bits(), (2.0 * a.0[l] - b.0[l]).to_bits());
        }
        assert_eq!(a.lt(b), [true, true, true, false]);
        assert_eq!(F64s::select([true, false, true, false], a, b).0[1], 7.0);
    }
}
