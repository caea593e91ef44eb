//! Smoothed wrapper (2D-VSR-Sim `SmoothedController`, vsr-model.md §4.6): each voxel's actuation
//! moves towards the inner controller's output by at most `speed·dt` per call, starting from 0, with
//! dt the time since the previous call (the first call measures from t = 0). No parameters of its
//! own.
//!
//! Short form: `smoothed:<speed>:<brain>`.

use super::wrapper::Inner;
use crate::short_form::{self, ShortForm};
use crate::validation::non_negative;
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};

/// Rate-limits the inner controller's output to `speed` per second.
pub struct SmoothedController {
    inner: Inner,
    speed: f64,
    last_t: f64,
    current: Vec<f64>,
}

impl SmoothedController {
    /// Wraps `inner` for a body of `voxels` voxels.
    pub fn new(inner: Box<dyn Controller>, speed: f64, voxels: usize) -> Self {
        SmoothedController {
            inner: Inner::new(inner, voxels),
            speed,
            last_t: 0.0,
            current: vec![0.0; voxels],
        }
    }
}

impl Controller for SmoothedController {
    fn reset(&mut self) {
        self.inner.reset();
        self.last_t = 0.0;
        self.current.fill(0.0);
    }

    fn describe(&self, probe: &mut dyn vsrlab_body::Probe) {
        self.inner.controller().describe(probe);
    }

    fn publish(&self, probe: &mut dyn vsrlab_body::Probe) {
        self.inner.controller().publish(probe);
    }

    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]) {
        let target = self.inner.control(t, readings);
        let max_change = self.speed * (t - self.last_t).max(0.0);
        self.last_t = t;
        for ((a, c), target) in actuations.iter_mut().zip(&mut self.current).zip(target) {
            *c += (target - *c).clamp(-max_change, max_change);
            *a = *c;
        }
    }
}

/// Description of a smoothed wrapper (`{"kind": "smoothed", "speed": 5.0, "inner": {…}}`): rate-limits
/// the inner brain's output (module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SmoothedSpec {
    /// Largest change of an actuation per second; required.
    pub speed: f64,
    /// The wrapped brain; required.
    pub inner: Box<BrainSpec>,
}

impl BrainKind for SmoothedSpec {
    fn name(&self) -> &'static str {
        "smoothed"
    }

    fn inner(&self) -> Option<&BrainSpec> {
        Some(&self.inner)
    }

    fn inner_mut(&mut self) -> Option<&mut BrainSpec> {
        Some(&mut self.inner)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        non_negative("speed", self.speed, " per second")?;
        let inner = self.inner.build(shape)?;
        Ok(Box::new(SmoothedController::new(inner, self.speed, shape.units())))
    }
}

/// `smoothed:<speed>:<brain>`, wrapping any short form.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "smoothed",
    usage: "smoothed:<speed>:<brain>",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let (speed, inner) = short_form::wrapped(argument)?;
    Some(BrainSpec::Smoothed(SmoothedSpec { speed, inner }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped, build_error};
    use crate::ConstantController;

    /// A square wave jumping between −1 and +1 every 10 calls.
    struct Square(u32);
    impl Controller for Square {
        fn reset(&mut self) {
            self.0 = 0;
        }
        fn control(&mut self, _t: f64, _r: &[f64], a: &mut [f64]) {
            self.0 += 1;
            a.fill(if (self.0 / 10) & 1 == 0 { 1.0 } else { -1.0 });
        }
    }

    #[test]
    fn changes_by_at_most_speed_dt_per_step_from_zero() {
        let (speed, dt) = (3.0, 1.0 / 60.0);
        let mut c = SmoothedController::new(Box::new(Square(0)), speed, 2);
        let mut a = [0.0; 2];
        let mut previous = 0.0;
        let mut t = 0.0;
        let mut largest: f64 = 0.0;
        for _ in 0..300 {
            t += dt;
            c.control(t, &[], &mut a);
            let change = (a[0] - previous).abs();
            assert!(change <= speed * dt + 1e-12, "{change}");
            largest = largest.max(change);
            previous = a[0];
        }
        assert!((largest - speed * dt).abs() < 1e-9, "the limit is reached: {largest}");
    }

    #[test]
    fn reaches_a_constant_target_and_stays() {
        let mut c = SmoothedController::new(Box::new(ConstantController { value: 0.5 }), 6.0, 1);
        let mut a = [0.0];
        c.control(1.0 / 60.0, &[], &mut a);
        assert!((a[0] - 0.1).abs() < 1e-12, "first step from 0 by 6/60: {}", a[0]);
        for k in 2..=10 {
            c.control(k as f64 / 60.0, &[], &mut a);
        }
        assert_eq!(a[0], 0.5);
        c.reset();
        c.control(1.0 / 60.0, &[], &mut a);
        assert!((a[0] - 0.1).abs() < 1e-12, "reset starts from 0 again");
    }

    #[test]
    fn the_spec_delegates_to_its_inner_brain_and_checks_its_speed() {
        let (m, rpv) = biped();
        assert_eq!(
            BrainSpec::parse("smoothed:2:distributed-mlp-hetero")
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv)),
            Ok(12 * 45)
        );
        let err = build_error(&BrainSpec::parse("smoothed:nan:phase").unwrap(), &rpv);
        assert_invalid(&err, "speed");
    }
}
