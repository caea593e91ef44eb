//! The constants of a mass-spring world. [`MassSpringSettings::evogym`] (also the `Default`) holds
//! the values of EvoGym's simulator; `docs/evogym-model.md` says where each comes from.

use serde::{Deserialize, Serialize};

/// Everything a [`MassSpringWorld`](super::MassSpringWorld) needs besides its points and springs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MassSpringSettings {
    /// Length of one substep in seconds (EvoGym: 1e-4).
    pub dt: f64,
    /// Substeps per call of [`step`](super::MassSpringWorld::step) (EvoGym: 30).
    pub substeps: u32,
    /// Downward gravitational acceleration (EvoGym: 110, force `mass * gravity`).
    pub gravity: f64,
    /// Linear drag: force `-drag * velocity` on every point (EvoGym: 0.1).
    pub drag: f64,
    /// Rest-length tracking: before each substep a spring's rest length becomes its current length
    /// plus this fraction of (goal length - current length) (EvoGym: 0.006). With 1.0 springs are
    /// classical Hooke springs whose rest length is the goal.
    pub tracking_rate: f64,
    /// Targets are clipped into `[min, max]` before use (EvoGym: 0.6 and 1.6).
    pub target_range: (f64, f64),
    /// Fraction of a spring's excess over its loose band removed per substep (EvoGym: 0.8).
    pub band_correction: f64,
    /// Fraction of a spring's excess over a tight limit removed by that limit (EvoGym: 0.5).
    pub limit_correction: f64,
    /// The half-plane below `y = height`, if any.
    pub ground: Option<GroundPlane>,
    /// Point-against-boundary contacts between quads.
    pub contact: ContactSettings,
}

/// A penalty half-plane `y < height` with regularised Coulomb friction along x.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GroundPlane {
    /// Height of the surface (EvoGym: 0).
    pub height: f64,
    /// Normal force per unit depth (EvoGym: 1.4e7).
    pub stiffness: f64,
    /// Friction coefficient: friction is at most `friction * normal force` (EvoGym: 2.0).
    pub friction: f64,
    /// Sharpness of the friction's `tanh(sharpness * vx * normal force)` (EvoGym: 0.2).
    pub friction_sharpness: f64,
}

/// Constants of the penalty contact between a point and a boundary side of another quad.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactSettings {
    /// Normal force per unit of (depth + `offset`) (EvoGym: 2.1e6).
    pub stiffness: f64,
    /// Added to the depth, so a touching point is already pushed (EvoGym: 0.005).
    pub offset: f64,
    /// Damping of each involved point's own normal velocity (EvoGym: 140; the side's endpoints
    /// get half each).
    pub damping: f64,
    /// Friction coefficient inside `tanh` (EvoGym: 0.2).
    pub friction: f64,
    /// Gain in front of the friction (EvoGym: 1200).
    pub friction_gain: f64,
}

impl MassSpringSettings {
    /// EvoGym's constants: dt 1e-4, 30 substeps, gravity 110, drag 0.1, tracking 0.006, targets in
    /// [0.6, 1.6], 80 % band and 50 % limit correction, ground plane at y = 0.
    pub fn evogym() -> Self {
        Self {
            dt: 1e-4,
            substeps: 30,
            gravity: 110.0,
            drag: 0.1,
            tracking_rate: 0.006,
            target_range: (0.6, 1.6),
            band_correction: 0.8,
            limit_correction: 0.5,
            ground: Some(GroundPlane::evogym()),
            contact: ContactSettings::evogym(),
        }
    }

    /// The same settings without gravity, drag and ground: isolated springs.
    pub fn weightless() -> Self {
        Self {
            gravity: 0.0,
            drag: 0.0,
            ground: None,
            ..Self::evogym()
        }
    }
}

impl Default for MassSpringSettings {
    fn default() -> Self {
        Self::evogym()
    }
}

impl GroundPlane {
    /// EvoGym's ground at y = 0.
    pub fn evogym() -> Self {
        Self {
            height: 0.0,
            stiffness: 2_000_000.0 * 7.0,
            friction: 10.0 * 0.2,
            friction_sharpness: 0.2,
        }
    }
}

impl ContactSettings {
    /// EvoGym's object-to-object contact constants.
    pub fn evogym() -> Self {
        Self {
            stiffness: 300_000.0 * 7.0,
            offset: 0.005,
            damping: 140.0,
            friction: 0.2,
            friction_gain: 150.0 * 8.0,
        }
    }
}
