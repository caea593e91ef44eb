//! A toy environment with a known answer, for tests, examples and checking a learner: a point
//! on a line pushed by the action (clipped to ±1, 0.2 per step) towards 0, reward −|x| per step,
//! 20-step episodes starting anywhere in [−1, 1].

use crate::environment::{Environment, StepError, Transition};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// The reaching task (see the module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Reach {
    x: f64,
    t: usize,
}

/// Steps of an episode.
pub const REACH_STEPS: usize = 20;

impl Environment for Reach {
    fn observation_size(&self) -> usize {
        1
    }

    fn action_size(&self) -> usize {
        1
    }

    fn reset(&mut self, seed: u64) -> Vec<f64> {
        self.x = ChaCha8Rng::seed_from_u64(seed).random_range(-1.0..1.0);
        self.t = 0;
        vec![self.x]
    }

    fn step(&mut self, action: &[f64]) -> Result<Transition, StepError> {
        self.x += 0.2 * action[0].clamp(-1.0, 1.0);
        self.t += 1;
        Ok(Transition {
            observation: vec![self.x],
            reward: -self.x.abs(),
            done: self.t == REACH_STEPS,
            truncated: self.t == REACH_STEPS,
        })
    }
}
