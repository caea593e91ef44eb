//! N f64 lanes: one value per episode of a population that steps together (issue 52's population
//! lanes, stored `[element][field][lane]`). Every operation is the scalar IEEE operation lane by
//! lane (no fused multiply–add, no approximations), so lane `l` of a computation gives the bits of
//! the same computation in scalar f64. The arrays are plain; a kernel compiled with AVX2 or
//! AVX-512 enabled (`#[target_feature]`, chosen at run time) has them vectorised by the compiler.
//! Branches that differ between lanes are computed both ways and chosen per lane ([`F64s::select`]).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// One f64 per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct F64s<const N: usize>(pub [f64; N]);

/// One bool per lane.
pub(crate) type Mask<const N: usize> = [bool; N];

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
pub(crate) fn and<const N: usize>(a: Mask<N>, b: Mask<N>) -> Mask<N> {
    std::array::from_fn(|l| a[l] && b[l])
}

/// Per lane: `a || b`.
#[inline(always)]
pub(crate) fn or<const N: usize>(a: Mask<N>, b: Mask<N>) -> Mask<N> {
    std::array::from_fn(|l| a[l] || b[l])
}

/// Whether any lane holds: a branch no lane takes is not computed (its lanes would be dropped).
#[inline(always)]
pub(crate) fn any<const N: usize>(a: Mask<N>) -> bool {
    a.iter().any(|&x| x)
}

/// Per lane: `!a`.
#[inline(always)]
pub(crate) fn not<const N: usize>(a: Mask<N>) -> Mask<N> {
    a.map(|x| !x)
}

/// A vector per lane: `x`, `y`, `z` each hold every lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct V3<const N: usize> {
    pub x: F64s<N>,
    pub y: F64s<N>,
    pub z: F64s<N>,
}

impl<const N: usize> V3<N> {
    /// The same vector in every lane.
    pub fn splat(v: glam::DVec3) -> Self {
        V3 {
            x: F64s::splat(v.x),
            y: F64s::splat(v.y),
            z: F64s::splat(v.z),
        }
    }

    /// Lane `l` as a glam vector.
    #[cfg(test)]
    pub fn lane(&self, l: usize) -> glam::DVec3 {
        glam::DVec3::new(self.x.0[l], self.y.0[l], self.z.0[l])
    }

    /// Sets lane `l`.
    pub fn set_lane(&mut self, l: usize, v: glam::DVec3) {
        (self.x.0[l], self.y.0[l], self.z.0[l]) = (v.x, v.y, v.z);
    }

    /// Component by component: `then` where `mask` holds, else `otherwise`.
    #[inline(always)]
    pub fn select(mask: Mask<N>, then: Self, otherwise: Self) -> Self {
        V3 {
            x: F64s::select(mask, then.x, otherwise.x),
            y: F64s::select(mask, then.y, otherwise.y),
            z: F64s::select(mask, then.z, otherwise.z),
        }
    }

    /// Component by component `self + o` (glam's `DVec3 + DVec3`).
    #[inline(always)]
    pub fn add(self, o: Self) -> Self {
        V3 {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    /// Component by component `self - o`.
    #[inline(always)]
    pub fn sub(self, o: Self) -> Self {
        V3 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    /// `s * self` (glam's `f64 * DVec3`).
    #[inline(always)]
    pub fn scale(self, s: F64s<N>) -> Self {
        V3 {
            x: s * self.x,
            y: s * self.y,
            z: s * self.z,
        }
    }

    /// glam's `length`: `sqrt(x·x + y·y + z·z)`.
    #[inline(always)]
    pub fn length(self) -> F64s<N> {
        (self.x * self.x + self.y * self.y + self.z * self.z).sqrt()
    }
}

/// A quaternion per lane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Q<const N: usize> {
    pub x: F64s<N>,
    pub y: F64s<N>,
    pub z: F64s<N>,
    pub w: F64s<N>,
}

impl<const N: usize> Q<N> {
    /// The same quaternion in every lane.
    pub fn splat(q: glam::DQuat) -> Self {
        Q {
            x: F64s::splat(q.x),
            y: F64s::splat(q.y),
            z: F64s::splat(q.z),
            w: F64s::splat(q.w),
        }
    }

    /// Lane `l` as a glam quaternion.
    #[cfg(test)]
    pub fn lane(&self, l: usize) -> glam::DQuat {
        glam::DQuat::from_xyzw(self.x.0[l], self.y.0[l], self.z.0[l], self.w.0[l])
    }

    /// Sets lane `l`.
    pub fn set_lane(&mut self, l: usize, q: glam::DQuat) {
        (self.x.0[l], self.y.0[l], self.z.0[l], self.w.0[l]) = (q.x, q.y, q.z, q.w);
    }

    /// Component by component: `then` where `mask` holds, else `otherwise`.
    #[inline(always)]
    pub fn select(mask: Mask<N>, then: Self, otherwise: Self) -> Self {
        Q {
            x: F64s::select(mask, then.x, otherwise.x),
            y: F64s::select(mask, then.y, otherwise.y),
            z: F64s::select(mask, then.z, otherwise.z),
            w: F64s::select(mask, then.w, otherwise.w),
        }
    }

    /// The conjugate (glam's `conjugate`).
    #[inline(always)]
    pub fn conjugate(self) -> Self {
        Q {
            x: -self.x,
            y: -self.y,
            z: -self.z,
            w: self.w,
        }
    }

    /// The Hamilton product `self * o`, term for term as glam's `DQuat::mul_quat`.
    #[inline(always)]
    pub fn mul(self, o: Self) -> Self {
        let (x0, y0, z0, w0) = (self.x, self.y, self.z, self.w);
        let (x1, y1, z1, w1) = (o.x, o.y, o.z, o.w);
        Q {
            x: w0 * x1 + x0 * w1 + y0 * z1 - z0 * y1,
            y: w0 * y1 - x0 * z1 + y0 * w1 + z0 * x1,
            z: w0 * z1 + x0 * y1 - y0 * x1 + z0 * w1,
            w: w0 * w1 - x0 * x1 - y0 * y1 - z0 * z1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
        let q = Q::<2>::splat(glam::DQuat::from_xyzw(0.1, -0.2, 0.3, 0.9));
        let p = Q::<2>::splat(glam::DQuat::from_xyzw(-0.5, 0.4, 0.2, 0.7));
        assert_eq!(q.mul(p).lane(1), q.lane(1) * p.lane(1));
    }
}
