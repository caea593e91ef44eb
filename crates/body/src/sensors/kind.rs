//! [`SensorKind`]: what every kind of sensor description provides, so that `SensorSpec` only
//! lists the kinds and delegates.
//!
//! Each sensor file (`velocity.rs`, `average.rs`, …) holds its running sensor, its description
//! (`VelocitySpec`, …) and this trait's implementation. Sensors without parameters (angle, touch, …)
//! describe themselves with a [`Parameterless`] value instead. The trait is crate-internal because
//! it builds [`Node`]s, the statically dispatched running sensors of the simulation's hot loop.

use super::node::{Node, Site};
use vsrlab_field::FieldError;

/// One kind of sensor: its readings, their domains, its checks and its running form.
pub(crate) trait SensorKind {
    /// Number of readings (default 1).
    fn dimension(&self) -> usize {
        1
    }

    /// Declared domain (min, max) of each reading, after wrapping.
    fn domains(&self) -> Vec<(f64, f64)>;

    /// Checks every parameter of the tree below; `noisy_depth` counts the `Noisy` wrappers above.
    /// The error's path is the parameter's in this description (`window`, `inner.range`); its
    /// message names the parameter in words and the accepted range. Default: nothing to check.
    fn validate(&self, noisy_depth: usize) -> Result<(), FieldError> {
        let _ = noisy_depth;
        Ok(())
    }

    /// The running form of this (validated) sensor placed at `site`.
    fn build(&self, site: Site) -> Node;
}

/// The description of a sensor without parameters (angle, area ratio, touch, CPG, malfunction): one
/// reading in a fixed domain, nothing to check, always the same running sensor.
pub(crate) struct Parameterless {
    /// Declared domain of the one reading.
    pub domain: (f64, f64),
    /// The running sensor (stateless: every placement gets a copy).
    pub node: Node,
}

impl SensorKind for Parameterless {
    fn domains(&self) -> Vec<(f64, f64)> {
        vec![self.domain]
    }

    fn build(&self, _site: Site) -> Node {
        self.node.clone()
    }
}

/// Errors unless `v` is finite and > 0: the error is on `field`, its message calls the
/// parameter `label` (`lidar range`).
pub(crate) fn check_positive(field: &str, label: &str, v: f64) -> Result<(), FieldError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(FieldError::new(
            field,
            format!("{label} must be a finite number > 0, got {v}"),
        ))
    }
}
