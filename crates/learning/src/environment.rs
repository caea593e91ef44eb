//! What PPO needs of an environment: observations, actions, rewards and the end of an episode.

use rayon::prelude::*;

/// The result of one step.
#[derive(Debug, Clone, PartialEq)]
pub struct Transition {
    /// The observation after the step.
    pub observation: Vec<f64>,
    /// The step's reward.
    pub reward: f64,
    /// Whether the episode ended with this step (the next step starts from a reset).
    pub done: bool,
    /// Whether it ended only because a time limit cut it (`done` is then true too): a learner
    /// may bootstrap from the value of `observation`, as if the episode went on.
    pub truncated: bool,
}

/// Why an environment could not step: its own typed error, kept whole (boxed, since every
/// environment has its own) so that the caller can print it or look inside.
pub type StepError = Box<dyn std::error::Error + Send + Sync>;

/// An episodic environment with continuous actions. Implementations must be deterministic in
/// the reset seed and the actions.
pub trait Environment: Send {
    /// Values per observation.
    fn observation_size(&self) -> usize;
    /// Values per action (the policy's output; the environment clips them to its own range).
    fn action_size(&self) -> usize;
    /// Starts an episode; `seed` makes it reproducible.
    fn reset(&mut self, seed: u64) -> Vec<f64>;
    /// One step with `action`; an error (the simulation failed in a way the environment cannot
    /// turn into the end of an episode) stops the training.
    fn step(&mut self, action: &[f64]) -> Result<Transition, StepError>;

    /// One step of each of `environments` with its action (`actions[i]` for `environments[i]`),
    /// in order: what [`Environment::step`] gives each alone, bit for bit. Environments that can
    /// step together (population lanes) override it; the default steps each alone, in parallel.
    fn step_all(environments: &mut [Self], actions: &[Vec<f64>]) -> Vec<Result<Transition, StepError>>
    where
        Self: Sized,
    {
        environments
            .par_iter_mut()
            .zip(actions)
            .map(|(env, action)| env.step(action))
            .collect()
    }
}
