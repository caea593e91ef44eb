//! The three lattice axes, and the fixed 90° rotations that let every link be computed as if it
//! pointed along +X (`docs/voxelyze-model.md` §3.1).

use glam::{DQuat, DVec3};

/// A lattice axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Along x.
    X,
    /// Along y.
    Y,
    /// Along z.
    Z,
}

impl Axis {
    /// A vector in the link's canonical frame (the link along +X).
    pub fn to_x(self, v: DVec3) -> DVec3 {
        match self {
            Axis::X => v,
            Axis::Y => DVec3::new(v.y, -v.x, v.z),
            Axis::Z => DVec3::new(v.z, v.y, -v.x),
        }
    }

    /// A vector of the canonical frame back in lattice axes.
    pub fn back_from_x(self, v: DVec3) -> DVec3 {
        match self {
            Axis::X => v,
            Axis::Y => DVec3::new(-v.y, v.x, v.z),
            Axis::Z => DVec3::new(-v.z, v.y, v.x),
        }
    }

    /// A rotation in the link's canonical frame (the vector part mapped as a vector).
    pub fn quat_to_x(self, q: DQuat) -> DQuat {
        let v = self.to_x(DVec3::new(q.x, q.y, q.z));
        DQuat::from_xyzw(v.x, v.y, v.z, q.w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_canonical_frame_turns_each_axis_onto_x_and_back() {
        for (axis, unit) in [(Axis::X, DVec3::X), (Axis::Y, DVec3::Y), (Axis::Z, DVec3::Z)] {
            assert_eq!(axis.to_x(unit), DVec3::X);
            let v = DVec3::new(1.0, 2.0, 3.0);
            assert_eq!(axis.back_from_x(axis.to_x(v)), v);
        }
    }
}
