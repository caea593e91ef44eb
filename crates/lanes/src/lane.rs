//! What a kernel over lanes asks of its number type: the scalar IEEE operations lane by lane,
//! comparisons giving a mask, a per-lane choice, and the few bit operations the elementary
//! functions need. [`F64s`](crate::F64s) is the portable form (plain arrays, vectorised by the
//! compiler where it can); an engine may add a form in explicit vector instructions, chosen at run
//! time. Every form gives the same bits in every lane, so a kernel written once over `L: Lanes`
//! gives the scalar engine's bits whichever form runs it.

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// One f64 per lane, with the operations the kernels use.
pub trait Lanes:
    Copy
    + Debug
    + PartialEq
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// One bool per lane.
    type Mask: LaneMask;

    /// Number of lanes.
    const LANES: usize;

    /// The same value in every lane.
    fn splat(x: f64) -> Self;

    /// Lane `lane`'s value.
    fn get(&self, lane: usize) -> f64;

    /// Sets lane `lane`.
    fn set(&mut self, lane: usize, x: f64);

    /// Square root, lane by lane (IEEE, correctly rounded).
    fn sqrt(self) -> Self;

    /// Absolute value, lane by lane (the sign bit cleared).
    fn abs(self) -> Self;

    /// `self < other`, lane by lane (false where either is NaN).
    fn lt(self, other: Self) -> Self::Mask;

    /// `self > other`, lane by lane (false where either is NaN).
    fn gt(self, other: Self) -> Self::Mask;

    /// `self >= other`, lane by lane (false where either is NaN).
    fn ge(self, other: Self) -> Self::Mask;

    /// `self <= other`, lane by lane (false where either is NaN).
    fn le(self, other: Self) -> Self::Mask;

    /// `self != other`, lane by lane (true where either is NaN: `x.ne(x)` finds NaN).
    fn ne(self, other: Self) -> Self::Mask;

    /// `self == other`, lane by lane (false where either is NaN).
    fn eq(self, other: Self) -> Self::Mask;

    /// Per lane: `then` where `mask` holds, else `otherwise`.
    fn select(mask: Self::Mask, then: Self, otherwise: Self) -> Self;

    /// `x.clamp(lo, hi)` lane by lane, as `f64::clamp` (NaN stays NaN).
    #[inline(always)]
    fn clamp(self, lo: f64, hi: f64) -> Self {
        let (lo, hi) = (Self::splat(lo), Self::splat(hi));
        let low = Self::select(self.lt(lo), lo, self);
        Self::select(low.gt(hi), hi, low)
    }

    /// The bits of each lane and'ed with `mask` (as `f64::from_bits(x.to_bits() & mask)`).
    fn bits_and(self, mask: u64) -> Self;

    /// The bits of each lane xor'ed with `other`'s.
    fn bits_xor(self, other: Self) -> Self;

    /// The bits of each lane shifted left by `S`.
    fn bits_shl<const S: i32>(self) -> Self;

    /// The lanes whose sign bit is set (negative numbers, −0, NaN with the sign bit).
    fn sign_mask(self) -> Self::Mask;

    /// `self · a + b` rounded once (a fused multiply–add), lane by lane. The engines never use it;
    /// [`fdlibm_tanh`](crate::fdlibm_tanh) does, to give the bits of a libm built with FMA. The
    /// vector forms need a CPU with FMA ([`avx::available`](crate::avx::available) checks it).
    fn mul_add(self, a: Self, b: Self) -> Self;

    /// Each lane rounded toward zero.
    fn trunc(self) -> Self;

    /// `(sin x, cos x)` lane by lane: each lane gives the bits of the scalar [`sin_cos`](crate::sin_cos).
    #[inline(always)]
    fn sin_cos(self) -> (Self, Self) {
        crate::trig::sin_cos_lanes(self)
    }

    /// sin x lane by lane, the bits of the scalar [`sin`](crate::sin).
    #[inline(always)]
    fn sin(self) -> Self {
        crate::trig::sin_cos_lanes(self).0
    }

    /// cos x lane by lane, the bits of the scalar [`cos`](crate::cos).
    #[inline(always)]
    fn cos(self) -> Self {
        crate::trig::sin_cos_lanes(self).1
    }

    /// tanh x lane by lane, the bits of the scalar [`tanh`](crate::tanh).
    #[inline(always)]
    fn tanh(self) -> Self {
        crate::tanh::tanh_lanes(self)
    }

    /// acos x lane by lane, the bits of the scalar [`acos`](crate::acos).
    #[inline(always)]
    fn acos(self) -> Self {
        crate::acos::acos_lanes(self)
    }
}

/// One bool per lane.
pub trait LaneMask: Copy + Debug + PartialEq {
    /// The same bool in every lane.
    fn splat(b: bool) -> Self;

    /// Lane `lane`'s bool.
    fn get(&self, lane: usize) -> bool;

    /// Sets lane `lane`.
    fn set(&mut self, lane: usize, b: bool);

    /// Per lane: `self && other`.
    fn and(self, other: Self) -> Self;

    /// Per lane: `self || other`.
    fn or(self, other: Self) -> Self;

    /// Per lane: `!self`.
    fn not(self) -> Self;

    /// Whether any lane holds.
    fn any(self) -> bool;
}

/// Per lane: `a && b`.
#[inline(always)]
pub fn and<M: LaneMask>(a: M, b: M) -> M {
    a.and(b)
}

/// Per lane: `a || b`.
#[inline(always)]
pub fn or<M: LaneMask>(a: M, b: M) -> M {
    a.or(b)
}

/// Whether any lane holds: a branch no lane takes is not computed (its lanes would be dropped).
#[inline(always)]
pub fn any<M: LaneMask>(a: M) -> bool {
    a.any()
}

/// Per lane: `!a`.
#[inline(always)]
pub fn not<M: LaneMask>(a: M) -> M {
    a.not()
}
