//! Average (vsr-model.md §3.2): the mean of the inner sensor's readings over the last `window`
//! seconds, the current reading included. The window is by timestamp and inclusive: it holds every
//! sample taken at or after t − window (16 samples for 0.25 s at 60 Hz, 31 for 0.5 s). The domain
//! is the inner sensor's.

use super::node::{Node, Site};
use super::spec::SensorSpec;
use super::window::{check_window, TimeWindow};
use super::wrapper::{Transform, Wrapped, WrapperKind};
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

/// Running mean over a time window.
#[derive(Debug, Clone)]
pub(crate) struct Average {
    samples: TimeWindow,
}

impl Average {
    /// Averages `dim` readings over `window` seconds, sampled every `dt` seconds.
    pub(crate) fn new(dim: usize, window: f64, dt: f64) -> Average {
        Average {
            samples: TimeWindow::new(window, dim, dt),
        }
    }
}

impl Transform for Average {
    /// Records the sample and writes the window's mean.
    fn apply(&mut self, t: f64, out: &mut [f64]) {
        self.samples.push(t, out);
        out.fill(0.0);
        // oldest sample first, as a plain loop over `values(k)` would add them (same bits)
        // one and two readings (touch, velocity) keep their sums in registers: a sum kept in `out`
        // would wait on a store and a load for every sample
        let runs = self.samples.value_runs();
        match out {
            [s] => {
                for run in runs {
                    *s = run.iter().fold(*s, |acc, v| acc + v);
                }
            }
            [sx, sy] => {
                for run in runs {
                    (*sx, *sy) = run.chunks_exact(2).fold((*sx, *sy), |(x, y), v| (x + v[0], y + v[1]));
                }
            }
            _ => {
                let dim = out.len();
                for sample in runs.iter().flat_map(|r| r.chunks_exact(dim)) {
                    for (o, v) in out.iter_mut().zip(sample) {
                        *o += v;
                    }
                }
            }
        }
        let n = self.samples.len() as f64;
        out.iter_mut().for_each(|o| *o /= n);
    }

    /// Empties the window.
    fn reset(&mut self) {
        self.samples.clear();
    }
}

/// Description of an average wrapper (`{"kind": "average", "window": 0.5, "inner": {…}}`): Mean of the inner readings over the samples taken at or after t − window; domain unchanged.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AverageSpec {
    /// Window (s), > 0 and at most [`super::MAX_WINDOW`].
    pub window: f64,
    /// The wrapped sensor.
    pub inner: Box<SensorSpec>,
}

impl WrapperKind for AverageSpec {
    fn inner(&self) -> &SensorSpec {
        &self.inner
    }

    /// The inner domain.
    fn domain(&self, inner: (f64, f64)) -> (f64, f64) {
        inner
    }

    fn check(&self) -> Result<(), FieldError> {
        check_window(self.window)
    }

    fn wrap(&self, inner: Box<Node>, site: Site) -> Node {
        let average = Average::new(self.inner.dimension(), self.window, site.dt);
        Node::Average(Wrapped::new(inner, average))
    }
}

#[cfg(test)]
mod tests {
    use crate::sensors::node::testing::{run, states_from};
    use crate::sensors::spec::SensorSpec;

    #[test]
    fn averages_touch_over_an_inclusive_quarter_second() {
        let spec = SensorSpec::Touch.averaged(0.25);
        // 60 steps, touching during the last 8 only
        let states = states_from(0..60, |s, k| s.touching = k >= 52);
        let readings = run(&spec, &states, 1.0 / 60.0);
        // the window holds 16 samples at 60 Hz, 8 of which touch
        assert!((readings[59][0] - 0.5).abs() < 1e-12, "{:?}", readings[59]);
        // before the window fills, the mean is over the samples so far
        assert_eq!(readings[0][0], 0.0);
        assert!((readings[52][0] - 1.0 / 16.0).abs() < 1e-12);
    }

    #[test]
    fn averages_each_component_of_a_ramp() {
        use crate::sensors::{Axes, VelocitySpec};
        let spec = SensorSpec::Velocity(VelocitySpec {
            rotated: false,
            vmax: 8.0,
            axes: Axes::Xy,
        })
        .averaged(0.5);
        let dt = 1.0 / 60.0;
        let states = states_from(1..=120, |s, k| s.velocity = vsrlab_physics::Vec2::new(k as f64, -2.0));
        let last = run(&spec, &states, dt).pop().unwrap();
        // samples k = 90 … 120 (31 of them): mean 105
        assert!(
            (last[0] - 105.0).abs() < 1e-9 && (last[1] + 2.0).abs() < 1e-12,
            "{last:?}"
        );
    }
}
