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
}
