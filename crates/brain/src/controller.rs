//! [`Controller`]: what every brain does at each control step.

/// A brain: maps (time, readings) to actuations, possibly with internal state.
pub trait Controller: Send {
    /// Clears internal state, as at the start of an episode.
    fn reset(&mut self);
    /// Computes one actuation per voxel (grid order) from all readings (grid order).
    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]);
    /// Weights that change during the episode ("adaptive weights": a Hebbian network's synapses,
    /// an attention controller's matrices),
    /// for snapshots, freezing and histograms; `None` for brains whose weights are fixed.
    /// Default: `None`.
    fn adaptive_weights(&self) -> Option<&[f64]> {
        None
    }
    /// Attention matrices of every voxel, for drawing: (side r, n·r² values, voxel-major,
    /// row-major within a voxel); `None` for brains without attention. Default: `None`.
    fn attention(&self) -> Option<(usize, &[f64])> {
        None
    }
    /// The neurons and edges of a graph brain with the neurons' outputs after the last step, for
    /// drawing; `None` for other brains. Default: `None`.
    fn graph(&self) -> Option<GraphView<'_>> {
        None
    }
}

/// What a graph brain shows of itself ([`Controller::graph`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GraphView<'a> {
    /// Each neuron's voxel (grid order index) and kind (0 sensing, 1 hidden, 2 actuator).
    pub neurons: &'a [(usize, u8)],
    /// Edges as (source, target, weight).
    pub edges: &'a [(usize, usize, f64)],
    /// Each neuron's output after the last step.
    pub outputs: &'a [f64],
}
