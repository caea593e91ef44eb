//! N f64 lanes in AVX2 instructions, four per 256-bit register (N a multiple of 4): the laned
//! world's number type on CPUs that have AVX2. The compiler vectorised the portable arrays
//! (`vsrlab_lanes::F64s`) only partly (two-wide and scalar instructions among the four-wide
//! ones, docs/performance.md); here every operation is one instruction per four lanes. Each is
//! the IEEE operation of the scalar engine, so every lane keeps the scalar bits.
//!
//! Values of these types run AVX2 instructions in their operations (making one, reading and
//! setting a lane do not; [`Lanes::mul_add`] runs FMA's): only code that checked the CPU first ([`available`]) may compute with
//! them (the 3D engine's `WorldLanes::of`, the Elman brain, the tests). The module is hidden
//! from the documentation for that reason: it is the workspace's, not a public interface.

use crate::{LaneMask, Lanes};
use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// N f64 lanes, `N / 4` registers.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(32))]
pub struct Avx<const N: usize>([f64; N]);

/// One bool per lane as a lane's sign bit (comparisons set all its bits).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
pub struct AvxMask<const N: usize>([f64; N]);

/// Whether this CPU can run [`Avx`] values: AVX2, and FMA for [`Lanes::mul_add`] (every CPU
/// with AVX2 has it; a virtual machine may hide it).
pub fn available() -> bool {
    is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma")
}

impl<const N: usize> Avx<N> {
    /// Registers per value: `WorldLanes::of` makes `Avx` values only for N a multiple of 4 (an
    /// assertion here would stop `WorldLanes<N>` of other N from compiling at all).
    const CHUNKS: usize = N / 4;

    #[inline(always)]
    fn load(&self, chunk: usize) -> __m256d {
        // SAFETY: in bounds (chunk < N / 4), aligned to 32 bytes; the CPU has AVX2 (module doc)
        unsafe { _mm256_load_pd(self.0.as_ptr().add(4 * chunk)) }
    }

    #[inline(always)]
    fn store(&mut self, chunk: usize, v: __m256d) {
        // SAFETY: as in `load`
        unsafe { _mm256_store_pd(self.0.as_mut_ptr().add(4 * chunk), v) }
    }
}

impl<const N: usize> AvxMask<N> {
    #[inline(always)]
    fn load(&self, chunk: usize) -> __m256d {
        // SAFETY: as in `Avx::load`
        unsafe { _mm256_load_pd(self.0.as_ptr().add(4 * chunk)) }
    }

    #[inline(always)]
    fn store(&mut self, chunk: usize, v: __m256d) {
        // SAFETY: as in `Avx::load`
        unsafe { _mm256_store_pd(self.0.as_mut_ptr().add(4 * chunk), v) }
    }
}

/// `$a` and `$b` (each `Avx` or `AvxMask`) chunk by chunk through the intrinsic `$f` into a new
/// `$out`.
macro_rules! chunks {
    ($out:ident, $a:expr, $b:expr, $f:ident) => {{
        let mut out = $out([0.0; N]);
        for c in 0..Avx::<N>::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc)
            out.store(c, unsafe { $f($a.load(c), $b.load(c)) });
        }
        out
    }};
}

/// A comparison, chunk by chunk, with the predicate `$p`.
macro_rules! compare {
    ($a:expr, $b:expr, $p:ident) => {{
        let mut out = AvxMask([0.0; N]);
        for c in 0..Avx::<N>::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc)
            out.store(c, unsafe { _mm256_cmp_pd::<$p>($a.load(c), $b.load(c)) });
        }
        out
    }};
}

macro_rules! arithmetic {
    ($tr:ident, $f:ident, $intrinsic:ident) => {
        impl<const N: usize> $tr for Avx<N> {
            type Output = Avx<N>;
            #[inline(always)]
            fn $f(self, o: Avx<N>) -> Avx<N> {
                chunks!(Avx, self, o, $intrinsic)
            }
        }
        impl<const N: usize> $tr<f64> for Avx<N> {
            type Output = Avx<N>;
            #[inline(always)]
            fn $f(self, o: f64) -> Avx<N> {
                chunks!(Avx, self, Avx::<N>::splat(o), $intrinsic)
            }
        }
        impl<const N: usize> $tr<Avx<N>> for f64 {
            type Output = Avx<N>;
            #[inline(always)]
            fn $f(self, o: Avx<N>) -> Avx<N> {
                chunks!(Avx, Avx::<N>::splat(self), o, $intrinsic)
            }
        }
    };
}
arithmetic!(Add, add, _mm256_add_pd);
arithmetic!(Sub, sub, _mm256_sub_pd);
arithmetic!(Mul, mul, _mm256_mul_pd);
arithmetic!(Div, div, _mm256_div_pd);

impl<const N: usize> Neg for Avx<N> {
    type Output = Avx<N>;
    #[inline(always)]
    fn neg(self) -> Avx<N> {
        chunks!(Avx, self, Avx::<N>::splat(-0.0), _mm256_xor_pd)
    }
}

