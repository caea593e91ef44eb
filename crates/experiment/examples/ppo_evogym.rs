//! PPO (`vsrlab_learning`, the EvoGym examples' settings: 4 environments × 128 steps per
//! iteration, 4 epochs × 4 minibatches, 64-64 tanh networks) learning a controller for one fixed
//! body on an EvoGym task. Prints the return of a deterministic episode (the policy's mean
//! actions) every `EVERY` iterations and the seconds per iteration (collection + update), the
//! figures `bench/evogym/ppo.py` prints for EvoGym's own PPO (docs/learning.md).
//!
//! `cargo run --release -p vsrlab-experiment --example ppo_evogym -- [TASK] [ITERATIONS] [SEED] [EVERY] [BODY] [plain|clip-value-loss|normalize-rewards]`
//!
//! Defaults: Walker-v0, 100 iterations, seed 1, every 25, the 5×5 body of horizontal actuators.
//! The reference's clipped value loss and reward normalisation (`clip_value_loss`,
//! `normalize_rewards`) are on; `plain` turns both off, `clip-value-loss` or `normalize-rewards`
//! keeps only that one.
//! `RAYON_NUM_THREADS=1` steps the four environments one after the other, as EvoGym's example.

use vsrlab_experiment::learning_env::EvoGymLearning;
use vsrlab_learning::{Environment, Ppo, PpoConfig, PpoError};
use vsrlab_tasks::kinds::evogym::{EvoGymTask, MaterialGrid};

fn main() -> Result<(), PpoError> {
    let mut args = std::env::args().skip(1);
    let task_name = args.next().unwrap_or_else(|| "Walker-v0".to_string());
    let task = EvoGymTask::from_name(&task_name).unwrap_or_else(|| panic!("{}", EvoGymTask::unknown(&task_name)));
    let iterations: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100);
    let seed: u64 = args.next().and_then(|a| a.parse().ok()).unwrap_or(1);
    let every: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(25).max(1);
    let rows = args
        .next()
        .unwrap_or_else(|| "33333/33333/33333/33333/33333".to_string());
    let body = MaterialGrid::from_rows(&rows).expect("a body of EvoGym materials, rows joined by '/'");
    let make = || EvoGymLearning::new(task, &body).expect("a valid robot");
    let options = args.next().unwrap_or_default();
    let config = PpoConfig {
        iterations,
        clip_value_loss: matches!(options.as_str(), "" | "clip-value-loss"),
        normalize_rewards: matches!(options.as_str(), "" | "normalize-rewards"),
        ..PpoConfig::default()
    };
    let mut envs: Vec<EvoGymLearning> = (0..config.environments).map(|_| make()).collect();
    let (observations, actions) = (envs[0].observation_size(), envs[0].action_size());
    let mut ppo = Ppo::new(observations, actions, config.clone(), seed)?;
    let mut evaluation = make();
    let (mut training, mut last) = (0.0, std::time::Instant::now());
    ppo.train_observed(&mut envs, |p, stats| {
        training += last.elapsed().as_secs_f64();
        let done = stats.map_or(0, |s| s.iteration + 1);
        if done % every == 0 {
            let (total, steps) = p.episode(&mut evaluation, 0, task.episode_steps())?;
            let training = stats.map_or(String::new(), |s| {
                format!(
                    "; rollouts: {:+.5} per step, entropy {:.2}, value loss {:.2e}",
                    s.mean_reward, s.entropy, s.value_loss
                )
            });
            println!("after {done:4} iterations: return of the mean policy {total:+.3} over {steps} steps{training}");
        }
        last = std::time::Instant::now();
        Ok(())
    })?;
    let steps = iterations * config.environments * config.steps_per_environment;
    println!(
        "{task_name}, body {rows}: {iterations} iterations ({steps} steps) in {training:.1} s of training: {:.1} ms per iteration, {:.0} steps/s with the updates",
        1000.0 * training / iterations as f64,
        steps as f64 / training
    );
    Ok(())
}
