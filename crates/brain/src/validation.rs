//! Checks shared by the brain kinds when they validate their fields; each error names the field.

use crate::{BrainError, BrainShape};

/// Errors unless `v` is finite.
pub(crate) fn finite(field: &'static str, v: f64) -> Result<(), BrainError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("must be a finite number, got {v}"),
        })
    }
}

/// Errors unless `v` is finite and ≥ 0; `unit` follows the bound in the message (" seconds").
pub(crate) fn non_negative(field: &'static str, v: f64, unit: &str) -> Result<(), BrainError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("must be ≥ 0{unit}, got {v}"),
        })
    }
}

/// Errors with the index of the first non-finite value.
pub(crate) fn check_finite(field: &'static str, values: &[f64]) -> Result<(), BrainError> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(i) => Err(BrainError::Invalid {
            field,
            msg: format!("value {i} is {}, all must be finite numbers", values[i]),
        }),
    }
}

/// Replaces the parameter vector `target` with `params`, unless a value is not finite
/// ([`check_finite`]).
pub(crate) fn set_finite(field: &'static str, target: &mut Vec<f64>, params: &[f64]) -> Result<(), BrainError> {
    check_finite(field, params)?;
    *target = params.to_vec();
    Ok(())
}

/// Errors unless a parameter vector has the count this body and sensors need.
pub(crate) fn check_count(field: &'static str, expected: usize, got: usize) -> Result<(), BrainError> {
    if expected == got {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("expected {expected} for this body and sensors, got {got}"),
        })
    }
}

/// Errors unless there is one readings count per unit of the shape's layout.
pub(crate) fn check_units(shape: &BrainShape) -> Result<(), BrainError> {
    let (readings, units) = (shape.readings().len(), shape.units());
    if readings == units {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field: "readings_per_voxel",
            msg: format!("{readings} entries for a body of {units} voxels"),
        })
    }
}
