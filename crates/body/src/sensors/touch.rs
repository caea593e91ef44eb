//! Touch (vsr-model.md §3.1): 1 while any corner of the voxel touches something that is not part of
//! the same robot (ground, obstacles, other robots), else 0.

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};

/// Declared domain.
pub(crate) const DOMAIN: (f64, f64) = (0.0, 1.0);

/// Reads [`crate::VoxelState::touching`] as 0 or 1.
#[derive(Debug, Clone)]
pub(crate) struct Touch;

impl Touch {
    /// Writes the one reading.
    pub(crate) fn sense(&self, frame: &Frame, out: &mut [f64]) {
        out[0] = if frame.state.touching { 1.0 } else { 0.0 };
    }
}

/// The touch sensor's description (it has no parameters): `SensorSpec::Touch`.
pub(crate) struct TouchSpec;

impl SensorKind for TouchSpec {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![DOMAIN]
    }

    fn build(&self, _site: Site) -> Node {
        Node::Touch(Touch)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, still_state};

    #[test]
    fn touching_reads_one() {
        let world = empty_world();
        let mut state = still_state();
        let mut out = [0.5];
        Touch.sense(
            &Frame {
                world: &world,
                state: &state,
                t: 0.0,
            },
            &mut out,
        );
        assert_eq!(out, [0.0]);
        state.touching = true;
        Touch.sense(
            &Frame {
                world: &world,
                state: &state,
                t: 0.0,
            },
            &mut out,
        );
        assert_eq!(out, [1.0]);
    }
}
