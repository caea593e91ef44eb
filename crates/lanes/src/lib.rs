//! `vsrlab-lanes`: f64 lanes ([`F64s`]), one value per episode of a population stepped together,
//! and elementary functions ([`sin`], [`cos`], [`sin_cos`], [`acos`], [`tanh`]) written once over lanes, so
//! that the scalar form (one lane) and every lane of the vector form give the same bits, on every
//! machine: they use only IEEE additions, multiplications, divisions and square roots, never the
//! platform's libm, whose bits differ between versions and CPUs (glibc picks an FMA variant at run
//! time). They are within 1 ulp (`tanh`: 2) of the correctly rounded value over the ranges the engines use
//! (tests below measure it against libm). [`fdlibm_tanh`] is the exception that proves the rule:
//! glibc's own evaluation of tanh on FMA CPUs, written out, so that the results computed with the
//! platform's tanh keep their bits, now on every machine and in lanes.
#![warn(missing_docs)]

mod acos;
#[cfg(target_arch = "x86_64")]
#[doc(hidden)]
pub mod avx;
#[cfg(target_arch = "x86_64")]
#[doc(hidden)]
pub mod avx512;
#[cfg(test)]
mod conformance;
mod f64s;
mod fdlibm_tanh;
mod lane;
mod tanh;
mod trig;

pub use acos::acos;
pub use f64s::{F64s, Mask};
pub use fdlibm_tanh::{fdlibm_tanh, fdlibm_tanh_in_place};
pub use lane::{and, any, not, or, LaneMask, Lanes};
pub use tanh::tanh;
pub use trig::{cos, sin, sin_cos};
