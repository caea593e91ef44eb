//! Each EvoGym task with a full 5 × 5 body of horizontal actuators driven by a square-wave gait:
//! the summed reward of one episode, and the time of one environment step (30 substeps).
//!
//! `cargo run --release -p vsrlab-tasks --example evogym_speed [steps] [task name part] [lanes]`;
//! EvoGym's own environments with the same body and gait: `bench/evogym/tasks.py`
//! (docs/multimaterial.md has both). With `lanes`, also the environment stepped alone and four of
//! its episodes stepped together in population lanes (`EnvLanes`: observations and rewards
//! included), µs per step and episode, the fastest of five alternating rounds.

use std::time::Instant;
use vsrlab_tasks::kinds::evogym::{EnvLanes, EvoGymEnv, EvoGymTask, MaterialGrid, LANES};

fn gait(t: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| if (t + 5 * (i % 5)) % 20 < 10 { 1.6 } else { 0.6 })
        .collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: usize = std::env::args().nth(1).map_or(Ok(1000), |s| s.parse())?;
    let only = std::env::args().nth(2).filter(|o| o != "all");
    let lanes = std::env::args().nth(3).is_some_and(|a| a == "lanes");
    let body = MaterialGrid::from_rows("33333/33333/33333/33333/33333")?;
    for &task in EvoGymTask::ALL {
        if only.as_deref().is_some_and(|o| !task.name().starts_with(o)) {
            continue;
        }
        let built = Instant::now();
        let mut env = EvoGymEnv::new(task, &body)?;
        if task.world_count() > 1 {
            // a task that draws its world: seed 0's, and the time to build the environment
            let placed: Vec<String> = task
                .world()
                .objects()
                .iter()
                .map(|o| format!("{} at {:?}", o.name, o.origin))
                .collect();
            println!(
                "{:16} seed 0's world: {}; {} worlds built in {:.1} ms",
                task.name(),
                placed.join(", "),
                task.world_count(),
                built.elapsed().as_secs_f64() * 1e3
            );
        }
        if task.name() == "BidirectionalWalker-v0" {
            // the goals seed 0 draws (cells), for bench/evogym/tasks.py's --bidirectional-goals
            let goals: Vec<String> = env.task_memory()[1..].iter().map(|g| g.to_string()).collect();
            println!("{:16} seed 0's goals: {}", task.name(), goals.join(","));
        }
        let actions: Vec<Vec<f64>> = (0..20).map(|t| gait(t, env.action_count())).collect();
        // one episode of the task's own length: the reward to compare with EvoGym's
        let (mut reward, mut taken) = (0.0, 0);
        for t in 0..task.episode_steps() {
            let r = env.step(&actions[t % 20])?;
            reward += r.reward;
            taken += 1;
            if r.done || r.truncated {
                break;
            }
        }
        // then the time per step over `steps` steps, episodes restarted as they end
        env.reset(0);
        let clock = Instant::now();
        for t in 0..steps {
            if env.steps() >= task.episode_steps() {
                env.reset(0);
            }
            if env.step(&actions[t % 20])?.done {
                env.reset(0);
            }
        }
        let micros = clock.elapsed().as_secs_f64() / steps as f64 * 1e6;
        println!(
            "{:16} obs {:3}  actions {:2}  points {:3}  springs {:4}  reward {reward:+.9} over {taken} steps  {micros:7.1} µs/step",
            task.name(),
            env.observation_size(),
            env.action_count(),
            env.world().point_count(),
            env.world().spring_count(),
        );
        if lanes {
            env.reset(0);
            // five alternating rounds, the fastest of each (this machine's timings wander)
            let (mut alone, mut laned) = (f64::INFINITY, f64::INFINITY);
            for _ in 0..5 {
                alone = alone.min(alone_rate(&env, &actions, steps / 5)?);
                laned = laned.min(lanes_rate(&env, &actions, steps / 5)?);
            }
            println!(
                "{:16} alone {alone:7.1} µs/step; {LANES} lanes {laned:7.1} ({:.2}x) per episode",
                task.name(),
                alone / laned,
            );
        }
    }
    Ok(())
}

/// µs per step of `start` stepped alone with the gait, restarted when its episode ends.
fn alone_rate(start: &EvoGymEnv, actions: &[Vec<f64>], steps: usize) -> Result<f64, Box<dyn std::error::Error>> {
    let mut env = start.clone();
    let clock = Instant::now();
    for t in 0..steps {
        if env.is_over() {
            env = start.clone();
        }
        env.step(&actions[t % 20])?;
    }
    Ok(clock.elapsed().as_secs_f64() / steps as f64 * 1e6)
}

/// µs per step and episode of [`LANES`] episodes of `start` in lanes, each a twentieth of the gait ahead
/// of the last, an ended episode replaced by a fresh one.
fn lanes_rate(start: &EvoGymEnv, actions: &[Vec<f64>], steps: usize) -> Result<f64, Box<dyn std::error::Error>> {
    let mut lanes = EnvLanes::new(start);
    let mut envs = vec![start.clone(); LANES];
    let rounds = steps.div_ceil(LANES);
    let clock = Instant::now();
    for t in 0..rounds {
        for env in envs.iter_mut().filter(|e| e.is_over()) {
            *env = start.clone();
        }
        let targets: Vec<&[f64]> = (0..LANES).map(|l| actions[(t + l) % 20].as_slice()).collect();
        let mut borrowed: Vec<&mut EvoGymEnv> = envs.iter_mut().collect();
        for step in lanes.step(&mut borrowed, &targets)? {
            step?;
        }
    }
    Ok(clock.elapsed().as_secs_f64() / (rounds * LANES) as f64 * 1e6)
}
