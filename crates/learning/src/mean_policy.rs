//! Off-line episodes of policies' mean actions, several at once: the co-design loop's learning
//! curve runs one after every PPO iteration, and a few iterations' episodes stepped together
//! ([`Environment::step_all`]: population lanes where the environment has them) cost less than
//! one after the other. Each episode is [`Ppo::episode`]'s, bit for bit.

use crate::environment::Environment;
use crate::mlp::Mlp;
use crate::normalizer::Normalizer;
use crate::ppo::{Ppo, PpoError};

/// The policy's mean action as it is now: the actor and the observation statistics, without the
/// learner around them.
#[derive(Debug, Clone)]
pub struct MeanPolicy {
    actor: Mlp,
    normalizer: Normalizer,
}

impl MeanPolicy {
    /// The mean action of `ppo`'s current policy.
    pub fn of(ppo: &Ppo) -> Self {
        MeanPolicy {
            actor: ppo.actor().clone(),
            normalizer: ppo.normalizer().clone(),
        }
    }

    /// The action for an observation, as [`Ppo::act`] gives it.
    pub fn act(&self, observation: &[f64]) -> Vec<f64> {
        self.actor
            .forward(&self.normalizer.normalize(observation))
            .output()
            .to_vec()
    }
}

/// One episode of each policy in its own copy of `env`, reset with `seed`, stepped together,
/// each as [`Ppo::episode`] runs it alone: the total reward and the steps, or the error that
/// ended it.
pub fn episodes<E: Environment + Clone>(
    policies: &[MeanPolicy],
    env: &E,
    seed: u64,
    max_steps: usize,
) -> Vec<Result<(f64, usize), PpoError>> {
    let mut environments = vec![env.clone(); policies.len()];
    let mut observations: Vec<Vec<f64>> = environments.iter_mut().map(|e| e.reset(seed)).collect();
    let mut results: Vec<Option<Result<(f64, usize), PpoError>>> = policies.iter().map(|_| None).collect();
    let mut totals = vec![(0.0, 0); policies.len()];
    // the running episodes come first: `order[i]` is the episode in environment slot `i`
    let mut order: Vec<usize> = (0..policies.len()).collect();
    let mut running = if max_steps == 0 { 0 } else { policies.len() };
    while running > 0 {
        let actions: Vec<Vec<f64>> = order[..running]
            .iter()
            .zip(&observations)
            .map(|(&k, observation)| policies[k].act(observation))
            .collect();
        let steps = E::step_all(&mut environments[..running], &actions);
        let mut ended = Vec::new();
        for (slot, step) in steps.into_iter().enumerate() {
            let k = order[slot];
            let result = match step {
                Err(source) => Some(Err(PpoError::Step {
                    environment: None,
                    source,
                })),
                Ok(step) if !step.reward.is_finite() || step.observation.iter().any(|v| !v.is_finite()) => {
                    Some(Err(PpoError::NonFinite("reward or observation of an episode".into())))
                }
                Ok(step) => {
                    let (total, steps) = &mut totals[k];
                    *total += step.reward;
                    *steps += 1;
                    observations[slot] = step.observation;
                    (step.done || *steps >= max_steps).then_some(Ok(totals[k]))
                }
            };
            if let Some(result) = result {
                results[k] = Some(result);
                ended.push(slot);
            }
        }
        // the last running episodes take the ended ones' slots, the highest slot first
        for &slot in ended.iter().rev() {
            running -= 1;
            order.swap(slot, running);
            environments.swap(slot, running);
            observations.swap(slot, running);
        }
    }
    results
        .into_iter()
        .zip(totals)
        .map(|(r, t)| r.unwrap_or(Ok(t)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::{StepError, Transition};
    use crate::ppo::PpoConfig;

    /// A point pushed by the action without a clip: the episode ends when it leaves [−2, 2]
    /// (so policies end at different steps), or with an error at x beyond 3.
    #[derive(Debug, Clone, Default)]
    struct Drift {
        x: f64,
    }

    impl Environment for Drift {
        fn observation_size(&self) -> usize {
            1
        }
        fn action_size(&self) -> usize {
            1
        }
        fn reset(&mut self, seed: u64) -> Vec<f64> {
            self.x = seed as f64 * 0.01;
            vec![self.x]
        }
        fn step(&mut self, action: &[f64]) -> Result<Transition, StepError> {
            self.x += 20.0 * action[0];
            if self.x > 3.0 {
                return Err("the point left the line".into());
            }
            Ok(Transition {
                observation: vec![self.x],
                reward: -self.x.abs(),
                done: self.x.abs() > 2.0,
                truncated: false,
            })
        }
    }

    #[test]
    fn episodes_together_are_each_policys_episode_alone() {
        let config = PpoConfig {
            hidden: vec![8],
            ..PpoConfig::default()
        };
        let learners: Vec<Ppo> = (0..9).map(|s| Ppo::new(1, 1, config.clone(), s).unwrap()).collect();
        let policies: Vec<MeanPolicy> = learners.iter().map(MeanPolicy::of).collect();
        for max_steps in [0, 7, 60] {
            let together = episodes(&policies, &Drift::default(), 3, max_steps);
            let mut lengths = Vec::new();
            for (ppo, result) in learners.iter().zip(&together) {
                let alone = ppo.episode(&mut Drift::default(), 3, max_steps);
                match (alone, result) {
                    (Ok((total, steps)), Ok((t, s))) => {
                        assert_eq!((total.to_bits(), steps), (t.to_bits(), *s));
                        lengths.push(steps);
                    }
                    (Err(a), Err(b)) => assert_eq!(a.to_string(), b.to_string()),
                    (a, b) => panic!("alone {a:?}, together {b:?}"),
                }
            }
            if max_steps == 60 {
                lengths.sort_unstable();
                lengths.dedup();
                assert!(lengths.len() >= 3, "episodes of different lengths: {lengths:?}");
            }
        }
    }
}
