//! Proximal policy optimisation (Schulman et al. 2017, the clipped objective) with a diagonal
//! Gaussian policy (a state-independent log σ per action) and a separate value network, as the
//! EvoGym examples' PPO: rollouts of `steps_per_environment` steps in each environment, GAE,
//! advantages normalised over the batch, `epochs` passes over `minibatches` shuffled
//! minibatches, one Adam over every parameter with the gradient clipped to a global norm, the
//! learning rate decayed linearly to 0 over the iterations.

use crate::adam::Adam;
use crate::environment::{Environment, StepError, Transition};
use crate::gaussian::{add_log_prob_gradient, entropy, log_prob};
use crate::mlp::{standard_normal, Mlp};
use crate::mlp_batch::BatchPass;
use crate::normalizer::Normalizer;
use crate::rollout::Rollout;
use rand::seq::SliceRandom;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

/// PPO's settings; the defaults are the EvoGym examples' (docs/learning.md).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PpoConfig {
    /// Iterations (rollout, then update) of one training.
    pub iterations: usize,
    /// Environments stepped in parallel, for callers that build them (4, the EvoGym examples';
    /// the thesis wrote 32).
    pub environments: usize,
    /// Steps of each environment per iteration (128).
    pub steps_per_environment: usize,
    /// Passes over the iteration's steps (4).
    pub epochs: usize,
    /// Minibatches per pass (4).
    pub minibatches: usize,
    /// Adam's step size at the first iteration (2.5e-4).
    pub learning_rate: f64,
    /// Whether the step size falls linearly to 0 over the iterations (yes).
    pub decay_learning_rate: bool,
    /// The ratio's clip range ε (0.1).
    pub clip: f64,
    /// Discount γ (0.99).
    pub gamma: f64,
    /// GAE's λ (0.95).
    pub lambda: f64,
    /// Weight of the value loss (0.5).
    pub value_coefficient: f64,
    /// Weight of the entropy bonus (0.01).
    pub entropy_coefficient: f64,
    /// The gradient is scaled down to this global norm when longer (0.5).
    pub max_gradient_norm: f64,
    /// Hidden layers of both networks, tanh ([64, 64]).
    pub hidden: Vec<usize>,
    /// Initial log σ of every action (0: σ = 1).
    pub initial_log_std: f64,
    /// Whether an episode cut by a time limit is bootstrapped with the value of the observation
    /// it was cut at (stable-baselines3's PPO, which EvoGym 2.0 uses) or ends as if the robot had
    /// died (false: the EvoGym 2022 examples' PPO without `--use-proper-time-limits`, which the
    /// thesis ran).
    pub bootstrap_time_limits: bool,
    /// When the observation statistics take in new observations: once per iteration after the
    /// update (the default, what every figure in docs/learning.md and docs/ch5.2.md used), or at
    /// every step, each new observation before the policy sees it (the reference's
    /// `VecNormalize`; it did not change Walker's seed-1 training, docs/learning.md).
    pub observation_statistics: ObservationStatistics,
    /// Whether the value loss is clipped as the reference's (`--use-clipped-value-loss`, yes):
    /// the larger of (V − R)² and (V_clipped − R)², V_clipped the old value moved at most `clip`
    /// towards V. Figures in the docs dated before 2026-11-28 ran without.
    pub clip_value_loss: bool,
    /// Whether the update learns from rewards divided by the running deviation of each
    /// environment's discounted return and clipped to ±10, as the reference's `VecNormalize`
    /// (yes). The statistics take in each iteration's returns after the iteration (environments
    /// in order; the reference's at every step), so the first iteration's rewards are unscaled.
    /// Reported rewards and episodes stay the environment's. Figures in the docs dated before
    /// 2026-11-28 ran without; on Walker it is what lets PPO leave its flat start
    /// (docs/learning.md).
    pub normalize_rewards: bool,
}

/// When PPO's observation statistics are updated ([`PpoConfig::observation_statistics`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObservationStatistics {
    /// With all of an iteration's observations, after its update.
    #[default]
    EveryIteration,
    /// With every step's new observations, environments in order (deterministic).
    EveryStep,
}

impl Default for PpoConfig {
    fn default() -> Self {
        PpoConfig {
            iterations: 1000,
            environments: 4,
            steps_per_environment: 128,
            epochs: 4,
            minibatches: 4,
            learning_rate: 2.5e-4,
            decay_learning_rate: true,
            clip: 0.1,
            gamma: 0.99,
            lambda: 0.95,
            value_coefficient: 0.5,
            entropy_coefficient: 0.01,
            max_gradient_norm: 0.5,
            hidden: vec![64, 64],
            initial_log_std: 0.0,
            bootstrap_time_limits: false,
            observation_statistics: ObservationStatistics::EveryIteration,
            clip_value_loss: true,
            normalize_rewards: true,
        }
    }
}

