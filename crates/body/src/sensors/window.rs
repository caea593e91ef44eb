//! A sliding time window of time-stamped readings: the memory behind `Average` and `Trend`
//! (vsr-model.md §3.2).
//!
//! The window keeps every sample whose timestamp is at least `t − span`, where `t` is the time of
//! the newest sample (inclusive, so a 0.25 s window holds 16 samples at 60 Hz). Samples live in a
//! ring buffer sized at construction from `span / dt`; sampling at the nominal rate (or slower)
//! never allocates. Sampling faster than the nominal rate still gives the right window: the ring
//! then grows once to fit, which is the only allocation it ever makes.

use super::kind::check_positive;
use vsrlab_field::FieldError;

/// Longest accepted window of `Average` and `Trend` (s).
pub const MAX_WINDOW: f64 = 3600.0;

/// Errors unless `window` is finite, > 0 and at most [`MAX_WINDOW`] seconds; the error is on the
/// field `window`.
pub(crate) fn check_window(window: f64) -> Result<(), FieldError> {
    check_positive("window", "window", window)?;
    if window > MAX_WINDOW {
        return Err(FieldError::new(
            "window",
            format!("window must be at most {MAX_WINDOW} s, got {window}"),
        ));
    }
    Ok(())
}

/// Relative tolerance on the window's lower edge, so that a sample lying exactly `span` before the
/// newest one is kept even when the accumulated time has rounding error (`t += dt` over many steps).
const EDGE_TOLERANCE: f64 = 1e-9;

/// Largest ring allocated up front; longer windows grow on demand (see the module docs).
const MAX_INITIAL_SLOTS: usize = 1 << 16;

/// Time-stamped samples of `dim` values each, oldest first, within `span` seconds of the newest.
#[derive(Debug, Clone)]
pub(crate) struct TimeWindow {
    span: f64,
    dim: usize,
    /// Timestamps, one slot per sample.
    times: Vec<f64>,
    /// Values, `dim` per slot.
    values: Vec<f64>,
    /// Slot of the oldest sample.
    head: usize,
    /// Samples held.
    len: usize,
}

impl TimeWindow {
    /// A window of `span` seconds over readings of `dim` values sampled every `dt` seconds.
    pub(crate) fn new(span: f64, dim: usize, dt: f64) -> TimeWindow {
        // at exactly `dt` spacing the window holds floor(span/dt) + 1 samples; one more slot absorbs
        // the edge tolerance
        let slots = ((span / dt).ceil() as usize).saturating_add(2).min(MAX_INITIAL_SLOTS);
        TimeWindow {
            span,
            dim,
            times: vec![0.0; slots],
            values: vec![0.0; slots * dim],
            head: 0,
            len: 0,
        }
    }

    /// Forgets every sample.
    pub(crate) fn clear(&mut self) {
        self.head = 0;
        self.len = 0;
    }

    /// Number of samples in the window.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Adds the sample taken at time `t`, then drops the samples older than `t − span`.
    pub(crate) fn push(&mut self, t: f64, values: &[f64]) {
        debug_assert_eq!(values.len(), self.dim);
        let edge = t - self.span - EDGE_TOLERANCE * t.abs().max(1.0);
        while self.len > 0 && self.times[self.head] < edge {
            self.head = (self.head + 1) % self.capacity();
            self.len -= 1;
        }
        if self.len == self.capacity() {
            self.grow();
        }
        let slot = (self.head + self.len) % self.capacity();
        self.times[slot] = t;
        self.values[slot * self.dim..(slot + 1) * self.dim].copy_from_slice(values);
        self.len += 1;
    }

    /// Timestamp of the k-th oldest sample.
    pub(crate) fn time(&self, k: usize) -> f64 {
        self.times[self.slot(k)]
    }

    /// Values of the k-th oldest sample.
    pub(crate) fn values(&self, k: usize) -> &[f64] {
        let s = self.slot(k);
        &self.values[s * self.dim..(s + 1) * self.dim]
    }

    /// The values of every sample, oldest first, as at most two contiguous runs of the ring (`dim`
    /// values per sample): the fast way to visit the whole window in order.
    pub(crate) fn value_runs(&self) -> [&[f64]; 2] {
        let end = self.head + self.len;
        if end <= self.capacity() {
            [&self.values[self.head * self.dim..end * self.dim], &[]]
        } else {
            let wrapped = end - self.capacity();
            [&self.values[self.head * self.dim..], &self.values[..wrapped * self.dim]]
        }
    }

    fn capacity(&self) -> usize {
        self.times.len()
    }

    fn slot(&self, k: usize) -> usize {
        debug_assert!(k < self.len);
        (self.head + k) % self.capacity()
    }

    /// Doubles the ring, keeping the samples in order (only when sampled faster than planned).
    fn grow(&mut self) {
        let new_slots = (self.capacity() * 2).max(2);
        let mut times = vec![0.0; new_slots];
        let mut values = vec![0.0; new_slots * self.dim];
        for k in 0..self.len {
            times[k] = self.time(k);
            values[k * self.dim..(k + 1) * self.dim].copy_from_slice(self.values(k));
        }
        self.times = times;
        self.values = values;
        self.head = 0;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_an_inclusive_window_at_sixty_hertz() {
        let dt = 1.0 / 60.0;
        let mut w = TimeWindow::new(0.25, 1, dt);
        let mut t = 0.0;
        for k in 0..200 {
            t += dt;
            w.push(t, &[k as f64]);
        }
        // 0.25 s = 15 steps: the samples at t − 15 dt … t, both ends included
        assert_eq!(w.len(), 16);
        assert_eq!(w.values(0), &[184.0]);
        assert_eq!(w.values(15), &[199.0]);
        let mut half = TimeWindow::new(0.5, 2, dt);
        for k in 1..=100 {
            half.push(k as f64 * dt, &[0.0, 1.0]);
        }
        assert_eq!(half.len(), 31);
    }

    #[test]
    fn faster_sampling_grows_the_ring_and_stays_correct() {
        // planned for 60 Hz, fed at 600 Hz: 0.1 s holds 61 samples
        let mut w = TimeWindow::new(0.1, 1, 1.0 / 60.0);
        for k in 0..1000 {
            w.push(k as f64 / 600.0, &[k as f64]);
        }
        assert_eq!(w.len(), 61);
        assert_eq!(w.values(0), &[939.0]);
        assert!((w.time(60) - 999.0 / 600.0).abs() < 1e-12);
    }

    #[test]
    fn value_runs_visit_the_window_in_order_across_the_wrap() {
        let mut w = TimeWindow::new(0.05, 2, 0.01);
        for k in 0..40 {
            let t = k as f64 * 0.01;
            w.push(t, &[k as f64, -(k as f64)]);
            let flat: Vec<f64> = w.value_runs().concat();
            let expected: Vec<f64> = (0..w.len()).flat_map(|i| w.values(i).to_vec()).collect();
            assert_eq!(flat, expected, "after sample {k}");
        }
    }

    #[test]
    fn clear_forgets_everything() {
        let mut w = TimeWindow::new(1.0, 1, 0.1);
        w.push(0.0, &[1.0]);
        w.push(0.1, &[2.0]);
        w.clear();
        assert_eq!(w.len(), 0);
        w.push(5.0, &[3.0]);
        assert_eq!((w.len(), w.values(0)[0]), (1, 3.0));
    }
}
