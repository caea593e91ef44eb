//! PPO on the pendulum swing-up (Gymnasium's Pendulum-v1), with rl-baselines3-zoo's PPO settings
//! for it but its state-dependent exploration (which vsrlab's PPO does not have): 4 environments
//! × 1024 steps per iteration, 10 epochs of 64-sample minibatches, learning rate 1e-3 (constant),
//! clip 0.2, γ 0.9, λ 0.95, no entropy bonus. Prints the mean return of 10 deterministic
//! episodes every 10 iterations (docs/learning.md).
//!
//! `cargo run --release -p vsrlab-learning --example pendulum -- [ITERATIONS] [SEED]`

use vsrlab_learning::pendulum::{Pendulum, PENDULUM_STEPS};
use vsrlab_learning::{Ppo, PpoConfig, PpoError};

/// Mean return of 10 deterministic episodes on seeds 1,000,000 onwards.
fn evaluate(ppo: &Ppo) -> Result<f64, PpoError> {
    let mut total = 0.0;
    for seed in 0..10 {
        total += ppo
            .episode(&mut Pendulum::default(), 1_000_000 + seed, PENDULUM_STEPS)?
            .0;
    }
    Ok(total / 10.0)
}

fn main() -> Result<(), PpoError> {
    let mut args = std::env::args().skip(1);
    let iterations = args.next().and_then(|a| a.parse().ok()).unwrap_or(25);
    let seed = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let config = PpoConfig {
        iterations,
        environments: 4,
        steps_per_environment: 1024,
        epochs: 10,
        minibatches: 64,
        learning_rate: 1e-3,
        decay_learning_rate: false,
        clip: 0.2,
        gamma: 0.9,
        lambda: 0.95,
        entropy_coefficient: 0.0,
        ..PpoConfig::default()
    };
    let mut ppo = Ppo::new(3, 1, config.clone(), seed)?;
    let mut envs = vec![Pendulum::default(); config.environments];
    let start = std::time::Instant::now();
    let mut curve = Vec::new();
    ppo.train_observed(&mut envs, |p, stats| {
        let iteration = stats.map_or(0, |s| s.iteration + 1);
        if iteration % 5 == 0 {
            let r = evaluate(p)?;
            println!(
                "after {iteration:3} iterations ({:7} steps): mean return {r:8.1}",
                iteration * 4096
            );
            curve.push(r);
        }
        Ok(())
    })?;
    println!(
        "{iterations} iterations ({} steps) in {:.1} s; last mean return {:.1}",
        iterations * 4096,
        start.elapsed().as_secs_f64(),
        curve.last().copied().unwrap_or(f64::NAN)
    );
    Ok(())
}
