//! [`Controller`]: what every brain does at each control step.

use vsrlab_body::{Channel, Probe};

/// The plastic weights of a brain whose weights change during the episode (a Hebbian network's
/// synapses, an attention controller's matrices): for snapshots, freezing and histograms, read by
/// observers (not kept by traces).
pub const PLASTIC_WEIGHTS: Channel = Channel::traced("plastic_weights").untraced();

/// A brain: maps (time, readings) to actuations, possibly with internal state.
pub trait Controller: Send {
    /// Clears internal state, as at the start of an episode.
    fn reset(&mut self);
    /// Computes one actuation per unit (unit order) from all readings (unit order).
    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]);
    /// Publishes what does not change during the episode (a graph brain's neurons and edges).
    /// Default: nothing.
    fn describe(&self, _probe: &mut dyn Probe) {}
    /// Publishes this step's inner quantities (attention matrices, neuron outputs,
    /// [`PLASTIC_WEIGHTS`]), after [`Controller::control`]. Default: nothing.
    fn publish(&self, _probe: &mut dyn Probe) {}
}

/// The brain's [`PLASTIC_WEIGHTS`] at this step, if it has any (a convenience over
/// [`Controller::publish`] with a [`vsrlab_body::Capture`]).
pub fn plastic_weights(controller: &dyn Controller) -> Option<Vec<f64>> {
    let mut capture = vsrlab_body::Capture::new();
    controller.publish(&mut capture);
    capture.get(PLASTIC_WEIGHTS.name).map(<[f64]>::to_vec)
}

/// A boxed brain is a brain (so helpers taking `&dyn Controller` take a `Box` too).
impl<C: Controller + ?Sized> Controller for Box<C> {
    fn reset(&mut self) {
        (**self).reset();
    }
    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]) {
        (**self).control(t, readings, actuations);
    }
    fn describe(&self, probe: &mut dyn Probe) {
        (**self).describe(probe);
    }
    fn publish(&self, probe: &mut dyn Probe) {
        (**self).publish(probe);
    }
}
