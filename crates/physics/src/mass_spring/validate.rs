//! The checks [`MassSpringBuilder::build`](super::MassSpringBuilder::build) runs; each error names
//! the element and the rule it breaks.

use super::builder::{PointDesc, QuadDesc, SpringDesc};
use super::handles::SpringId;
use super::{MassSpringError, MassSpringSettings};

fn invalid(msg: String) -> MassSpringError {
    MassSpringError::Invalid(msg)
}

fn positive(what: &str, v: f64) -> Result<(), MassSpringError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(format!("{what} must be positive and finite, got {v}")))
    }
}

fn non_negative(what: &str, v: f64) -> Result<(), MassSpringError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(invalid(format!("{what} must be finite and not negative, got {v}")))
    }
}

/// Time step, rates and constants.
pub(crate) fn settings(s: &MassSpringSettings) -> Result<(), MassSpringError> {
    positive("settings.dt", s.dt)?;
    if s.substeps == 0 {
        return Err(invalid("settings.substeps must be at least 1".into()));
    }
    non_negative("settings.gravity", s.gravity.abs())?;
    non_negative("settings.drag", s.drag)?;
    positive("settings.tracking_rate", s.tracking_rate)?;
    non_negative("settings.band_correction", s.band_correction)?;
    non_negative("settings.limit_correction", s.limit_correction)?;
    let (lo, hi) = s.target_range;
    if !(lo.is_finite() && hi.is_finite() && lo <= hi) {
        return Err(invalid(format!(
            "settings.target_range ({lo}, {hi}) must be finite with min <= max"
        )));
    }
    if let Some(g) = &s.ground {
        non_negative("settings.ground.height", g.height.abs())?;
        non_negative("settings.ground.stiffness", g.stiffness)?;
        non_negative("settings.ground.friction", g.friction)?;
        non_negative("settings.ground.friction_sharpness", g.friction_sharpness)?;
    }
    let c = &s.contact;
    non_negative("settings.contact.stiffness", c.stiffness)?;
    non_negative("settings.contact.offset", c.offset)?;
    non_negative("settings.contact.damping", c.damping)?;
    positive("settings.contact.friction", c.friction)?;
    non_negative("settings.contact.friction_gain", c.friction_gain)
}

/// Finite positions and velocities, positive masses.
pub(crate) fn points(p: &[PointDesc]) -> Result<(), MassSpringError> {
    for (i, p) in p.iter().enumerate() {
        let values = [p.position.0, p.position.1, p.velocity.0, p.velocity.1];
        if !values.iter().all(|v| v.is_finite()) {
            return Err(invalid(format!("point {i}: position and velocity must be finite")));
        }
        positive(&format!("point {i}: mass"), p.mass)?;
    }
    Ok(())
}

/// Existing, distinct ends; stiffness and band not negative.
pub(crate) fn spring(i: usize, s: &SpringDesc, n_points: usize) -> Result<(), MassSpringError> {
    if s.a.index() >= n_points || s.b.index() >= n_points || s.a == s.b {
        return Err(invalid(format!(
            "spring {i}: ends must be two different existing points"
        )));
    }
    non_negative(&format!("spring {i}: stiffness"), s.stiffness)?;
    non_negative(&format!("spring {i}: band"), s.band)
}

/// Limits on existing springs with bands not negative.
pub(crate) fn limits(l: &[(SpringId, f64)], n_springs: usize) -> Result<(), MassSpringError> {
    for (i, (s, band)) in l.iter().enumerate() {
        if s.index() >= n_springs {
            return Err(invalid(format!(
                "length limit {i}: spring {} does not exist",
                s.index()
            )));
        }
        non_negative(&format!("length limit {i}: band"), *band)?;
    }
    Ok(())
}

/// Actuators driving at least one existing spring.
pub(crate) fn actuators(a: &[Vec<SpringId>], n_springs: usize) -> Result<(), MassSpringError> {
    for (i, list) in a.iter().enumerate() {
        if list.is_empty() || list.iter().any(|s| s.index() >= n_springs) {
            return Err(invalid(format!(
                "actuator {i}: must drive one or more existing springs"
            )));
        }
    }
    Ok(())
}

/// An existing body and four distinct existing corners.
pub(crate) fn quad(i: usize, q: &QuadDesc, n_bodies: usize, n_points: usize) -> Result<(), MassSpringError> {
    if q.body.index() >= n_bodies {
        return Err(invalid(format!("quad {i}: body {} does not exist", q.body.index())));
    }
    let c = q.corners.map(|p| p.index());
    let distinct = (0..4).all(|a| (a + 1..4).all(|b| c[a] != c[b]));
    if !distinct || c.iter().any(|&p| p >= n_points) {
        return Err(invalid(format!(
            "quad {i}: corners must be four different existing points"
        )));
    }
    Ok(())
}
