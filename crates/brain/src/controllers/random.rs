//! Uniform random actuations, redrawn periodically: a baseline and a physics stress test. No
//! parameters. Short form: `random[:<period s>]`.

use crate::short_form::{self, ShortForm};
use crate::validation::non_negative;
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Each voxel gets an independent uniform value in [-1, 1], redrawn every `period` seconds.
#[derive(Debug, Clone)]
pub struct RandomController {
    period: f64,
    seed: u64,
    rng: ChaCha8Rng,
    last_draw: Option<f64>,
    current: Vec<f64>,
}

impl RandomController {
    /// A controller redrawing every `period` seconds (0 = every call) from `seed`.
    pub fn new(period: f64, seed: u64) -> Self {
        RandomController {
            period,
            seed,
            rng: ChaCha8Rng::seed_from_u64(seed),
            last_draw: None,
            current: Vec::new(),
        }
    }
}

impl Controller for RandomController {
    fn reset(&mut self) {
        self.rng = ChaCha8Rng::seed_from_u64(self.seed);
        self.last_draw = None;
    }

    fn control(&mut self, t: f64, _readings: &[f64], actuations: &mut [f64]) {
        let due = self.last_draw.is_none_or(|last| t - last >= self.period);
        if due || self.current.len() != actuations.len() {
            self.current.resize(actuations.len(), 0.0);
            for v in &mut self.current {
                *v = self.rng.random_range(-1.0..=1.0);
            }
            self.last_draw = Some(t);
        }
        actuations.copy_from_slice(&self.current);
    }
}

/// Description of a random brain (`{"kind": "random", "period": 0.0, "seed": 0}`): independent
/// uniform random actuations in [-1, 1], redrawn every `period` seconds. Every field has a default.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RandomSpec {
    /// Seconds between redraws (0 = every step); default 0.
    pub period: f64,
    /// Seed of the generator; default 0.
    pub seed: u64,
}

impl BrainKind for RandomSpec {
    fn name(&self) -> &'static str {
        "random"
    }

    fn build(&self, _shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        non_negative("period", self.period, " seconds")?;
        Ok(Box::new(RandomController::new(self.period, self.seed)))
    }
}

/// `random` (a redraw every step) or `random:<period s>`, seed 0.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "random",
    usage: "random[:<period s>]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let period = match argument {
        None => 0.0,
        Some(period) => short_form::number(period)?,
    };
    Some(BrainSpec::Random(RandomSpec { period, seed: 0 }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn redraws_on_schedule_and_is_reproducible() {
        let mut a = RandomController::new(0.5, 7);
        let mut out1 = vec![0.0; 3];
        let mut out2 = vec![0.0; 3];
        a.control(0.1, &[], &mut out1);
        a.control(0.2, &[], &mut out2);
        assert_eq!(out1, out2, "no redraw before the period");
        a.control(0.7, &[], &mut out2);
        assert_ne!(out1, out2, "redraw after the period");
        assert!(out2.iter().all(|v| (-1.0..=1.0).contains(v)));
        a.reset();
        a.control(0.1, &[], &mut out2);
        assert_eq!(out1, out2, "reset restarts the stream");
    }
}