/// Why PPO cannot start or go on.
#[derive(Debug, thiserror::Error)]
pub enum PpoError {
    /// A setting out of its range; names the field.
    #[error("{field}: {message}")]
    Invalid {
        /// The setting.
        field: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The environments disagree with the policy (sizes, count).
    #[error("environments: {0}")]
    Environment(String),
    /// An environment's step failed (`environment`: which of the training's environments;
    /// `None` for the off-line episode of [`Ppo::episode`]).
    #[error("environments: {}{source}", environment.map(|e| format!("environment {e}: ")).unwrap_or_default())]
    Step {
        /// Which environment.
        environment: Option<usize>,
        /// The environment's own error.
        #[source]
        source: StepError,
    },
    /// An environment gave a non-finite observation or reward, or an update made a parameter
    /// non-finite.
    #[error("non-finite {0}")]
    NonFinite(String),
}

impl PpoConfig {
    /// Checks every setting, naming the field.
    pub fn validate(&self) -> Result<(), PpoError> {
        let invalid = |field, message: String| Err(PpoError::Invalid { field, message });
        let counts = [
            ("iterations", self.iterations, 1_000_000),
            ("environments", self.environments, 1024),
            ("steps_per_environment", self.steps_per_environment, 1_000_000),
            ("epochs", self.epochs, 1000),
            ("minibatches", self.minibatches, 1_000_000),
        ];
        for (field, value, most) in counts {
            if value == 0 || value > most {
                return invalid(field, format!("must be in 1..={most}, got {value}"));
            }
        }
        let ranges = [
            ("learning_rate", self.learning_rate, 0.0, 1.0),
            ("clip", self.clip, 0.0, 1.0),
            ("gamma", self.gamma, 0.0, 1.0),
            ("lambda", self.lambda, 0.0, 1.0),
            ("value_coefficient", self.value_coefficient, 0.0, 1e6),
            ("entropy_coefficient", self.entropy_coefficient, 0.0, 1e6),
            ("max_gradient_norm", self.max_gradient_norm, 0.0, f64::MAX),
            ("initial_log_std", self.initial_log_std, -20.0, 5.0),
        ];
        for (field, value, low, high) in ranges {
            if !(value.is_finite() && (low..=high).contains(&value)) {
                return invalid(field, format!("must be a number in [{low}, {high:e}], got {value}"));
            }
        }
        if self.hidden.len() > 16 || self.hidden.iter().any(|&n| n == 0 || n > 4096) {
            return invalid(
                "hidden",
                format!("at most 16 layers of 1 to 4096 neurons, got {:?}", self.hidden),
            );
        }
        Ok(())
    }
}

/// What one iteration did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IterationStats {
    /// Iteration, from 0.
    pub iteration: usize,
    /// Mean reward per step of the rollouts.
    pub mean_reward: f64,
    /// Mean return of the episodes that ended during the rollouts (`None`: none ended).
    pub mean_episode_return: Option<f64>,
    /// Episodes that ended during the rollouts.
    pub episodes: usize,
    /// Mean clipped surrogate loss of the last epoch.
    pub policy_loss: f64,
    /// Mean value loss (½ squared error) of the last epoch.
    pub value_loss: f64,
    /// The policy's entropy after the update.
    pub entropy: f64,
    /// The step size used.
    pub learning_rate: f64,
}

/// One environment's state between steps.
#[derive(Debug, Clone)]
struct Slot {
    observation: Vec<f64>,
    episode_return: f64,
    episodes: u64,
    /// The discounted return so far of the current episode (for `normalize_rewards`).
    discounted_return: f64,
}

/// A PPO learner: policy, value network, optimiser state and observation statistics.
#[derive(Debug, Clone)]
pub struct Ppo {
    config: PpoConfig,
    actor: Mlp,
    log_std: Vec<f64>,
    critic: Mlp,
    adam: Adam,
    normalizer: Normalizer,
    /// Running statistics of the discounted returns (`normalize_rewards`).
    return_statistics: Normalizer,
    seed: u64,
}

/// Added to the return variance before its root (`normalize_rewards`).
const REWARD_EPSILON: f64 = 1e-8;
/// Scaled rewards are clipped to ± this.
const REWARD_CLIP: f64 = 10.0;

/// The value loss ½·(V − R)² of one sample and its derivative with respect to V; with
/// `clip = Some(ε)` the reference's clipped loss ½·max((V − R)², (V_c − R)²), V_c = old + clamp(V
/// − old, ±ε), whose derivative is 0 where the clipped term is the larger and V_c is clamped.
fn value_loss_of(value: f64, old: f64, target: f64, clip: Option<f64>) -> (f64, f64) {
    let error = value - target;
    let Some(clip) = clip else {
        return (0.5 * error * error, error);
    };
    let moved = value - old;
    let clipped_error = old + moved.clamp(-clip, clip) - target;
    if error * error >= clipped_error * clipped_error {
        (0.5 * error * error, error)
    } else if moved.abs() < clip {
        (0.5 * clipped_error * clipped_error, clipped_error)
    } else {
        (0.5 * clipped_error * clipped_error, 0.0)
    }
}

