//! Area ratio (vsr-model.md §3.1): the voxel's current area over its rest area L².

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};

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
pub(crate) struct AreaRatioSpec;

impl SensorKind for AreaRatioSpec {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![DOMAIN]
    }

    fn build(&self, _site: Site) -> Node {
        Node::AreaRatio(AreaRatio)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, still_state};

    #[test]
    fn reads_the_area_ratio() {
        let world = empty_world();
        let mut state = still_state();
        state.area_ratio = 0.83;
        let mut out = [0.0];
        AreaRatio.sense(
            &Frame {
                world: &world,
                state: &state,
                t: 0.0,
            },
            &mut out,
        );
        assert_eq!(out, [0.83]);
    }
}
