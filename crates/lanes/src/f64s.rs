//! N f64 lanes: one value per episode of a population that steps together (population lanes,
//! stored `[element][field][lane]`). Every operation is the scalar IEEE operation lane by
//! lane (no fused multiply–add, no approximations), so lane `l` of a computation gives the bits of
//! the same computation in scalar f64. The arrays are plain; a kernel compiled with AVX2 or
//! AVX-512 enabled (`#[target_feature]`, chosen at run time) has them vectorised by the compiler.
//! Branches that differ between lanes are computed both ways and chosen per lane ([`F64s::select`]).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// One f64 per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct F64s<const N: usize>(pub [f64; N]);

/// One bool per lane.
pub type Mask<const N: usize> = [bool; N];

impl<const N: usize> F64s<N> {
    /// The same value in every lane.
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        F64s([x; N])
    }

    /// `f` lane by lane: for functions of the standard library (`acos`, `sin`), whose bits are
    /// then those of the scalar call.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f64) -> f64) -> Self {
        F64s(self.0.map(f))
    }

    /// Square root, lane by lane.
    #[inline(always)]
    pub fn sqrt(self) -> Self {
        self.map(f64::sqrt)
    }

    /// Absolute value, lane by lane.
    #[inline(always)]
    pub fn abs(self) -> Self {
        self.map(f64::abs)
    }

    /// `self < other`, lane by lane (false where either is NaN).
    #[inline(always)]
    pub fn lt(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] < other.0[l])
    }

    /// `self > other`, lane by lane.
    #[inline(always)]
    pub fn gt(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] > other.0[l])
    }

    /// `self >= other`, lane by lane.
    #[inline(always)]
    pub fn ge(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] >= other.0[l])
    }

    /// `self <= other`, lane by lane.
    #[inline(always)]
    pub fn le(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] <= other.0[l])
    }

    /// `self != other`, lane by lane (true where either is NaN: `x.ne(x)` finds NaN).
    #[inline(always)]
    pub fn ne(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] != other.0[l])
    }

    /// `self == other`, lane by lane.
    #[inline(always)]
    pub fn eq(self, other: Self) -> Mask<N> {
        std::array::from_fn(|l| self.0[l] == other.0[l])
    }

    /// `x.clamp(lo, hi)` lane by lane, as `f64::clamp` (NaN stays NaN).
    #[inline(always)]
    pub fn clamp(self, lo: f64, hi: f64) -> Self {
        self.map(|x| x.clamp(lo, hi))
    }

    /// Per lane: `then` where `mask` holds, else `otherwise`.
    #[inline(always)]
    pub fn select(mask: Mask<N>, then: Self, otherwise: Self) -> Self {
        F64s(std::array::from_fn(
            |l| if mask[l] { then.0[l] } else { otherwise.0[l] },
        ))
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
        self.map(|x| -x)
    }
}

/// Per lane: `a && b`.
#[inline(always)]
pub fn and<const N: usize>(a: Mask<N>, b: Mask<N>) -> Mask<N> {
    std::array::from_fn(|l| a[l] && b[l])
}

/// Per lane: `a || b`.
#[inline(always)]
pub fn or<const N: usize>(a: Mask<N>, b: Mask<N>) -> Mask<N> {
    std::array::from_fn(|l| a[l] || b[l])
}

/// Whether any lane holds: a branch no lane takes is not computed (its lanes would be dropped).
#[inline(always)]
pub fn any<const N: usize>(a: Mask<N>) -> bool {
    a.iter().any(|&x| x)
}

/// Per lane: `!a`.
#[inline(always)]
pub fn not<const N: usize>(a: Mask<N>) -> Mask<N> {
    a.map(|x| !x)
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
