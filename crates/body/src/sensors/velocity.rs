//! Velocity (vsr-model.md §3.1): the voxel's linear velocity, either in world axes or, when
//! `rotated`, projected on the voxel's own x axis (direction `angle`) and y axis (`angle + π/2`).

use super::kind::{check_positive, SensorKind};
use super::node::{Frame, Node, Site};
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics::Vec2;

/// Which velocity components a velocity sensor reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axes {
    /// The x component only.
    X,
    /// The y component only.
    Y,
    /// Both, x first.
    Xy,
}

/// Declared domain of each component: [−vmax, vmax].
pub(crate) fn domain(vmax: f64) -> (f64, f64) {
    (-vmax, vmax)
}

/// The velocity `v` of a voxel at `angle`, in world axes or in the voxel's own axes.
pub(crate) fn components(v: Vec2, angle: f64, rotated: bool) -> Vec2 {
    if rotated {
        let (sin, cos) = angle.sin_cos();
        Vec2::new(v.dot(Vec2::new(cos, sin)), v.dot(Vec2::new(-sin, cos)))
    } else {
        v
    }
}

/// Reads one or both velocity components.
#[derive(Debug, Clone)]
pub(crate) struct Velocity {
    rotated: bool,
    axes: Axes,
}

impl Velocity {
    /// A velocity sensor reporting `axes`, in the voxel's frame if `rotated`.
    pub(crate) fn new(rotated: bool, axes: Axes) -> Velocity {
        Velocity { rotated, axes }
    }

    /// Writes x, y or x then y.
    pub(crate) fn sense(&self, frame: &Frame, out: &mut [f64]) {
        let v = components(frame.state.velocity, frame.state.angle, self.rotated);
        match self.axes {
            Axes::X => out[0] = v.x,
            Axes::Y => out[0] = v.y,
            Axes::Xy => {
                out[0] = v.x;
                out[1] = v.y;
            }
        }
    }
}

/// Description of a velocity sensor (`{"kind": "velocity", "rotated": true, "vmax": 8.0, "axes": "xy"}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VelocitySpec {
    /// Project on the voxel's own x axis (its angle) and y axis (angle + π/2) instead of the
    /// world's.
    pub rotated: bool,
    /// Half-width of the domain (> 0).
    pub vmax: f64,
    /// Components reported.
    pub axes: Axes,
}

impl SensorKind for VelocitySpec {
    fn dimension(&self) -> usize {
        match self.axes {
            Axes::Xy => 2,
            Axes::X | Axes::Y => 1,
        }
    }

    fn domains(&self) -> Vec<(f64, f64)> {
        vec![domain(self.vmax); self.dimension()]
    }

    fn validate(&self, _noisy_depth: usize) -> Result<(), FieldError> {
        check_positive("vmax", "velocity vmax", self.vmax)
    }

    fn build(&self, _site: Site) -> Node {
        Node::Velocity(Velocity::new(self.rotated, self.axes))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{read_once, still_state};
    use crate::sensors::SensorSpec;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_6};

    fn read(rotated: bool, axes: Axes, velocity: Vec2, angle: f64) -> Vec<f64> {
        let mut state = still_state();
        state.velocity = velocity;
        state.angle = angle;
        let spec = SensorSpec::Velocity(VelocitySpec {
            rotated,
            vmax: 8.0,
            axes,
        });
        read_once(&spec, &state, 0.0)
    }

    #[test]
    fn unrotated_velocity_is_in_world_axes() {
        assert_eq!(read(false, Axes::Xy, Vec2::new(1.5, -2.0), 0.7), vec![1.5, -2.0]);
        assert_eq!(read(false, Axes::Y, Vec2::new(1.5, -2.0), 0.7), vec![-2.0]);
    }

    #[test]
    fn rotated_velocity_is_in_the_voxel_frame() {
        // turned by +90°: world +y is the voxel's +x, world −x its +y
        let v = read(true, Axes::Xy, Vec2::new(-1.0, 2.0), FRAC_PI_2);
        assert!((v[0] - 2.0).abs() < 1e-12 && (v[1] - 1.0).abs() < 1e-12, "{v:?}");
        // turned by 30°, moving along its own x axis at speed 3
        let along = Vec2::new(3.0 * FRAC_PI_6.cos(), 3.0 * FRAC_PI_6.sin());
        let x = read(true, Axes::X, along, FRAC_PI_6);
        let y = read(true, Axes::Y, along, FRAC_PI_6);
        assert!((x[0] - 3.0).abs() < 1e-12 && y[0].abs() < 1e-12, "{x:?} {y:?}");
    }
}
