//! The quaternion operations of Voxelyze's `Quat3D` with its approximations (small-angle
//! branches, no renormalisation), on glam's `DQuat` (Hamilton product) and `DVec3`
//! (`docs/voxelyze-model.md` §6.4).

use glam::{DQuat, DVec3};

/// `q v q*`: `v` rotated by `q` (not assumed unit, as Voxelyze never renormalises).
pub fn rotate(q: DQuat, v: DVec3) -> DVec3 {
    sandwich(q, v, q.conjugate())
}

/// `q* v q`: `v` rotated by the inverse of `q`.
pub fn rotate_inverse(q: DQuat, v: DVec3) -> DVec3 {
    sandwich(q.conjugate(), v, q)
}

/// The vector part of `a (v, 0) b`: the two Hamilton products as glam computes them, term for
/// term, without the terms of the pure quaternion's zero scalar part, as Voxelyze's
/// `RotateVec3D` (8 of 56 operations, and the unused scalar part). Leaving out a `± x·0` changes a
/// sum only when all its other terms are zero, and then only the sign of that zero.
fn sandwich(a: DQuat, v: DVec3, b: DQuat) -> DVec3 {
    let tx = a.w * v.x + a.y * v.z - a.z * v.y;
    let ty = a.w * v.y - a.x * v.z + a.z * v.x;
    let tz = a.w * v.z + a.x * v.y - a.y * v.x;
    let tw = -(a.x * v.x) - a.y * v.y - a.z * v.z;
    DVec3::new(
        tw * b.x + tx * b.w + ty * b.z - tz * b.y,
        tw * b.y - tx * b.z + ty * b.w + tz * b.x,
        tw * b.z + tx * b.y - ty * b.x + tz * b.w,
    )
}

/// The rotation of rotation vector `r` (axis × angle), with Voxelyze's series for small angles.
pub fn from_rotation_vector(r: DVec3) -> DQuat {
    let h = r * 0.5;
    let h2 = h.length_squared();
    let (w, scale) = if h2 * h2 < 5.328e-15 {
        (1.0 - h2 / 2.0, 1.0 - h2 / 6.0)
    } else {
        let a = h2.sqrt();
        let (sin, cos) = vsrlab_lanes::sin_cos(a);
        (cos, sin / a)
    };
    DQuat::from_xyzw(h.x * scale, h.y * scale, h.z * scale, w)
}

/// The rotation vector of `q`, with Voxelyze's series near the identity (no sign
/// canonicalisation: w < 0 gives an angle beyond π).
pub fn to_rotation_vector(q: DQuat) -> DVec3 {
    if q.w >= 1.0 || q.w <= -1.0 {
        return DVec3::ZERO;
    }
    let s = 1.0 - q.w * q.w;
    let v = DVec3::new(q.x, q.y, q.z);
    if s < 2.4e-3 {
        v * (2.0 * ((2.0 - 2.0 * q.w) / s).sqrt())
    } else {
        v * (2.0 * vsrlab_lanes::acos(q.w) / s.sqrt())
    }
}

/// The rotation that turns `d` onto +X (Voxelyze's `FromAngleToPosX`), with its first-order
/// branch for nearly aligned vectors; `current` is kept when `d` is zero.
pub fn align_to_x(d: DVec3, current: DQuat) -> DQuat {
    if d == DVec3::ZERO {
        return current;
    }
    let (ry, rz) = (d.y / d.x, d.z / d.x);
    if ry.abs() < 1.732e-2 && rz.abs() < 1.732e-2 && d.x != 0.0 {
        let (y, z) = (0.5 * rz, -0.5 * ry);
        return DQuat::from_xyzw(0.0, y, z, 1.0 - 0.5 * (y * y + z * z));
    }
    let n = d / d.length();
    let theta = vsrlab_lanes::acos(n.x.clamp(-1.0, 1.0));
    if theta > std::f64::consts::PI - 1e-7 {
        return DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0);
    }
    let (sin, cos) = vsrlab_lanes::sin_cos(theta / 2.0);
    let s = sin / (n.y * n.y + n.z * n.z).sqrt();
    DQuat::from_xyzw(0.0, n.z * s, -n.y * s, cos)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_vectors_round_trip_and_rotate_as_expected() {
        for r in [
            DVec3::new(0.3, -0.2, 0.1),
            DVec3::new(1e-5, 2e-5, -1e-5),
            DVec3::new(0.0, 0.0, 2.0),
        ] {
            let q = from_rotation_vector(r);
            assert!((to_rotation_vector(q) - r).length() < 1e-9, "{r}");
        }
        let quarter = from_rotation_vector(DVec3::new(0.0, 0.0, std::f64::consts::FRAC_PI_2));
        assert!((rotate(quarter, DVec3::X) - DVec3::Y).length() < 1e-12);
        assert!((rotate_inverse(quarter, DVec3::Y) - DVec3::X).length() < 1e-12);
    }

    #[test]
    fn rotations_without_the_zero_terms_give_the_full_products_bits() {
        let full = |a: DQuat, v: DVec3, b: DQuat| {
            let r = a * DQuat::from_xyzw(v.x, v.y, v.z, 0.0) * b;
            DVec3::new(r.x, r.y, r.z)
        };
        // a small deterministic generator: quaternions near and far from the identity, vectors
        // with exact zeros among their components (as the lattice's are)
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let mut compared = 0;
        for i in 0..20_000 {
            let q = match i % 3 {
                0 => DQuat::IDENTITY,
                1 => from_rotation_vector(DVec3::new(next(), next(), next()) * 1e-3),
                _ => DQuat::from_xyzw(next(), next(), next(), next()),
            };
            let mut v = DVec3::new(next(), next(), next()) * 0.01;
            if i % 4 == 0 {
                v.y = 0.0;
            }
            for (fast, slow) in [
                (rotate(q, v), full(q, v, q.conjugate())),
                (rotate_inverse(q, v), full(q.conjugate(), v, q)),
            ] {
                for k in 0..3 {
                    // equal as numbers; bit for bit unless both are zeros
                    assert_eq!(fast[k], slow[k], "{q} {v}");
                    if slow[k] != 0.0 {
                        assert_eq!(fast[k].to_bits(), slow[k].to_bits(), "{q} {v}");
                        compared += 1;
                    }
                }
            }
        }
        assert!(compared > 100_000);
    }

    #[test]
    fn align_to_x_turns_a_vector_onto_x() {
        for d in [
            DVec3::new(1.0, 0.5, -0.3),
            DVec3::new(0.1, 1.0, 0.0),
            DVec3::new(1.0, 1e-3, 1e-3),
        ] {
            let q = align_to_x(d, DQuat::IDENTITY);
            let turned = rotate(q, d);
            assert!(
                turned.y.abs() < 1e-6 * d.length() && turned.z.abs() < 1e-6 * d.length(),
                "{d} -> {turned}"
            );
            assert!(turned.x > 0.0);
        }
    }
}
