//! N f64 lanes in AVX-512 instructions, eight per 512-bit register (N a multiple of 8): the
//! laned engines' number type on CPUs that have AVX-512F, twice the lanes per instruction of
//! [`Avx`](crate::avx::Avx). Masks are the CPU's own mask registers, one bit per lane. Each
//! operation is the IEEE operation of the scalar engine (no fused multiply–add but `mul_add`), so every lane
//! keeps the scalar bits.
//!
//! As with `Avx`, only code that checked the CPU first ([`available`]) may compute with these
//! values; the module is hidden from the documentation for that reason.

use crate::{LaneMask, Lanes};
use std::arch::x86_64::*;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// N f64 lanes, `N / 8` registers.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Avx512<const N: usize>([f64; N]);

/// One bool per lane, lane `l` in bit `l` (N ≤ 64).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Avx512Mask<const N: usize>(u64);

/// Whether this CPU can run [`Avx512`] values.
pub fn available() -> bool {
    is_x86_feature_detected!("avx512f")
}

impl<const N: usize> Avx512<N> {
    /// Registers per value (the engines make `Avx512` values only for N a multiple of 8).
    const CHUNKS: usize = N / 8;

    /// Every lane's bit set.
    const ALL: u64 = if N >= 64 { u64::MAX } else { (1 << N) - 1 };

    #[inline(always)]
    fn load(&self, chunk: usize) -> __m512d {
        // SAFETY: in bounds (chunk < N / 8), aligned to 64 bytes; the CPU has AVX-512F (module doc)
        unsafe { _mm512_load_pd(self.0.as_ptr().add(8 * chunk)) }
    }

    #[inline(always)]
    fn store(&mut self, chunk: usize, v: __m512d) {
        // SAFETY: as in `load`
        unsafe { _mm512_store_pd(self.0.as_mut_ptr().add(8 * chunk), v) }
    }

    #[inline(always)]
    fn bits(&self, chunk: usize) -> __m512i {
        // SAFETY: a reinterpretation; the CPU has AVX-512F (module doc)
        unsafe { _mm512_castpd_si512(self.load(chunk)) }
    }

    #[inline(always)]
    fn store_bits(&mut self, chunk: usize, v: __m512i) {
        // SAFETY: as in `bits`
        self.store(chunk, unsafe { _mm512_castsi512_pd(v) })
    }
}

impl<const N: usize> Avx512Mask<N> {
    /// Chunk `chunk`'s eight lanes as a mask register.
    #[inline(always)]
    fn chunk(self, chunk: usize) -> __mmask8 {
        (self.0 >> (8 * chunk)) as __mmask8
    }
}

/// `$a` and `$b` chunk by chunk through the intrinsic `$f` into a new `Avx512`.
macro_rules! chunks {
    ($a:expr, $b:expr, $f:ident) => {{
        let mut out = Avx512([0.0; N]);
        for c in 0..Avx512::<N>::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc)
            out.store(c, unsafe { $f($a.load(c), $b.load(c)) });
        }
        out
    }};
}

/// `$a` and `$b`'s bits chunk by chunk through the integer intrinsic `$f`.
macro_rules! bit_chunks {
    ($a:expr, $b:expr, $f:ident) => {{
        let mut out = Avx512([0.0; N]);
        for c in 0..Avx512::<N>::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc)
            out.store_bits(c, unsafe { $f($a.bits(c), $b.bits(c)) });
        }
        out
    }};
}

/// A comparison, chunk by chunk, with the predicate `$p`, into a mask.
macro_rules! compare {
    ($a:expr, $b:expr, $p:ident) => {{
        let mut bits = 0u64;
        for c in 0..Avx512::<N>::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc)
            let m = unsafe { _mm512_cmp_pd_mask::<$p>($a.load(c), $b.load(c)) };
            bits |= (m as u64) << (8 * c);
        }
        Avx512Mask(bits)
    }};
}

macro_rules! arithmetic {
    ($tr:ident, $f:ident, $intrinsic:ident) => {
        impl<const N: usize> $tr for Avx512<N> {
            type Output = Avx512<N>;
            #[inline(always)]
            fn $f(self, o: Avx512<N>) -> Avx512<N> {
                chunks!(self, o, $intrinsic)
            }
        }
        impl<const N: usize> $tr<f64> for Avx512<N> {
            type Output = Avx512<N>;
            #[inline(always)]
            fn $f(self, o: f64) -> Avx512<N> {
                chunks!(self, Avx512::<N>::splat(o), $intrinsic)
            }
        }
        impl<const N: usize> $tr<Avx512<N>> for f64 {
            type Output = Avx512<N>;
            #[inline(always)]
            fn $f(self, o: Avx512<N>) -> Avx512<N> {
                chunks!(Avx512::<N>::splat(self), o, $intrinsic)
            }
        }
    };
}
arithmetic!(Add, add, _mm512_add_pd);
arithmetic!(Sub, sub, _mm512_sub_pd);
arithmetic!(Mul, mul, _mm512_mul_pd);
arithmetic!(Div, div, _mm512_div_pd);

