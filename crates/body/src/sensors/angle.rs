//! Angle (vsr-model.md §3.1, §1.9): the voxel's orientation in radians.

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};
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
pub(crate) struct AngleSpec;

impl SensorKind for AngleSpec {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![DOMAIN]
    }

    fn build(&self, _site: Site) -> Node {
        Node::Angle(Angle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, still_state};

    #[test]
    fn reads_the_angle() {
        let world = empty_world();
        let mut state = still_state();
        state.angle = -0.3;
        let mut out = [0.0];
        Angle.sense(
            &Frame {
                world: &world,
                state: &state,
                t: 0.0,
            },
            &mut out,
        );
        assert_eq!(out, [-0.3]);
    }
}
