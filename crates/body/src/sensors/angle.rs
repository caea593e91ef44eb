//! Angle (vsr-model.md §3.1, §1.9): the voxel's orientation in radians.

use super::kind::Parameterless;
use super::node::{Frame, Node};
use std::f64::consts::PI;

/// Declared domain.
pub(crate) const DOMAIN: (f64, f64) = (-PI, PI);

/// Reads [`crate::VoxelState::angle`] (not wrapped: it may leave the domain, as in the original).
#[derive(Debug, Clone)]
pub(crate) struct Angle;

impl Angle {
    /// Writes the one reading.
    pub(crate) fn sense(&self, frame: &Frame, out: &mut [f64]) {
        out[0] = frame.state.angle;
    }
}

/// The angle sensor's description (it has no parameters): `SensorSpec::Angle`.
pub(crate) static SPEC: Parameterless = Parameterless {
    domain: DOMAIN,
    node: Node::Angle(Angle),
};

#[cfg(test)]
mod tests {
    use crate::sensors::node::testing::{read_once, still_state};
    use crate::sensors::SensorSpec;

    #[test]
    fn reads_the_angle() {
        let mut state = still_state();
        state.angle = -0.3;
        assert_eq!(read_once(&SensorSpec::Angle, &state, 0.0), [-0.3]);
    }
}
