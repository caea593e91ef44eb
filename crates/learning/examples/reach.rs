//! PPO on a one-dimensional reaching task: prints the mean reward per step of each iteration
//! and the learned actions (docs/learning.md). `cargo run --release -p vsrlab-learning --example reach`

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vsrlab_learning::{Environment, Ppo, PpoConfig, Transition};

/// A point on a line pushed by the action (clipped to ±1) towards 0: reward −|x| per step, 20
/// steps per episode, starting anywhere in [−1, 1].
struct Reach {
    x: f64,
    t: usize,
}

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
    fn step(&mut self, action: &[f64]) -> Result<Transition, String> {
        self.x += 0.2 * action[0].clamp(-1.0, 1.0);
        self.t += 1;
        Ok(Transition {
            observation: vec![self.x],
            reward: -self.x.abs(),
            done: self.t == 20,
        })
    }
}

fn main() {
    let config = PpoConfig {
        iterations: 100,
        ..PpoConfig::default()
    };
    let mut ppo = Ppo::new(1, 1, config, 1).expect("valid settings");
    let mut envs: Vec<Reach> = (0..4).map(|_| Reach { x: 0.0, t: 0 }).collect();
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
