//! Area ratio (vsr-model.md §3.1): the voxel's current area over its rest area L².

use super::kind::Parameterless;
use super::node::{Frame, Node};

/// Declared domain: half to one and a half times the rest area.
pub(crate) const DOMAIN: (f64, f64) = (0.5, 1.5);

/// Reads [`crate::VoxelState::area_ratio`].
#[derive(Debug, Clone)]
pub(crate) struct AreaRatio;

impl AreaRatio {
    /// Writes the one reading.
    pub(crate) fn sense(&self, frame: &Frame, out: &mut [f64]) {
        out[0] = frame.state.area_ratio;
    }
}

/// The area ratio sensor's description (it has no parameters): `SensorSpec::AreaRatio`.
pub(crate) static SPEC: Parameterless = Parameterless {
    domain: DOMAIN,
    node: Node::AreaRatio(AreaRatio),
};

#[cfg(test)]
mod tests {
    use crate::sensors::node::testing::{read_once, still_state};
    use crate::sensors::SensorSpec;

    #[test]
    fn reads_the_area_ratio() {
        let mut state = still_state();
        state.area_ratio = 0.83;
        assert_eq!(read_once(&SensorSpec::AreaRatio, &state, 0.0), [0.83]);
    }
}
