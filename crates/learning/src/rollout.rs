//! What one environment did during an iteration, and generalised advantage estimation (GAE,
//! Schulman et al. 2016) over it.

/// One environment's steps of an iteration, in order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Rollout {
    /// Raw observations the actions were chosen from.
    pub raw_observations: Vec<Vec<f64>>,
    /// The same, normalised as the policy saw them.
    pub observations: Vec<Vec<f64>>,
    /// Sampled actions.
    pub actions: Vec<Vec<f64>>,
    /// Their log-probabilities under the policy that sampled them.
    pub log_probs: Vec<f64>,
    /// Rewards.
    pub rewards: Vec<f64>,
    /// What a step's return adds for a time limit that cut its episode: γ × the value of the
    /// observation it was cut at (0 for every other step).
    pub bootstraps: Vec<f64>,
    /// Whether the step ended an episode.
    pub dones: Vec<bool>,
    /// The value network's estimate of each observation.
    pub values: Vec<f64>,
    /// The value of the observation after the last step (0 if it ended an episode).
    pub last_value: f64,
    /// Returns of the episodes that ended during the rollout.
    pub episode_returns: Vec<f64>,
}

impl Rollout {
    /// Advantages and returns (advantage + value) of every step, by GAE with discount `gamma`
    /// and `lambda`; an episode's end stops both the bootstrap and the accumulation.
    pub fn advantages(&self, gamma: f64, lambda: f64) -> (Vec<f64>, Vec<f64>) {
        let n = self.rewards.len();
        let mut advantages = vec![0.0; n];
        let mut next_advantage = 0.0;
        let mut next_value = self.last_value;
        for t in (0..n).rev() {
            let go_on = if self.dones[t] { 0.0 } else { 1.0 };
            let bootstrap = self.bootstraps.get(t).copied().unwrap_or(0.0);
            let delta = self.rewards[t] + bootstrap + gamma * next_value * go_on - self.values[t];
            next_advantage = delta + gamma * lambda * go_on * next_advantage;
            advantages[t] = next_advantage;
            next_value = self.values[t];
        }
        let returns = advantages.iter().zip(&self.values).map(|(a, v)| a + v).collect();
        (advantages, returns)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_lambda_one_and_perfect_zero_values_returns_are_discounted_sums() {
        let r = Rollout {
            rewards: vec![1.0, 2.0, 3.0, 4.0],
            dones: vec![false, true, false, false],
            values: vec![0.0; 4],
            last_value: 10.0,
            ..Rollout::default()
        };
        let (adv, ret) = r.advantages(0.5, 1.0);
        // the first episode ends at step 1; the second is bootstrapped with the last value
        assert_eq!(
            ret,
            vec![1.0 + 0.5 * 2.0, 2.0, 3.0 + 0.5 * (4.0 + 0.5 * 10.0), 4.0 + 0.5 * 10.0]
        );
        assert_eq!(adv, ret);
        // λ = 0: one-step temporal differences
        let v = Rollout {
            values: vec![1.0, 1.0, 1.0, 1.0],
            ..r
        };
        let (adv, _) = v.advantages(0.5, 0.0);
        assert_eq!(adv, vec![1.0 + 0.5 - 1.0, 2.0 - 1.0, 3.0 + 0.5 - 1.0, 4.0 + 5.0 - 1.0]);
    }
}
