//! Wrapper sensors (vsr-model.md §3.2): an inner sensor whose readings are transformed, one output
//! reading per inner reading — average, trend, normalization, soft normalization and noise.
//!
//! Running side: [`Wrapped`] holds the running inner sensor and a [`Transform`] (the wrapper's own
//! state: sample window, domains, noise stream), so that reading, resetting and walking the tree are
//! written once. Description side: a [`WrapperKind`] gives its [`SensorKind`] from the inner
//! sensor's (the noisy wrapper, whose checks and noise streams depend on its nesting, implements
//! [`SensorKind`] itself).

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};
use super::spec::SensorSpec;
use vsrlab_field::FieldError;

/// What a wrapper does to its inner sensor's readings at each step.
pub(crate) trait Transform {
    /// Turns `readings`, the inner sensor's readings at time `t`, into the wrapper's, in place.
    fn apply(&mut self, t: f64, readings: &mut [f64]);

    /// Back to the state at construction (default: there is nothing to forget).
    fn reset(&mut self) {}
}

/// A running wrapper: the inner sensor and the transform of its readings.
#[derive(Debug, Clone)]
pub(crate) struct Wrapped<T> {
    inner: Box<Node>,
    transform: T,
}

impl<T: Transform> Wrapped<T> {
    /// Applies `transform` to the readings of `inner`.
    pub(crate) fn new(inner: Box<Node>, transform: T) -> Wrapped<T> {
        Wrapped { inner, transform }
    }

    /// Reads the inner sensor into `out` and transforms the readings there.
    pub(crate) fn sense(&mut self, frame: &Frame, out: &mut [f64]) {
        self.inner.sense(frame, out);
        self.transform.apply(frame.t, out);
    }

    /// Back to the state at construction, inner sensor included.
    pub(crate) fn reset(&mut self) {
        self.transform.reset();
        self.inner.reset();
    }

    /// The wrapped sensor.
    pub(crate) fn inner(&self) -> &Node {
        &self.inner
    }
}

/// The description of a wrapper whose checks and running inner sensor are those of its inner
/// description (average, trend, normalization, soft normalization); its [`SensorKind`] follows.
pub(crate) trait WrapperKind {
    /// The wrapped sensor.
    fn inner(&self) -> &SensorSpec;

    /// Declared domain of an output reading whose inner reading has domain `inner`.
    fn domain(&self, inner: (f64, f64)) -> (f64, f64);

    /// Checks this wrapper's own parameters (default: it has none to check).
    fn check(&self) -> Result<(), FieldError> {
        Ok(())
    }

    /// The running wrapper around `inner`, the running inner sensor, both placed at `site`.
    fn wrap(&self, inner: Box<Node>, site: Site) -> Node;
}

impl<W: WrapperKind> SensorKind for W {
    /// One reading per inner reading.
    fn dimension(&self) -> usize {
        self.inner().dimension()
    }

    fn domains(&self) -> Vec<(f64, f64)> {
        self.inner().domains().into_iter().map(|d| self.domain(d)).collect()
    }

    /// This wrapper's parameters, then the inner sensor's.
    fn validate(&self, noisy_depth: usize) -> Result<(), FieldError> {
        self.check()?;
        self.inner().validate_at(noisy_depth).map_err(|e| e.at("inner"))
    }

    fn build(&self, site: Site) -> Node {
        self.wrap(Box::new(Node::build(self.inner(), site)), site)
    }
}
