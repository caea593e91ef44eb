//! The quaternion operations of Voxelyze's `Quat3D` with its approximations (small-angle
//! branches, no renormalisation), on glam's `DQuat` (Hamilton product) and `DVec3`
//! (`docs/voxelyze-model.md` §6.4).

use glam::{DQuat, DVec3};

/// `q v q*`: `v` rotated by `q` (not assumed unit, as Voxelyze never renormalises).
pub fn rotate(q: DQuat, v: DVec3) -> DVec3 {
    let r = q * DQuat::from_xyzw(v.x, v.y, v.z, 0.0) * q.conjugate();
    DVec3::new(r.x, r.y, r.z)
}

/// `q* v q`: `v` rotated by the inverse of `q`.
pub fn rotate_inverse(q: DQuat, v: DVec3) -> DVec3 {
    let r = q.conjugate() * DQuat::from_xyzw(v.x, v.y, v.z, 0.0) * q;
    DVec3::new(r.x, r.y, r.z)
}

/// The rotation of rotation vector `r` (axis × angle), with Voxelyze's series for small angles.
pub fn from_rotation_vector(r: DVec3) -> DQuat {
    let h = r * 0.5;
    let h2 = h.length_squared();
    let (w, scale) = if h2 * h2 < 5.328e-15 {
        (1.0 - h2 / 2.0, 1.0 - h2 / 6.0)
    } else {
        let a = h2.sqrt();
        (a.cos(), a.sin() / a)
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
        v * (2.0 * q.w.acos() / s.sqrt())
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
    let theta = n.x.clamp(-1.0, 1.0).acos();
    if theta > std::f64::consts::PI - 1e-7 {
        return DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0);
    }
    let s = (theta / 2.0).sin() / (n.y * n.y + n.z * n.z).sqrt();
    DQuat::from_xyzw(0.0, n.z * s, -n.y * s, (theta / 2.0).cos())
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
