//! Reinforcement learning for the co-design loop of thesis ch. 5.2: proximal policy optimisation
//! (Schulman et al. 2017) with a diagonal Gaussian policy and a separate value network, over any
//! [`Environment`] (observations, actions, rewards, done). It knows nothing of robots: a robot
//! task becomes an environment in the crates above it.
//!
//! The networks are small (64-64 tanh), so they are hand-written dense layers on `f64` with
//! their own backward pass ([`Mlp`]), updated by [`Adam`]. Environments are stepped in parallel
//! with rayon; every random draw comes from a generator seeded by (seed, iteration, environment),
//! so a run is bit-identical for a seed whatever the number of threads. docs/learning.md.

pub mod adam;
pub mod environment;
pub mod gaussian;
pub mod mean_policy;
pub mod mlp;
pub mod mlp_batch;
pub mod normalizer;
pub mod pendulum;
pub mod ppo;
pub mod reach;
pub mod rollout;

pub use adam::Adam;
pub use environment::{Environment, StepError, Transition};
pub use mean_policy::MeanPolicy;
pub use mlp::Mlp;
pub use mlp_batch::BatchPass;
pub use normalizer::Normalizer;
pub use ppo::{IterationStats, ObservationStatistics, Ppo, PpoConfig, PpoError};