/// The rollout's forward passes over every environment at once, kept from step to step so that
/// their buffers are allocated once per rollout.
#[derive(Debug, Default)]
struct RolloutPasses {
    inputs: Vec<f64>,
    actor: BatchPass,
    critic: BatchPass,
}

/// A seed from a base seed and two indices (SplitMix64 steps), for per-environment and
/// per-iteration generators.
fn mix(seed: u64, a: u64, b: u64) -> u64 {
    let mut z = seed ^ a.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ b.wrapping_mul(0xD1B5_4A32_D192_ED03);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

impl Ppo {
    /// A learner for observations of `observations` values and actions of `actions` values.
    pub fn new(observations: usize, actions: usize, config: PpoConfig, seed: u64) -> Result<Ppo, PpoError> {
        config.validate()?;
        if observations == 0 || actions == 0 {
            return Err(PpoError::Environment(format!(
                "{observations} observation and {actions} action values: PPO needs at least one of each"
            )));
        }
        let mut rng = ChaCha8Rng::seed_from_u64(mix(seed, u64::MAX, 0));
        let sizes = |outputs: usize| [vec![observations], config.hidden.clone(), vec![outputs]].concat();
        let actor = Mlp::new(&sizes(actions), 0.01, &mut rng);
        let critic = Mlp::new(&sizes(1), 1.0, &mut rng);
        let adam = Adam::new(actor.parameters.len() + actions + critic.parameters.len());
        Ok(Ppo {
            log_std: vec![config.initial_log_std; actions],
            actor,
            critic,
            adam,
            normalizer: Normalizer::new(observations),
            return_statistics: Normalizer::new(1),
            config,
            seed,
        })
    }

    /// The policy network (its output is the Gaussian's mean).
    pub fn actor(&self) -> &Mlp {
        &self.actor
    }

    /// The observation statistics the policy normalises its input with.
    pub fn normalizer(&self) -> &Normalizer {
        &self.normalizer
    }

    /// The policy's action for an observation: its mean, without noise.
    pub fn act(&self, observation: &[f64]) -> Vec<f64> {
        self.actor
            .forward(&self.normalizer.normalize(observation))
            .output()
            .to_vec()
    }

    /// Trains for the configured iterations on `environments` (stepped in parallel); returns
    /// what each iteration did.
    pub fn train<E: Environment>(&mut self, environments: &mut [E]) -> Result<Vec<IterationStats>, PpoError> {
        self.train_observed(environments, |_, _| Ok(()))
    }

    /// [`Ppo::train`] calling `after` with the learner and the iteration's statistics after every
    /// iteration (and once before the first, with `None`): how the co-design loop records a
    /// learning curve. An error from `after` stops the training.
    pub fn train_observed<E: Environment>(
        &mut self,
        environments: &mut [E],
        mut after: impl FnMut(&Ppo, Option<&IterationStats>) -> Result<(), PpoError>,
    ) -> Result<Vec<IterationStats>, PpoError> {
        self.check_environments(environments)?;
        after(self, None)?;
        let mut slots: Vec<Slot> = environments
            .iter_mut()
            .enumerate()
            .map(|(e, env)| Slot {
                observation: env.reset(mix(self.seed, e as u64, 0)),
                episode_return: 0.0,
                episodes: 0,
                discounted_return: 0.0,
            })
            .collect();
        if self.config.observation_statistics == ObservationStatistics::EveryStep {
            self.observe(&slots);
        }
        (0..self.config.iterations)
            .map(|iteration| {
                let stats = self.iterate(iteration, environments, &mut slots)?;
                after(self, Some(&stats))?;
                Ok(stats)
            })
            .collect()
    }

    /// One episode of the policy's mean action (no noise, no learning) from a reset with `seed`,
    /// at most `max_steps` steps: the total reward and the steps taken. The thesis's "off-line"
    /// simulation (§5.2.4, eq. 5.7).
    pub fn episode<E: Environment>(&self, env: &mut E, seed: u64, max_steps: usize) -> Result<(f64, usize), PpoError> {
        let mut observation = env.reset(seed);
        let (mut total, mut steps) = (0.0, 0);
        while steps < max_steps {
            let step = env.step(&self.act(&observation)).map_err(|source| PpoError::Step {
                environment: None,
                source,
            })?;
            if !step.reward.is_finite() || step.observation.iter().any(|v| !v.is_finite()) {
                return Err(PpoError::NonFinite("reward or observation of an episode".into()));
            }
            total += step.reward;
            steps += 1;
            observation = step.observation;
            if step.done {
                break;
            }
        }
        Ok((total, steps))
    }

    fn check_environments<E: Environment>(&self, environments: &[E]) -> Result<(), PpoError> {
        if environments.is_empty() {
            return Err(PpoError::Environment("none given".into()));
        }
        let (observations, actions) = (self.normalizer.len(), self.log_std.len());
        for (e, env) in environments.iter().enumerate() {
            if env.observation_size() != observations || env.action_size() != actions {
                return Err(PpoError::Environment(format!(
                    "environment {e} has {} observation and {} action values, the policy {observations} and {actions}",
                    env.observation_size(),
                    env.action_size()
                )));
            }
        }
        Ok(())
    }

    /// One rollout in every environment, then the update.
    fn iterate<E: Environment>(
        &mut self,
        iteration: usize,
        environments: &mut [E],
        slots: &mut [Slot],
    ) -> Result<IterationStats, PpoError> {
        let mut rollouts = self.roll_out(iteration, environments, slots)?;
        let steps: usize = rollouts.iter().map(|r| r.rewards.len()).sum();
        let mean_reward = rollouts.iter().flat_map(|r| r.rewards.iter()).sum::<f64>() / steps.max(1) as f64;
        if self.config.normalize_rewards {
            self.scale_rewards(&mut rollouts, slots);
        }
        let (policy_loss, value_loss, learning_rate) = self.update(iteration, &rollouts)?;
        if self.config.observation_statistics == ObservationStatistics::EveryIteration {
            let raw: Vec<Vec<f64>> = rollouts
                .iter()
                .flat_map(|r| r.raw_observations.iter().cloned())
                .collect();
            self.normalizer.update(&raw);
        }
        let returns: Vec<f64> = rollouts
            .iter()
            .flat_map(|r| r.episode_returns.iter().copied())
            .collect();
        Ok(IterationStats {
            iteration,
            mean_reward,
            mean_episode_return: (!returns.is_empty()).then(|| returns.iter().sum::<f64>() / returns.len() as f64),
            episodes: returns.len(),
            policy_loss,
            value_loss,
            entropy: entropy(&self.log_std),
            learning_rate,
        })
    }

    /// `normalize_rewards`: each reward divided by √(var + 1e-8) of the discounted returns seen
    /// before this iteration and clipped to ±10; then this iteration's discounted returns (each
    /// environment's running one, reset at an episode's end; environments in order) join the
    /// statistics.
    fn scale_rewards(&mut self, rollouts: &mut [Rollout], slots: &mut [Slot]) {
        let scale = 1.0 / (self.return_statistics.var()[0] + REWARD_EPSILON).sqrt();
        let mut returns = Vec::new();
        for (r, slot) in rollouts.iter_mut().zip(slots.iter_mut()) {
            for (reward, &done) in r.rewards.iter_mut().zip(&r.dones) {
                slot.discounted_return = slot.discounted_return * self.config.gamma + *reward;
                returns.push(vec![slot.discounted_return]);
                if done {
                    slot.discounted_return = 0.0;
                }
                *reward = (*reward * scale).clamp(-REWARD_CLIP, REWARD_CLIP);
            }
        }
        self.return_statistics.update(&returns);
    }

    /// Adds the slots' current observations (environments in order) to the statistics.
    fn observe(&mut self, slots: &[Slot]) {
        let observations: Vec<Vec<f64>> = slots.iter().map(|s| s.observation.clone()).collect();
        self.normalizer.update(&observations);
    }

    /// `steps_per_environment` steps of every environment from its slot, stepped in parallel,
    /// actions sampled from the policy with a generator of (seed, iteration, environment). With
    /// statistics updated at every step, the environments go in lockstep and each step's new
    /// observations join the statistics (in environment order) before the next step.
    fn roll_out<E: Environment>(
        &mut self,
        iteration: usize,
        environments: &mut [E],
        slots: &mut [Slot],
    ) -> Result<Vec<Rollout>, PpoError> {
        let n = environments.len();
        let mut rngs: Vec<ChaCha8Rng> = (0..n)
            .map(|e| ChaCha8Rng::seed_from_u64(mix(self.seed, iteration as u64 + 1, e as u64)))
            .collect();
        let mut rollouts = vec![Rollout::default(); n];
        let steps = self.config.steps_per_environment;
        let (chunk, rounds) = match self.config.observation_statistics {
            ObservationStatistics::EveryStep => (1, steps),
            ObservationStatistics::EveryIteration => (steps, 1),
        };
        let mut passes = RolloutPasses::default();
        for _ in 0..rounds {
            for _ in 0..chunk {
                self.step_all(environments, slots, &mut rngs, &mut rollouts, &mut passes)?;
            }
            if chunk == 1 {
                self.observe(slots);
            }
        }
        for (r, slot) in rollouts.iter_mut().zip(slots.iter()) {
            r.last_value = self
                .critic
                .forward(&self.normalizer.normalize(&slot.observation))
                .output()[0];
        }
        Ok(rollouts)
    }

    /// One step of every environment from its slot, recorded into its rollout: the actions
    /// chosen together (both networks' forward passes over every environment's observation at
    /// once, [`Mlp::forward_batch`]: row by row the bits of one at a time), the environments
    /// stepped together ([`Environment::step_all`]), the steps recorded in parallel. Each
    /// environment goes through the same calls as when it stepped alone; the first failing
    /// environment (in order) stops the training.
    fn step_all<E: Environment>(
        &self,
        environments: &mut [E],
        slots: &mut [Slot],
        rngs: &mut [ChaCha8Rng],
        rollouts: &mut [Rollout],
        passes: &mut RolloutPasses,
    ) -> Result<(), PpoError> {
        passes.inputs.clear();
        let observations: Vec<Vec<f64>> = slots
            .iter()
            .map(|slot| self.normalizer.normalize(&slot.observation))
            .inspect(|o| passes.inputs.extend_from_slice(o))
            .collect();
        let n = observations.len();
        self.actor.forward_batch(&passes.inputs, n, &mut passes.actor);
        self.critic.forward_batch(&passes.inputs, n, &mut passes.critic);
        let actions: Vec<Vec<f64>> = observations
            .into_iter()
            .zip(rngs.iter_mut().zip(rollouts.iter_mut()))
            .enumerate()
            .map(|(e, (observation, (rng, r)))| {
                let (mean, value) = (passes.actor.output(e), passes.critic.output(e)[0]);
                self.choose(observation, mean, value, rng, r)
            })
            .collect();
        let steps = E::step_all(environments, &actions);
        let recorded: Vec<Result<(), PpoError>> = environments
            .par_iter_mut()
            .zip(slots.par_iter_mut())
            .zip(rollouts.par_iter_mut())
            .zip(steps.into_par_iter().zip(actions.into_par_iter()))
            .enumerate()
            .map(|(e, (((env, slot), r), (step, action)))| self.record(e, env, slot, r, step, action))
            .collect();
        recorded.into_iter().collect()
    }

    /// The action for a normalised observation whose policy mean and value are given, sampled
    /// with the environment's generator; its log-probability, the value and the observation go
    /// into `r`.
    fn choose(
        &self,
        observation: Vec<f64>,
        mean: &[f64],
        value: f64,
        rng: &mut ChaCha8Rng,
        r: &mut Rollout,
    ) -> Vec<f64> {
        let action: Vec<f64> = mean
            .iter()
            .zip(&self.log_std)
            .map(|(m, s)| m + s.exp() * standard_normal(rng))
            .collect();
        r.log_probs.push(log_prob(&action, mean, &self.log_std));
        r.values.push(value);
        r.observations.push(observation);
        action
    }

    /// Records environment `e`'s step with `action` into `r` and its slot; resets the
    /// environment at the end of an episode.
    fn record<E: Environment>(
        &self,
        e: usize,
        env: &mut E,
        slot: &mut Slot,
        r: &mut Rollout,
        step: Result<Transition, StepError>,
        action: Vec<f64>,
    ) -> Result<(), PpoError> {
        let step = step.map_err(|source| PpoError::Step {
            environment: Some(e),
            source,
        })?;
        if !step.reward.is_finite() || step.observation.iter().any(|v| !v.is_finite()) {
            return Err(PpoError::NonFinite(format!(
                "reward or observation from environment {e}"
            )));
        }
        let bootstrap = if step.truncated && self.config.bootstrap_time_limits {
            self.config.gamma
                * self
                    .critic
                    .forward(&self.normalizer.normalize(&step.observation))
                    .output()[0]
        } else {
            0.0
        };
        r.bootstraps.push(bootstrap);
        r.raw_observations
            .push(std::mem::replace(&mut slot.observation, step.observation));
        r.actions.push(action);
        r.rewards.push(step.reward);
        r.dones.push(step.done);
        slot.episode_return += step.reward;
        if step.done {
            r.episode_returns.push(slot.episode_return);
            slot.episode_return = 0.0;
            slot.episodes += 1;
            slot.observation = env.reset(mix(self.seed, e as u64, slot.episodes));
        }
        Ok(())
    }

    /// The update: `epochs` passes of minibatch Adam steps on the clipped objective, the value
    /// loss and the entropy bonus. Returns the last epoch's mean policy and value losses and the
    /// step size.
    fn update(&mut self, iteration: usize, rollouts: &[Rollout]) -> Result<(f64, f64, f64), PpoError> {
        let c = self.config.clone();
        let mut samples = Vec::new(); // (rollout, step, advantage, return)
        for (k, r) in rollouts.iter().enumerate() {
            let (advantages, returns) = r.advantages(c.gamma, c.lambda);
            samples.extend((0..r.rewards.len()).map(|t| (k, t, advantages[t], returns[t])));
        }
        let n = samples.len() as f64;
        let mean = samples.iter().map(|s| s.2).sum::<f64>() / n;
        let sd = (samples.iter().map(|s| (s.2 - mean).powi(2)).sum::<f64>() / n).sqrt();
        for s in &mut samples {
            s.2 = (s.2 - mean) / (sd + 1e-8);
        }
        let learning_rate = if c.decay_learning_rate {
            c.learning_rate * (1.0 - iteration as f64 / c.iterations as f64)
        } else {
            c.learning_rate
        };
        let (actor_len, actions) = (self.actor.parameters.len(), self.log_std.len());
        let mut rng = ChaCha8Rng::seed_from_u64(mix(self.seed, iteration as u64 + 1, u64::MAX));
        let size = samples.len().div_ceil(c.minibatches).max(1);
        let (mut policy_loss, mut value_loss) = (0.0, 0.0);
        // the minibatch's observations, output gradients and passes (reused: the passes over a
        // whole minibatch have the bits of one sample at a time, `mlp_batch`)
        let (mut inputs, mut d_mean, mut d_value, mut active) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut pass, mut value_pass) = (BatchPass::default(), BatchPass::default());
        for _ in 0..c.epochs {
            samples.shuffle(&mut rng);
            (policy_loss, value_loss) = (0.0, 0.0);
            for batch in samples.chunks(size) {
                let mut gradient = vec![0.0; self.adam_len()];
                let (actor_g, rest) = gradient.split_at_mut(actor_len);
                let (log_std_g, critic_g) = rest.split_at_mut(actions);
                let inv = 1.0 / batch.len() as f64;
                inputs.clear();
                for &(k, t, _, _) in batch {
                    inputs.extend_from_slice(&rollouts[k].observations[t]);
                }
                self.actor.forward_batch(&inputs, batch.len(), &mut pass);
                d_mean.clear();
                d_mean.resize(batch.len() * actions, 0.0);
                active.clear();
                for (s, &(k, t, advantage, _)) in batch.iter().enumerate() {
                    let r = &rollouts[k];
                    let new = log_prob(&r.actions[t], pass.output(s), &self.log_std);
                    let ratio = (new - r.log_probs[t]).exp();
                    let unclipped = ratio * advantage;
                    let clipped = ratio.clamp(1.0 - c.clip, 1.0 + c.clip) * advantage;
                    policy_loss -= unclipped.min(clipped) * inv;
                    active.push(unclipped <= clipped);
                    if unclipped <= clipped {
                        // d(−ratio·A)/d ln p = −ratio·A
                        add_log_prob_gradient(
                            &r.actions[t],
                            pass.output(s),
                            &self.log_std,
                            -unclipped * inv,
                            &mut d_mean[s * actions..(s + 1) * actions],
                            log_std_g,
                        );
                    }
                }
                self.actor.backward_batch(&mut pass, &d_mean, &active, actor_g);
                self.critic.forward_batch(&inputs, batch.len(), &mut value_pass);
                d_value.clear();
                let clip = c.clip_value_loss.then_some(c.clip);
                for (s, &(k, t, _, target)) in batch.iter().enumerate() {
                    let old = rollouts[k].values[t];
                    let (loss, d) = value_loss_of(value_pass.output(s)[0], old, target, clip);
                    value_loss += loss * inv;
                    d_value.push(c.value_coefficient * d * inv);
                }
                active.clear();
                active.resize(batch.len(), true);
                self.critic.backward_batch(&mut value_pass, &d_value, &active, critic_g);
                for g in log_std_g.iter_mut() {
                    *g -= c.entropy_coefficient; // the bonus: −coefficient · ∂ entropy / ∂ log σ
                }
                self.adam_step(&gradient, learning_rate)?;
            }
        }
        // the sums above add each minibatch's mean: their mean over the minibatches
        let batches = samples.len().div_ceil(size) as f64;
        Ok((policy_loss / batches, value_loss / batches, learning_rate))
    }

    fn adam_len(&self) -> usize {
        self.actor.parameters.len() + self.log_std.len() + self.critic.parameters.len()
    }

    /// One Adam step over (actor, log σ, critic).
    fn adam_step(&mut self, gradient: &[f64], learning_rate: f64) -> Result<(), PpoError> {
        let mut all = [self.actor.parameters.as_slice(), &self.log_std, &self.critic.parameters].concat();
        self.adam
            .step(&mut all, gradient, learning_rate, self.config.max_gradient_norm);
        if all.iter().any(|p| !p.is_finite()) {
            return Err(PpoError::NonFinite("parameter after an update".into()));
        }
        let (actor, rest) = all.split_at(self.actor.parameters.len());
        let (log_std, critic) = rest.split_at(self.log_std.len());
        self.actor.parameters.copy_from_slice(actor);
        self.log_std.copy_from_slice(log_std);
        self.critic.parameters.copy_from_slice(critic);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::environment::Transition;
    use crate::reach::Reach;

    fn reach(n: usize) -> Vec<Reach> {
        vec![Reach::default(); n]
    }

    fn small(iterations: usize) -> PpoConfig {
        PpoConfig {
            iterations,
            steps_per_environment: 64,
            learning_rate: 3e-3,
            hidden: vec![16, 16],
            ..PpoConfig::default()
        }
    }

    /// The clipped value loss is the unclipped one while V stays within ε of the old value, the
    /// larger of the two beyond, with no gradient where the clipped term wins and is clamped.
    #[test]
    fn the_clipped_value_loss_is_the_references() {
        assert_eq!(value_loss_of(1.5, 1.0, 0.5, None), (0.5, 1.0));
        // within the clip: the same loss and gradient
        let (loss, d) = value_loss_of(1.05, 1.0, 0.5, Some(0.1));
        assert!((loss - 0.5 * 0.55 * 0.55).abs() < 1e-12 && (d - 0.55).abs() < 1e-12);
        // V moved far towards the target: the clipped term (old + 0.1 − R)² is larger, no gradient
        let (loss, d) = value_loss_of(0.5, 1.0, 0.5, Some(0.1));
        assert!((loss - 0.5 * 0.4 * 0.4).abs() < 1e-12 && d == 0.0, "{loss} {d}");
        // V moved far away from the target: the unclipped term is larger and keeps its gradient
        let (loss, d) = value_loss_of(2.0, 1.0, 0.5, Some(0.1));
        assert!((loss - 0.5 * 1.5 * 1.5).abs() < 1e-12 && d == 1.5);
    }

    /// Scaled rewards: the first iteration's are the environment's (variance 1 at the start), the
    /// statistics then hold the discounted returns; the reported reward stays the environment's;
    /// with both reference options the reaching task is still learned.
    #[test]
    fn normalised_rewards_and_the_clipped_value_loss_still_learn() {
        let config = PpoConfig {
            normalize_rewards: true,
            clip_value_loss: true,
            ..small(60)
        };
        let without = PpoConfig {
            normalize_rewards: false,
            clip_value_loss: false,
            ..small(1)
        };
        let mut plain = Ppo::new(1, 1, without, 7).unwrap();
        let mut scaled = Ppo::new(
            1,
            1,
            PpoConfig {
                iterations: 1,
                ..config.clone()
            },
            7,
        )
        .unwrap();
        let (a, b) = (
            plain.train(&mut reach(4)).unwrap(),
            scaled.train(&mut reach(4)).unwrap(),
        );
        assert_eq!(
            a[0].mean_reward, b[0].mean_reward,
            "the same rollout, reported unscaled"
        );
        assert!(scaled.return_statistics.var()[0] != 1.0 && scaled.return_statistics.mean()[0] < 0.0);
        let mut ppo = Ppo::new(1, 1, config, 7).unwrap();
        let stats = ppo.train(&mut reach(4)).unwrap();
        let first = stats[0].mean_reward;
        let last = stats[stats.len() - 5..].iter().map(|s| s.mean_reward).sum::<f64>() / 5.0;
        assert!(last > first + 0.1, "mean reward per step {first:.3} → {last:.3}");
    }

    #[test]
    fn it_learns_to_reach_the_target() {
        let mut ppo = Ppo::new(1, 1, small(60), 7).unwrap();
        let stats = ppo.train(&mut reach(4)).unwrap();
        let first = stats[0].mean_reward;
        let last = stats[stats.len() - 5..].iter().map(|s| s.mean_reward).sum::<f64>() / 5.0;
        assert!(last > first + 0.1, "mean reward per step {first:.3} → {last:.3}");
        // the learned policy pushes towards 0 from either side
        assert!(
            ppo.act(&[0.8])[0] < -0.2 && ppo.act(&[-0.8])[0] > 0.2,
            "{:?} {:?}",
            ppo.act(&[0.8]),
            ppo.act(&[-0.8])
        );
        assert!(stats
            .iter()
            .all(|s| s.episodes > 0 && s.policy_loss.is_finite() && s.value_loss.is_finite()));
    }

    #[test]
    fn the_observer_sees_every_iteration_and_episodes_use_the_mean_action() {
        let mut ppo = Ppo::new(1, 1, small(5), 3).unwrap();
        let mut seen = Vec::new();
        let stats = ppo
            .train_observed(&mut reach(2), |p, s| {
                let (total, steps) = p.episode(&mut Reach::default(), 9, 1000)?;
                seen.push((s.map(|s| s.iteration), total, steps));
                Ok(())
            })
            .unwrap();
        assert_eq!(stats.len(), 5);
        let iterations: Vec<_> = seen.iter().map(|s| s.0).collect();
        assert_eq!(iterations, [None, Some(0), Some(1), Some(2), Some(3), Some(4)]);
        // the episode is deterministic and ends where the environment ends it
        let again = ppo.episode(&mut Reach::default(), 9, 1000).unwrap();
        assert_eq!(again, (seen[5].1, seen[5].2));
        assert!(again.1 > 0 && again.1 < 1000 && again.0.is_finite());
        assert_eq!(ppo.episode(&mut Reach::default(), 9, 3).unwrap().1, 3);
        // an observer's error stops the training
        let err = ppo
            .train_observed(&mut reach(2), |_, s| match s {
                Some(_) => Err(PpoError::NonFinite("stop".into())),
                None => Ok(()),
            })
            .unwrap_err();
        assert!(matches!(&err, PpoError::NonFinite(what) if what == "stop"), "{err}");
    }

    #[test]
    fn a_time_limit_is_bootstrapped_only_when_asked() {
        let run = |bootstrap: bool| {
            let config = PpoConfig {
                bootstrap_time_limits: bootstrap,
                ..small(2)
            };
            let mut ppo = Ppo::new(1, 1, config, 5).unwrap();
            format!("{:?}", ppo.train(&mut reach(2)).unwrap())
        };
        // Reach's episodes end by their time limit: the value estimates differ, so do the updates
        assert_ne!(run(true), run(false));
        assert_eq!(run(true), run(true));
    }

    #[test]
    fn statistics_at_every_step_are_deterministic_and_differ_from_once_per_iteration() {
        let train = |statistics: ObservationStatistics, threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| {
                let config = PpoConfig {
                    observation_statistics: statistics,
                    ..small(3)
                };
                let mut ppo = Ppo::new(1, 1, config, 11).unwrap();
                let stats = ppo.train(&mut reach(4)).unwrap();
                (format!("{stats:?}"), ppo.act(&[0.3]))
            })
        };
        let every_step = train(ObservationStatistics::EveryStep, 1);
        assert_eq!(every_step, train(ObservationStatistics::EveryStep, 2));
        assert_ne!(every_step, train(ObservationStatistics::EveryIteration, 1));
    }

    #[test]
    fn training_is_bit_identical_whatever_the_thread_count() {
        let train = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| {
                let mut ppo = Ppo::new(1, 1, small(3), 11).unwrap();
                let stats = ppo.train(&mut reach(4)).unwrap();
                (format!("{stats:?}"), ppo.act(&[0.3]), ppo.act(&[-0.6]))
            })
        };
        let one = train(1);
        assert_eq!(one, train(2));
        assert_eq!(one, train(1), "and run to run");
    }

    #[test]
    fn bad_settings_and_environments_are_refused_naming_what() {
        let bad = PpoConfig {
            clip: f64::NAN,
            ..PpoConfig::default()
        };
        assert!(matches!(
            Ppo::new(1, 1, bad, 0),
            Err(PpoError::Invalid { field: "clip", .. })
        ));
        let none = PpoConfig {
            minibatches: 0,
            ..PpoConfig::default()
        };
        assert!(matches!(
            Ppo::new(1, 1, none, 0),
            Err(PpoError::Invalid {
                field: "minibatches",
                ..
            })
        ));
        let mut two = Ppo::new(2, 1, small(1), 0).unwrap();
        let e = two.train(&mut reach(1)).unwrap_err().to_string();
        assert!(e.contains("environment 0 has 1 observation"), "{e}");
        struct Broken;
        impl Environment for Broken {
            fn observation_size(&self) -> usize {
                1
            }
            fn action_size(&self) -> usize {
                1
            }
            fn reset(&mut self, _: u64) -> Vec<f64> {
                vec![0.0]
            }
            fn step(&mut self, _: &[f64]) -> Result<Transition, StepError> {
                Ok(Transition {
                    observation: vec![f64::NAN],
                    reward: 0.0,
                    done: false,
                    truncated: false,
                })
            }
        }
        let mut ppo = Ppo::new(1, 1, small(1), 0).unwrap();
        assert!(matches!(ppo.train(&mut [Broken]), Err(PpoError::NonFinite(_))));
        // an environment's own error comes back typed, with the environment that gave it
        #[derive(Debug, thiserror::Error)]
        #[error("the robot fell apart")]
        struct Apart;
        struct Failing;
        impl Environment for Failing {
            fn observation_size(&self) -> usize {
                1
            }
            fn action_size(&self) -> usize {
                1
            }
            fn reset(&mut self, _: u64) -> Vec<f64> {
                vec![0.0]
            }
            fn step(&mut self, _: &[f64]) -> Result<Transition, StepError> {
                Err(Box::new(Apart))
            }
        }
        let err = ppo.train(&mut [Failing, Failing]).unwrap_err();
        assert_eq!(err.to_string(), "environments: environment 0: the robot fell apart");
        match err {
            PpoError::Step { environment, source } => {
                assert_eq!(environment, Some(0));
                assert!(source.downcast_ref::<Apart>().is_some());
            }
            other => panic!("expected a step error, got {other}"),
        }
        let err = ppo.episode(&mut Failing, 0, 5).unwrap_err();
        assert_eq!(err.to_string(), "environments: the robot fell apart");
    }
}
