//! Central pattern generator (vsr-model.md §3.3, `cpg`): a 1 Hz sine of simulated time,
//! sin(−2πt), the same on every voxel that carries it.

use super::kind::Parameterless;
use super::node::{Frame, Node};
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
pub(crate) static SPEC: Parameterless = Parameterless {
    domain: DOMAIN,
    node: Node::Cpg(Cpg),
};

#[cfg(test)]
mod tests {
    use crate::sensors::node::testing::{read_once, still_state};
    use crate::sensors::SensorSpec;

    #[test]
    fn is_a_one_hertz_sine_going_down_first() {
        let read = |t| read_once(&SensorSpec::Cpg, &still_state(), t)[0];
        assert!(read(0.0).abs() < 1e-12);
        assert!((read(0.25) + 1.0).abs() < 1e-12);
        assert!((read(0.75) - 1.0).abs() < 1e-12);
        assert!((read(1.3) - read(0.3)).abs() < 1e-12);
    }
}
