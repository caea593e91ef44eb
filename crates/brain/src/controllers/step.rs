//! Step wrapper (2D-VSR-Sim `StepController`, vsr-model.md §4.6): the inner controller runs at every
//! control step, so its state evolves, but the applied actuations are refreshed only when at least
//! `period` seconds passed since the last refresh (the first call always refreshes) and held in
//! between. AttentionVSRs used 0.33 s, i.e. a refresh every 20 steps at 1/60 s (20·(1/60) ≈ 0.3333 ≥
//! 0.33 while 19 steps ≈ 0.3167 are not enough). A period of exactly k·dt is fragile with a time
//! accumulated in floating point; give a slightly smaller one. No parameters of its own.
//!
//! Short form: `step:<period s>:<brain>`.

use super::wrapper::Inner;
use crate::short_form::{self, ShortForm};
use crate::validation::non_negative;
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};

/// Holds the inner controller's output for `period` seconds.
pub struct StepController {
    inner: Inner,
    period: f64,
    last_refresh: Option<f64>,
    held: Vec<f64>,
}

impl StepController {
    /// Wraps `inner` for a body of `voxels` voxels.
    pub fn new(inner: Box<dyn Controller>, period: f64, voxels: usize) -> Self {
        StepController {
            inner: Inner::new(inner, voxels),
            period,
            last_refresh: None,
            held: vec![0.0; voxels],
        }
    }
}

impl Controller for StepController {
    fn reset(&mut self) {
        self.inner.reset();
        self.last_refresh = None;
        self.held.fill(0.0);
    }

    fn describe(&self, probe: &mut dyn vsrlab_body::Probe) {
        self.inner.controller().describe(probe);
    }

    fn publish(&self, probe: &mut dyn vsrlab_body::Probe) {
        self.inner.controller().publish(probe);
    }

    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]) {
        let target = self.inner.control(t, readings);
        if self.last_refresh.is_none_or(|last| t - last >= self.period) {
            self.held.copy_from_slice(target);
            self.last_refresh = Some(t);
        }
        actuations.copy_from_slice(&self.held);
    }
}

/// Description of a step wrapper (`{"kind": "step", "period": 0.33, "inner": {…}}`): holds the inner
/// brain's output for `period` seconds (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StepSpec {
    /// Seconds between refreshes of the applied actuations (0 = every step); required.
    pub period: f64,
    /// The wrapped brain; required.
    pub inner: Box<BrainSpec>,
}

impl BrainKind for StepSpec {
    fn name(&self) -> &'static str {
        "step"
    }

    fn inner(&self) -> Option<&BrainSpec> {
        Some(&self.inner)
    }

    fn inner_mut(&mut self) -> Option<&mut BrainSpec> {
        Some(&mut self.inner)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        non_negative("period", self.period, " seconds")?;
        let inner = self.inner.build(shape)?;
        Ok(Box::new(StepController::new(inner, self.period, shape.units())))
    }
}

/// `step:<period s>:<brain>`, wrapping any short form.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "step",
    usage: "step:<period s>:<brain>",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let (period, inner) = short_form::wrapped(argument)?;
    Some(BrainSpec::Step(StepSpec { period, inner }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped, build_error};

    /// Outputs the number of calls so far (so every call gives a new value) and counts resets.
    struct Counter(f64);
    impl Controller for Counter {
        fn reset(&mut self) {
            self.0 = 0.0;
        }
        fn control(&mut self, _t: f64, _r: &[f64], a: &mut [f64]) {
            self.0 += 1.0;
            a.fill(self.0);
        }
    }

    #[test]
    fn refreshes_exactly_every_twenty_steps_with_0_33_s() {
        let mut c = StepController::new(Box::new(Counter(0.0)), 0.33, 2);
        let dt = 1.0 / 60.0;
        let mut t = 0.0;
        let mut a = [0.0; 2];
        let mut refreshes = Vec::new();
        let mut last = f64::NAN;
        for step in 1..=200 {
            t += dt;
            c.control(t, &[], &mut a);
            if a[0] != last {
                refreshes.push(step);
                last = a[0];
            }
            // the held value is the inner's output at the last refresh step: it ran every step
            assert_eq!(a[0], *refreshes.last().unwrap() as f64);
        }
        assert_eq!(refreshes, (0..10).map(|k| 1 + 20 * k).collect::<Vec<_>>());
        c.reset();
        c.control(dt, &[], &mut a);
        assert_eq!(a, [1.0, 1.0], "reset: the first call refreshes, inner restarted");
    }

    #[test]
    fn zero_period_is_a_pass_through() {
        let mut c = StepController::new(Box::new(Counter(0.0)), 0.0, 1);
        let mut a = [0.0];
        for k in 1..=5 {
            c.control(k as f64 / 60.0, &[], &mut a);
            assert_eq!(a[0], k as f64);
        }
    }

    #[test]
    fn the_spec_delegates_to_its_inner_brain_and_checks_its_period() {
        let (m, rpv) = biped();
        assert_eq!(
            BrainSpec::parse("step:0.33:mlp")
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv)),
            Ok(1336)
        );
        let err = build_error(&BrainSpec::parse("step:0.3:distributed-mlp-hetero").unwrap(), &rpv);
        assert_eq!(
            err.to_string(),
            "brain.weights: expected 540 for this body and sensors, got 0"
        );
        let err = build_error(&BrainSpec::parse("step:-1:phase").unwrap(), &rpv);
        assert_invalid(&err, "period");
    }
}
