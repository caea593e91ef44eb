//! PPO on a one-dimensional reaching task: prints the mean reward per step of each iteration
//! and the learned actions (docs/learning.md). `cargo run --release -p vsrlab-learning --example reach`

use vsrlab_learning::reach::Reach;
use vsrlab_learning::{Ppo, PpoConfig};

fn main() {
    let config = PpoConfig {
        iterations: 100,
        ..PpoConfig::default()
    };
    let mut ppo = Ppo::new(1, 1, config, 1).expect("valid settings");
    let mut envs = vec![Reach::default(); 4];
    let start = std::time::Instant::now();
    let stats = ppo.train(&mut envs).expect("finite environment");
    let seconds = start.elapsed().as_secs_f64();
    for s in stats
        .iter()
        .filter(|s| s.iteration % 10 == 0 || s.iteration + 1 == stats.len())
    {
        println!(
            "iteration {:3}: mean reward per step {:+.3}, episode return {:+.2}, entropy {:.3}",
            s.iteration,
            s.mean_reward,
            s.mean_episode_return.unwrap_or(f64::NAN),
            s.entropy
        );
    }
    println!(
        "actions at x = -0.8, 0, 0.8: {:+.3} {:+.3} {:+.3}",
        ppo.act(&[-0.8])[0],
        ppo.act(&[0.0])[0],
        ppo.act(&[0.8])[0]
    );
    println!("{} iterations of 4 × 128 steps in {seconds:.2} s", stats.len());
}
