//! Malfunction (vsr-model.md §3.1): 1 once a breakable voxel has broken, else 0.
//!
//! vsrlab has no breakable voxels yet, so this sensor always reads 0. It exists so that placements
//! which request it (`spinedTouch-…-t-…`, `uniform-…+m-…`) keep the published input sizes.

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};

/// Declared domain.
pub(crate) const DOMAIN: (f64, f64) = (0.0, 1.0);

/// Always 0 (no voxel can break).
#[derive(Debug, Clone)]
pub(crate) struct Malfunction;

impl Malfunction {
    /// Writes the one reading.
    pub(crate) fn sense(&self, _frame: &Frame, out: &mut [f64]) {
        out[0] = 0.0;
    }
}

/// The malfunction sensor's description (it has no parameters): `SensorSpec::Malfunction`.
pub(crate) struct MalfunctionSpec;

impl SensorKind for MalfunctionSpec {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![DOMAIN]
    }

    fn build(&self, _site: Site) -> Node {
        Node::Malfunction(Malfunction)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, still_state};

    #[test]
    fn always_reads_zero() {
        let world = empty_world();
        let state = still_state();
        let mut out = [0.7];
        Malfunction.sense(
            &Frame {
                world: &world,
                state: &state,
                t: 12.0,
            },
            &mut out,
        );
        assert_eq!(out, [0.0]);
    }
}
