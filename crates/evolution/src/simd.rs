//! Run-time choice of AVX for the dense kernels of CMA-ES (`linalg` and the covariance update).
//!
//! Every kernel exists once, as an `#[inline(always)]` body, and is compiled twice: plain, and
//! inside a `#[target_feature(enable = "avx")]` wrapper that this module's [`avx`] selects. The
//! kernels use only IEEE-754 additions and multiplications lane by lane (Rust never fuses them
//! into multiply–adds), so both versions give the same bits: a run is bit-identical on CPUs with
//! and without AVX, and for any thread count.

#[cfg(test)]
use std::sync::atomic::{AtomicBool, Ordering};

/// Whether the AVX versions of the kernels may run on this CPU.
#[inline]
pub(crate) fn avx() -> bool {
    #[cfg(test)]
    if FORCE_PORTABLE.load(Ordering::Relaxed) {
        return false;
    }
    #[cfg(target_arch = "x86_64")]
    {
        is_x86_feature_detected!("avx")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// Tests set this to run the portable kernels and compare their bits with the AVX ones.
#[cfg(test)]
pub(crate) static FORCE_PORTABLE: AtomicBool = AtomicBool::new(false);
