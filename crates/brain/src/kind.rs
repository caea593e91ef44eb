//! [`BrainKind`]: the behaviour every kind of brain description provides.

use crate::{BrainError, BrainShape, BrainSpec, Controller};
use std::fmt::Debug;

/// One kind of brain, as described in configs and robot files: its fields, its parameter vector and
/// how it builds its [`Controller`] for a body.
///
/// Each controller module has a description struct implementing this trait (for example
/// [`crate::MlpSpec`] next to [`crate::CentralizedMlpController`]); [`crate::BrainSpec`] wraps them
/// all and delegates to this trait. The default methods are those of a parameterless brain, or of a
/// wrapper (`step`, `smoothed`) when [`BrainKind::inner`] names the brain it wraps: a wrapper has no
/// parameters of its own, its parameters are the inner brain's.
pub trait BrainKind: Debug + Send + Sync {
    /// The `kind` tag, as in configs (the kebab-case name of the [`crate::BrainSpec`] variant).
    fn name(&self) -> &'static str;

    /// The brain this one wraps, for a wrapper. Default: none.
    fn inner(&self) -> Option<&BrainSpec> {
        None
    }

    /// [`BrainKind::inner`], mutable. Default: none.
    fn inner_mut(&mut self) -> Option<&mut BrainSpec> {
        None
    }

    /// Number of parameters this brain needs for a body whose voxels (voxel order) have these
    /// readings counts. Errors when the shape does not fit the body. Default: the inner brain's, or
    /// 0.
    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        match self.inner() {
            Some(inner) => inner.parameter_count(shape),
            None => Ok(0),
        }
    }

    /// The parameter vector (empty for an unfilled template). Default: the inner brain's, or empty.
    fn parameters(&self) -> &[f64] {
        self.inner().map_or(&[], BrainSpec::parameters)
    }

    /// Replaces the parameter vector; errors when a value is not finite (the count for a body is
    /// checked by [`BrainKind::build`]). Default: passed to the inner brain; without one, only an
    /// empty vector is accepted, an error on field `parameters` otherwise.
    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        if let Some(inner) = self.inner_mut() {
            return inner.as_kind_mut().set_parameters(params);
        }
        if params.is_empty() {
            Ok(())
        } else {
            Err(BrainError::Invalid {
                field: "parameters",
                msg: format!(
                    "expected 0 for a {} brain (it has none), got {}",
                    self.name(),
                    params.len()
                ),
            })
        }
    }

    /// Makes the brain start every episode from these plastic weights and never change them
    /// (the frozen-weight test, thesis §5.3.4.2). Default: the inner brain's, or an error on
    /// `kind` for brains without plastic weights.
    fn freeze_with(&mut self, weights: &[f64]) -> Result<(), BrainError> {
        match self.inner_mut() {
            Some(inner) => inner.as_kind_mut().freeze_with(weights),
            None => Err(no_plasticity(self.name())),
        }
    }

    /// Makes learning stop at simulated time `t` (s). Default: the inner brain's, or an error on
    /// `kind` for brains without plastic weights.
    fn stop_learning_at(&mut self, t: f64) -> Result<(), BrainError> {
        match self.inner_mut() {
            Some(inner) => inner.as_kind_mut().stop_learning_at(t),
            None => Err(no_plasticity(self.name())),
        }
    }

    /// Takes the transferable module of `source` (an evolved brain of another body) and fixes it
    /// in this brain, whose parameters then are the rest (thesis §4.2.4.1: an attention module
    /// moved to another body, the downstream network re-evolved). Default: the inner brain's,
    /// with the source's inner brain when it is a wrapper too; an error on `kind` for brains
    /// without a transferable module.
    fn transfer_from(&mut self, source: &BrainSpec) -> Result<(), BrainError> {
        let name = self.name();
        match self.inner_mut() {
            Some(inner) => inner
                .as_kind_mut()
                .transfer_from(source.as_kind().inner().unwrap_or(source)),
            None => Err(BrainError::Invalid {
                field: "kind",
                msg: format!("a {name} brain has no module to transfer (use an attention brain)"),
            }),
        }
    }

    /// Validates every field and builds the controller for a body whose voxels (voxel order) have
    /// these readings counts; a parameter vector of the wrong length is an error naming its field:
    /// "expected N for this body and sensors, got M".
    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError>;
}

/// The error of freezing a brain that does not learn.
fn no_plasticity(name: &str) -> BrainError {
    BrainError::Invalid {
        field: "kind",
        msg: format!("a {name} brain has no plastic weights to freeze (use a hebbian brain)"),
    }
}
