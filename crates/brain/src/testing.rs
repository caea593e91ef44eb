//! Fixtures shared by the unit tests of the brain kinds.

use crate::{BrainError, BrainShape, BrainSpec};
use vsrlab_body::Morphology;

/// The biped-4x3 (10 voxels) with 4 readings per voxel: the body of the published check values.
pub(crate) fn biped() -> (Morphology, Vec<usize>) {
    (Morphology::named("biped-4x3").unwrap(), vec![4; 10])
}

/// The error of building `spec` for the biped whose voxels have these readings counts (panics if it
/// builds).
pub(crate) fn build_error(spec: &BrainSpec, readings_per_voxel: &[usize]) -> BrainError {
    match spec.build(&BrainShape::grid(&biped().0, readings_per_voxel)) {
        Ok(_) => panic!("{spec:?} builds"),
        Err(err) => err,
    }
}

/// Asserts that `err` is [`BrainError::Invalid`] on `field`.
pub(crate) fn assert_invalid(err: &BrainError, field: &str) {
    assert!(
        matches!(err, BrainError::Invalid { field: f, .. } if *f == field),
        "expected an error on {field}, got {err}"
    );
}
