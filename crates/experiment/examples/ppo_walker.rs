//! PPO (`vsrlab_learning`, the EvoGym examples' settings) learning a controller for one fixed
//! body on EvoGym's Walker-v0: prints the mean reward per step and the episode returns as it
//! learns, then the return of the learned policy's mean actions (docs/learning.md).
//!
//! `cargo run --release -p vsrlab-experiment --example ppo_walker -- [ITERATIONS] [BODY]`

use vsrlab_experiment::learning_env::EvoGymLearning;
use vsrlab_learning::{Environment, Ppo, PpoConfig};
use vsrlab_tasks::kinds::evogym::{EvoGymTask, MaterialGrid};

fn main() {
    let mut args = std::env::args().skip(1);
    let iterations: usize = args.next().and_then(|a| a.parse().ok()).unwrap_or(100);
    let rows = args
        .next()
        .unwrap_or_else(|| "33333/33333/33333/33333/33333".to_string());
    let body = MaterialGrid::from_rows(&rows).expect("a body of EvoGym materials, rows joined by '/'");
    let make = || EvoGymLearning::new(EvoGymTask::Walker, &body).expect("a valid robot");
    let mut envs: Vec<EvoGymLearning> = (0..4).map(|_| make()).collect();
    let config = PpoConfig {
        iterations,
        ..PpoConfig::default()
    };
    let (observations, actions) = (envs[0].observation_size(), envs[0].action_size());
    let mut ppo = Ppo::new(observations, actions, config, 1).expect("valid settings");
    let start = std::time::Instant::now();
    let stats = ppo.train(&mut envs).expect("training");
    let seconds = start.elapsed().as_secs_f64();
    for s in stats
        .iter()
        .filter(|s| s.iteration % 10 == 0 || s.iteration + 1 == stats.len())
    {
        println!(
            "iteration {:4}: mean reward per step {:+.4}, episodes ended {}, mean return {}",
            s.iteration,
            s.mean_reward,
            s.episodes,
            s.mean_episode_return.map_or("-".to_string(), |r| format!("{r:+.3}"))
        );
    }
    // the learned policy without noise, one whole episode
    let mut env = make();
    let mut observation = env.reset(0);
    let (mut total, mut steps) = (0.0, 0);
    loop {
        let step = env.step(&ppo.act(&observation)).expect("a step");
        total += step.reward;
        steps += 1;
        observation = step.observation;
        if step.done {
            break;
        }
    }
    println!("body {rows}: return of the mean policy {total:+.3} over {steps} steps");
    println!(
        "{iterations} iterations of 4 × 128 steps ({} steps) in {seconds:.1} s: {:.0} steps/s with the updates",
        iterations * 512,
        (iterations * 512) as f64 / seconds
    );
}
