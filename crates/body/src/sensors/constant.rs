//! Constant position (vsr-model.md §3.3, `px` and `py`): the voxel's relative place in the grid, a
//! value fixed when the robot is built.
//!
//! Column x of a grid W wide reads x/(W − 1), row y of a grid H tall reads y/(H − 1) (row 0 at the
//! bottom). A grid one cell wide (or tall) reads 0.5 on that axis: the original divides by zero
//! there and reads NaN.

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};
use serde::{Deserialize, Serialize};

/// A grid axis, for the constant position sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// Column: x/(W − 1).
    X,
    /// Row: y/(H − 1), row 0 at the bottom.
    Y,
}

/// Declared domain (the original's `Constant` domain [min(0, v), max(1, v)] with v in [0, 1]).
pub(crate) const DOMAIN: (f64, f64) = (0.0, 1.0);

/// Relative position of cell `c` along an axis with `n` cells: c/(n − 1), or 0.5 when n = 1.
pub(crate) fn relative_position(c: usize, n: usize) -> f64 {
    if n > 1 {
        c as f64 / (n - 1) as f64
    } else {
        0.5
    }
}

/// A fixed reading.
#[derive(Debug, Clone)]
pub(crate) struct ConstantPosition {
    value: f64,
}

impl ConstantPosition {
    /// A sensor that always reads `value`.
    pub(crate) fn new(value: f64) -> ConstantPosition {
        ConstantPosition { value }
    }

    /// Writes the one reading.
    pub(crate) fn sense(&self, _frame: &Frame, out: &mut [f64]) {
        out[0] = self.value;
    }
}

/// Description of a constant position sensor (`{"kind": "constant-position", "axis": "x"}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstantPositionSpec {
    /// Which axis.
    pub axis: Axis,
}

impl SensorKind for ConstantPositionSpec {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![DOMAIN]
    }

    fn build(&self, site: Site) -> Node {
        Node::ConstantPosition(ConstantPosition::new(match self.axis {
            Axis::X => site.rel.0,
            Axis::Y => site.rel.1,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{empty_world, frame, still_state};

    #[test]
    fn relative_positions_span_zero_to_one() {
        assert_eq!(relative_position(0, 5), 0.0);
        assert_eq!(relative_position(2, 5), 0.5);
        assert_eq!(relative_position(4, 5), 1.0);
        assert_eq!(relative_position(0, 1), 0.5);
    }

    #[test]
    fn reads_its_value_at_any_time() {
        let world = empty_world();
        let state = still_state();
        let s = ConstantPosition::new(0.25);
        let mut out = [0.0];
        s.sense(&frame(&world, &state, 3.0), &mut out);
        assert_eq!(out, [0.25]);
    }
}