impl<const N: usize> Lanes for Avx<N> {
    type Mask = AvxMask<N>;
    const LANES: usize = N;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        debug_assert!(N.is_multiple_of(4), "AVX lanes come in fours");
        Avx([x; N])
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
        let mut out = Avx([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc)
            out.store(c, unsafe { _mm256_sqrt_pd(self.load(c)) });
        }
        out
    }

    #[inline(always)]
    fn abs(self) -> Self {
        // andnot(a, b) is !a & b: the sign bit cleared
        chunks!(Avx, Avx::<N>::splat(-0.0), self, _mm256_andnot_pd)
    }

    #[inline(always)]
    fn lt(self, other: Self) -> AvxMask<N> {
        compare!(self, other, _CMP_LT_OQ)
    }

    #[inline(always)]
    fn gt(self, other: Self) -> AvxMask<N> {
        compare!(self, other, _CMP_GT_OQ)
    }

    #[inline(always)]
    fn ge(self, other: Self) -> AvxMask<N> {
        compare!(self, other, _CMP_GE_OQ)
    }

    #[inline(always)]
    fn le(self, other: Self) -> AvxMask<N> {
        compare!(self, other, _CMP_LE_OQ)
    }

    #[inline(always)]
    fn ne(self, other: Self) -> AvxMask<N> {
        compare!(self, other, _CMP_NEQ_UQ)
    }

    #[inline(always)]
    fn eq(self, other: Self) -> AvxMask<N> {
        compare!(self, other, _CMP_EQ_OQ)
    }

    #[inline(always)]
    fn select(mask: AvxMask<N>, then: Self, otherwise: Self) -> Self {
        let mut out = Avx([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc); blendv takes `then` where the sign bit is set
            out.store(c, unsafe {
                _mm256_blendv_pd(otherwise.load(c), then.load(c), mask.load(c))
            });
        }
        out
    }

    #[inline(always)]
    fn bits_and(self, mask: u64) -> Self {
        chunks!(Avx, self, Avx::<N>::splat(f64::from_bits(mask)), _mm256_and_pd)
    }

    #[inline(always)]
    fn bits_xor(self, other: Self) -> Self {
        chunks!(Avx, self, other, _mm256_xor_pd)
    }

    #[inline(always)]
    fn bits_shl<const S: i32>(self) -> Self {
        let mut out = Avx([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc)
            out.store(c, unsafe {
                _mm256_castsi256_pd(_mm256_slli_epi64::<S>(_mm256_castpd_si256(self.load(c))))
            });
        }
        out
    }

    #[inline(always)]
    fn sign_mask(self) -> AvxMask<N> {
        AvxMask(self.0)
    }

    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        let mut out = Avx([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX2 and FMA (module doc)
            out.store(c, unsafe { _mm256_fmadd_pd(self.load(c), a.load(c), b.load(c)) });
        }
        out
    }

    #[inline(always)]
    fn trunc(self) -> Self {
        let mut out = Avx([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc)
            out.store(c, unsafe {
                _mm256_round_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(self.load(c))
            });
        }
        out
    }
}

impl<const N: usize> LaneMask for AvxMask<N> {
    #[inline(always)]
    fn splat(b: bool) -> Self {
        AvxMask([f64::from_bits(if b { u64::MAX } else { 0 }); N])
    }

    #[inline(always)]
    fn get(&self, lane: usize) -> bool {
        self.0[lane].is_sign_negative()
    }

    #[inline(always)]
    fn set(&mut self, lane: usize, b: bool) {
        self.0[lane] = f64::from_bits(if b { u64::MAX } else { 0 });
    }

    #[inline(always)]
    fn and(self, other: Self) -> Self {
        chunks!(AvxMask, self, other, _mm256_and_pd)
    }

    #[inline(always)]
    fn or(self, other: Self) -> Self {
        chunks!(AvxMask, self, other, _mm256_or_pd)
    }

    #[inline(always)]
    fn not(self) -> Self {
        chunks!(AvxMask, self, AvxMask::<N>::splat(true), _mm256_xor_pd)
    }

    #[inline(always)]
    fn any(self) -> bool {
        let mut any = 0;
        for c in 0..Avx::<N>::CHUNKS {
            // SAFETY: the CPU has AVX2 (module doc)
            any |= unsafe { _mm256_movemask_pd(self.load(c)) };
        }
        any != 0
    }
}

impl<const N: usize> PartialEq for AvxMask<N> {
    /// Lane by lane, by the bool each lane holds (its sign bit).
    fn eq(&self, other: &Self) -> bool {
        (0..N).all(|l| self.get(l) == other.get(l))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every operation of the trait on awkward values against the portable lanes, bit for bit,
    /// in one register and in two.
    #[test]
    fn every_operation_gives_the_portable_bits() {
        if !available() {
            eprintln!("no AVX2 on this CPU: nothing to compare");
            return;
        }
        crate::conformance::every_operation_gives_the_portable_bits::<Avx<4>, 4>(Avx);
        crate::conformance::every_operation_gives_the_portable_bits::<Avx<8>, 8>(Avx);
    }
}
