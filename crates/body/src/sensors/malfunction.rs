//! Malfunction (vsr-model.md §3.1): 1 once a breakable voxel has broken, else 0.
//!
//! vsrlab has no breakable voxels yet, so this sensor always reads 0. It exists so that placements
//! which request it (`spinedTouch-…-t-…`, `uniform-…+m-…`) keep the published input sizes.

use super::kind::Parameterless;
use super::node::{Frame, Node};

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
pub(crate) static SPEC: Parameterless = Parameterless {
    domain: DOMAIN,
    node: Node::Malfunction(Malfunction),
};

#[cfg(test)]
mod tests {
    use crate::sensors::node::testing::{read_once, still_state};
    use crate::sensors::SensorSpec;

    #[test]
    fn always_reads_zero() {
        assert_eq!(read_once(&SensorSpec::Malfunction, &still_state(), 12.0), [0.0]);
    }
}
