//! Central pattern generator (vsr-model.md §3.3, `cpg`): a 1 Hz sine of simulated time,
//! sin(−2πt), the same on every voxel that carries it.

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};
use std::f64::consts::TAU;

/// Declared domain.
pub(crate) const DOMAIN: (f64, f64) = (-1.0, 1.0);

/// sin(−2πt) with t the simulated time in seconds.
#[derive(Debug, Clone)]
pub(crate) struct Cpg;

impl Cpg {
    /// Writes the one reading.
    pub(crate) fn sense(&self, frame: &Frame, out: &mut [f64]) {
        out[0] = (-TAU * frame.t).sin();
    }
}

/// The CPG sensor's description (it has no parameters): `SensorSpec::Cpg`.
pub(crate) struct CpgSpec;

impl SensorKind for CpgSpec {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![DOMAIN]
    }

    fn build(&self, _site: Site) -> Node {
        Node::Cpg(Cpg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, still_state};

    #[test]
    fn is_a_one_hertz_sine_going_down_first() {
        let world = empty_world();
        let state = still_state();
        let read = |t| {
            let mut out = [0.0];
            Cpg.sense(
                &Frame {
                    world: &world,
                    state: &state,
                    t,
                },
                &mut out,
            );
            out[0]
        };
        assert!(read(0.0).abs() < 1e-12);
        assert!((read(0.25) + 1.0).abs() < 1e-12);
        assert!((read(0.75) - 1.0).abs() < 1e-12);
        assert!((read(1.3) - read(0.3)).abs() < 1e-12);
    }
}
