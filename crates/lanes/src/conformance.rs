//! The test every vector form of [`Lanes`] passes: each operation of the trait, and the
//! elementary functions, on awkward values (NaN, ±0, infinities, subnormals) give the portable
//! lanes' bits in every lane.

use crate::{F64s, LaneMask, Lanes};

/// Values the comparison cycles through.
const VALUES: [f64; 12] = [
    0.1,
    -3.0,
    1e-310,
    f64::NAN,
    -0.0,
    0.0,
    f64::INFINITY,
    -2.5,
    7.0,
    1e300,
    -1e-300,
    0.75,
];

/// Compares every operation of `L` (N lanes, made from an array by `make`) with [`F64s`].
/// (A NaN's sign after an operation on two NaNs is not the same in every form, as the compiler
/// may swap a commutative operation's operands; the values hold no negative NaN.)
pub(crate) fn every_operation_gives_the_portable_bits<L: Lanes, const N: usize>(make: impl Fn([f64; N]) -> L) {
    for i in 0..VALUES.len() {
        let a: [f64; N] = std::array::from_fn(|l| VALUES[(i + l) % VALUES.len()]);
        let b: [f64; N] = std::array::from_fn(|l| VALUES[(i + 3 * l + 1) % VALUES.len()]);
        let (pa, pb) = (F64s(a), F64s(b));
        let (va, vb) = (make(a), make(b));
        let same = |p: F64s<N>, v: L, what: &str| {
            for l in 0..N {
                assert_eq!(p.0[l].to_bits(), v.get(l).to_bits(), "{what}, lane {l}: {a:?} {b:?}");
            }
        };
        let same_mask = |p: [bool; N], v: L::Mask, what: &str| {
            for (l, &p) in p.iter().enumerate() {
                assert_eq!(p, v.get(l), "{what}, lane {l}: {a:?} {b:?}");
            }
        };
        same(pa + pb, va + vb, "add");
        same(pa - pb, va - vb, "sub");
        same(pa * pb, va * vb, "mul");
        same(pa / pb, va / vb, "div");
        same(pa * 0.3 - 2.0, va * 0.3 - 2.0, "scalar operands");
        same(-pa, -va, "neg");
        same(pa.sqrt(), va.sqrt(), "sqrt");
        same(pa.abs(), va.abs(), "abs");
        same(pa.clamp(-1.0, 2.0), va.clamp(-1.0, 2.0), "clamp");
        same(
            pa.bits_and(0xffff_ffff_0000_0000),
            va.bits_and(0xffff_ffff_0000_0000),
            "and",
        );
        same(pa.bits_xor(pb), va.bits_xor(vb), "xor");
        same(pa.bits_and(3).bits_shl::<62>(), va.bits_and(3).bits_shl::<62>(), "shl");
        same(pa.sin_cos().0, va.sin_cos().0, "sin");
        same(pa.cos(), va.cos(), "cos");
        same(pa.acos(), va.acos(), "acos");
        same(pa.tanh(), va.tanh(), "tanh");
        same(pa.mul_add(pb, pa), va.mul_add(vb, va), "mul_add");
        same(pa.trunc(), va.trunc(), "trunc");
        same(
            crate::fdlibm_tanh::tanh_lanes(pa),
            crate::fdlibm_tanh::tanh_lanes(va),
            "fdlibm tanh",
        );
        let (pm, vm) = (pa.lt(pb), va.lt(vb));
        same_mask(pm, vm, "lt");
        same_mask(pa.gt(pb), va.gt(vb), "gt");
        same_mask(pa.ge(pb), va.ge(vb), "ge");
        same_mask(pa.le(pb), va.le(vb), "le");
        same_mask(pa.ne(pb), va.ne(vb), "ne");
        same_mask(pa.eq(pb), va.eq(vb), "eq");
        same_mask(pa.sign_mask(), va.sign_mask(), "sign");
        same_mask(pm.not(), vm.not(), "not");
        same_mask(pm.and(pa.gt(pb)), vm.and(va.gt(vb)), "and");
        same_mask(pm.or(pa.ne(pb)), vm.or(va.ne(vb)), "or");
        assert_eq!(pm.any(), vm.any());
        same(F64s::select(pm, pa, pb), L::select(vm, va, vb), "select");
    }
    assert!(!L::Mask::splat(false).any() && L::Mask::splat(true).any());
    assert_eq!(L::Mask::splat(true).not(), L::Mask::splat(false));
}
