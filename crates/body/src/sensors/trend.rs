//! Trend (vsr-model.md §3.2, since 2021-08 in place of `Derivative`): how fast the inner readings
//! change over the last `window` seconds, (last − first)/(t_last − t_first) over the samples of the
//! inclusive window. With a single sample (the first step) it reads 0. Its domain is
//! ±extent/window per reading, where extent is the width of the inner sensor's domain.

use super::node::{Node, Site};
use super::spec::SensorSpec;
use super::window::{check_window, TimeWindow};
use super::wrapper::{Transform, Wrapped, WrapperKind};
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

/// Declared domain for an inner domain `(lo, hi)` over `window` seconds.
pub(crate) fn domain((lo, hi): (f64, f64), window: f64) -> (f64, f64) {
    let extent = hi - lo;
    (-extent / window, extent / window)
}

/// Slope between the oldest and the newest sample of a time window.
#[derive(Debug, Clone)]
pub(crate) struct Trend {
    samples: TimeWindow,
}

impl Trend {
    /// The trend of `dim` readings over `window` seconds, sampled every `dt` seconds.
    pub(crate) fn new(dim: usize, window: f64, dt: f64) -> Trend {
        Trend {
            samples: TimeWindow::new(window, dim, dt),
        }
    }
}

impl Transform for Trend {
    /// Records the sample and writes the slope.
    fn apply(&mut self, t: f64, out: &mut [f64]) {
        self.samples.push(t, out);
        let last = self.samples.len() - 1;
        let elapsed = self.samples.time(last) - self.samples.time(0);
        if elapsed > 0.0 {
            let (first, newest) = (self.samples.values(0), self.samples.values(last));
            for ((o, a), b) in out.iter_mut().zip(first).zip(newest) {
                *o = (b - a) / elapsed;
            }
        } else {
            out.fill(0.0);
        }
    }

    /// Empties the window.
    fn reset(&mut self) {
        self.samples.clear();
    }
}

/// Description of a trend wrapper (`{"kind": "trend", "window": 0.5, "inner": {…}}`): (last − first)/(t_last − t_first) over the window; domain ±extent/window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrendSpec {
    /// Window (s), > 0 and at most [`super::MAX_WINDOW`].
    pub window: f64,
    /// The wrapped sensor.
    pub inner: Box<SensorSpec>,
}

impl WrapperKind for TrendSpec {
    fn inner(&self) -> &SensorSpec {
        &self.inner
    }

    /// ±extent/window.
    fn domain(&self, inner: (f64, f64)) -> (f64, f64) {
        domain(inner, self.window)
    }

    fn check(&self) -> Result<(), FieldError> {
        check_window(self.window)
    }

    fn wrap(&self, inner: Box<Node>, site: Site) -> Node {
        let trend = Trend::new(self.inner.dimension(), self.window, site.dt);
        Node::Trend(Wrapped::new(inner, trend))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{run, states_from};
    use crate::sensors::spec::SensorSpec;
    use crate::sensors::{Axes, VelocitySpec};
    use vsrlab_physics::Vec2;

    #[test]
    fn the_trend_of_a_ramp_is_its_slope() {
        let spec = SensorSpec::Velocity(VelocitySpec {
            rotated: false,
            vmax: 4.0,
            axes: Axes::Xy,
        })
        .trend(0.5);
        let dt = 1.0 / 60.0;
        let states = states_from(1..=90, |s, k| {
            let t = k as f64 * dt;
            s.velocity = Vec2::new(3.0 * t + 1.0, -0.5 * t);
        });
        let readings = run(&spec, &states, dt);
        assert_eq!(readings[0], vec![0.0, 0.0], "one sample: no trend yet");
        for r in &readings[1..] {
            assert!((r[0] - 3.0).abs() < 1e-9 && (r[1] + 0.5).abs() < 1e-9, "{r:?}");
        }
    }

    #[test]
    fn the_trend_forgets_what_left_the_window() {
        // a step at step 10: the slope is nonzero while the step is inside the 0.5 s window, then 0
        let spec = SensorSpec::AreaRatio.trend(0.5);
        let dt = 1.0 / 60.0;
        let states = states_from(0..80, |s, k| s.area_ratio = if k < 10 { 1.0 } else { 1.2 });
        let readings = run(&spec, &states, dt);
        assert!(readings[20][0] > 0.0);
        assert_eq!(readings[79][0], 0.0);
    }

    #[test]
    fn domain_is_extent_over_window() {
        assert_eq!(domain((-4.0, 4.0), 0.5), (-16.0, 16.0));
    }
}
