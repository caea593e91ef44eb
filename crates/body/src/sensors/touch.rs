//! Touch (vsr-model.md §3.1): 1 while any corner of the voxel touches something that is not part of
//! the same robot (ground, obstacles, other robots), else 0.

use super::kind::Parameterless;
use super::node::{Frame, Node};

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
pub(crate) static SPEC: Parameterless = Parameterless {
    domain: DOMAIN,
    node: Node::Touch(Touch),
};

#[cfg(test)]
mod tests {
    use crate::sensors::node::testing::{read_once, still_state};
    use crate::sensors::SensorSpec;

    #[test]
    fn touching_reads_one() {
        let mut state = still_state();
        assert_eq!(read_once(&SensorSpec::Touch, &state, 0.0), [0.0]);
        state.touching = true;
        assert_eq!(read_once(&SensorSpec::Touch, &state, 0.0), [1.0]);
    }
}