impl<const N: usize> Neg for Avx512<N> {
    type Output = Avx512<N>;
    #[inline(always)]
    fn neg(self) -> Avx512<N> {
        bit_chunks!(self, Avx512::<N>::splat(-0.0), _mm512_xor_si512)
    }
}

impl<const N: usize> Lanes for Avx512<N> {
    type Mask = Avx512Mask<N>;
    const LANES: usize = N;

    #[inline(always)]
    fn splat(x: f64) -> Self {
        debug_assert!(N.is_multiple_of(8) && N <= 64, "AVX-512 lanes come in eights");
        Avx512([x; N])
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
        let mut out = Avx512([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc)
            out.store(c, unsafe { _mm512_sqrt_pd(self.load(c)) });
        }
        out
    }

    #[inline(always)]
    fn abs(self) -> Self {
        // andnot(a, b) is !a & b: the sign bit cleared
        bit_chunks!(Avx512::<N>::splat(-0.0), self, _mm512_andnot_si512)
    }

    #[inline(always)]
    fn lt(self, other: Self) -> Avx512Mask<N> {
        compare!(self, other, _CMP_LT_OQ)
    }

    #[inline(always)]
    fn gt(self, other: Self) -> Avx512Mask<N> {
        compare!(self, other, _CMP_GT_OQ)
    }

    #[inline(always)]
    fn ge(self, other: Self) -> Avx512Mask<N> {
        compare!(self, other, _CMP_GE_OQ)
    }

    #[inline(always)]
    fn le(self, other: Self) -> Avx512Mask<N> {
        compare!(self, other, _CMP_LE_OQ)
    }

    #[inline(always)]
    fn ne(self, other: Self) -> Avx512Mask<N> {
        compare!(self, other, _CMP_NEQ_UQ)
    }

    #[inline(always)]
    fn eq(self, other: Self) -> Avx512Mask<N> {
        compare!(self, other, _CMP_EQ_OQ)
    }

    #[inline(always)]
    fn select(mask: Avx512Mask<N>, then: Self, otherwise: Self) -> Self {
        let mut out = Avx512([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc); the blend takes `then` where the bit is set
            out.store(c, unsafe {
                _mm512_mask_blend_pd(mask.chunk(c), otherwise.load(c), then.load(c))
            });
        }
        out
    }

    #[inline(always)]
    fn bits_and(self, mask: u64) -> Self {
        bit_chunks!(self, Avx512::<N>::splat(f64::from_bits(mask)), _mm512_and_si512)
    }

    #[inline(always)]
    fn bits_xor(self, other: Self) -> Self {
        bit_chunks!(self, other, _mm512_xor_si512)
    }

    #[inline(always)]
    fn bits_shl<const S: i32>(self) -> Self {
        let mut out = Avx512([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc); the count is the low 64 bits of the
            // 128-bit operand
            out.store_bits(c, unsafe {
                _mm512_sll_epi64(self.bits(c), _mm_set_epi64x(0, S as i64))
            });
        }
        out
    }

    #[inline(always)]
    fn sign_mask(self) -> Avx512Mask<N> {
        let mut bits = 0u64;
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc); the sign bit is the integer's
            let m = unsafe { _mm512_cmplt_epi64_mask(self.bits(c), _mm512_setzero_si512()) };
            bits |= (m as u64) << (8 * c);
        }
        Avx512Mask(bits)
    }

    #[inline(always)]
    fn mul_add(self, a: Self, b: Self) -> Self {
        let mut out = Avx512([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc), whose fused multiply–add this is
            out.store(c, unsafe { _mm512_fmadd_pd(self.load(c), a.load(c), b.load(c)) });
        }
        out
    }

    #[inline(always)]
    fn trunc(self) -> Self {
        let mut out = Avx512([0.0; N]);
        for c in 0..Self::CHUNKS {
            // SAFETY: the CPU has AVX-512F (module doc)
            out.store(c, unsafe {
                _mm512_roundscale_pd::<{ _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC }>(self.load(c))
            });
        }
        out
    }
}

impl<const N: usize> LaneMask for Avx512Mask<N> {
    #[inline(always)]
    fn splat(b: bool) -> Self {
        Avx512Mask(if b { Avx512::<N>::ALL } else { 0 })
    }

    #[inline(always)]
    fn get(&self, lane: usize) -> bool {
        self.0 >> lane & 1 == 1
    }

    #[inline(always)]
    fn set(&mut self, lane: usize, b: bool) {
        self.0 = self.0 & !(1 << lane) | (b as u64) << lane;
    }

    #[inline(always)]
    fn and(self, other: Self) -> Self {
        Avx512Mask(self.0 & other.0)
    }

    #[inline(always)]
    fn or(self, other: Self) -> Self {
        Avx512Mask(self.0 | other.0)
    }

    #[inline(always)]
    fn not(self) -> Self {
        Avx512Mask(self.0 ^ Avx512::<N>::ALL)
    }

    #[inline(always)]
    fn any(self) -> bool {
        self.0 != 0
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
            eprintln!("no AVX-512 on this CPU: nothing to compare");
            return;
        }
        crate::conformance::every_operation_gives_the_portable_bits::<Avx512<8>, 8>(Avx512);
        crate::conformance::every_operation_gives_the_portable_bits::<Avx512<16>, 16>(Avx512);
    }
}
