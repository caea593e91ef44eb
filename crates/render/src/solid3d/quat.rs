//! Unit quaternions (w, x, y, z) as recorded in `voxel_quat`: turning a voxel's body axes into
//! world axes.

use super::vec3::Vec3;

/// A rotation as a quaternion w, x, y, z.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Quat([f64; 4]);

impl Quat {
    /// No rotation.
    pub const IDENTITY: Quat = Quat([1.0, 0.0, 0.0, 0.0]);

    /// The rotation of recorded values w, x, y, z, normalised; the identity when they are missing,
    /// not finite or all zero (a damaged trace still draws).
    pub fn from_slice(values: Option<&[f64]>) -> Quat {
        let Some(&[w, x, y, z]) = values else {
            return Quat::IDENTITY;
        };
        let norm = (w * w + x * x + y * y + z * z).sqrt();
        if norm > 0.0 && norm.is_finite() {
            Quat([w / norm, x / norm, y / norm, z / norm])
        } else {
            Quat::IDENTITY
        }
    }

    /// `v` rotated: v + 2w (u × v) + 2 u × (u × v), with u the vector part.
    pub fn rotate(self, v: Vec3) -> Vec3 {
        let [w, x, y, z] = self.0;
        let u = Vec3::new(x, y, z);
        let t = u.cross(v) * 2.0;
        v + t * w + u.cross(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn a_quarter_turn_about_z_takes_x_to_y() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let q = Quat::from_slice(Some(&[h, 0.0, 0.0, h]));
        assert!(close(q.rotate(Vec3::new(1.0, 0.0, 0.0)), Vec3::new(0.0, 1.0, 0.0)));
        assert!(close(q.rotate(Vec3::new(0.0, 0.0, 2.0)), Vec3::new(0.0, 0.0, 2.0)));
    }

    #[test]
    fn unusable_values_give_the_identity() {
        for values in [
            None,
            Some(&[0.0; 4][..]),
            Some(&[f64::NAN, 0.0, 0.0, 0.0][..]),
            Some(&[1.0][..]),
        ] {
            assert_eq!(Quat::from_slice(values), Quat::IDENTITY);
        }
        // not normalised: still a pure rotation
        let q = Quat::from_slice(Some(&[2.0, 0.0, 0.0, 0.0]));
        assert!(close(q.rotate(Vec3::new(1.0, 2.0, 3.0)), Vec3::new(1.0, 2.0, 3.0)));
    }
}
