//! Time of one EvoGym environment step (30 substeps) of each task with a full 5 × 5 body of
//! horizontal actuators driven by a square-wave gait, and how far the gait takes the robot.
//!
//! `cargo run --release -p vsrlab-tasks --example evogym_speed [steps]` (EvoGym's own simulator:
//! about 1.4 ms per step for Walker-v0).

use std::time::Instant;
use vsrlab_tasks::kinds::evogym::{EvoGymEnv, EvoGymTask, MaterialGrid};

fn gait(t: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| if (t + 5 * (i % 5)) % 20 < 10 { 1.6 } else { 0.6 })
        .collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steps: usize = std::env::args().nth(1).map_or(Ok(500), |s| s.parse())?;
    let body = MaterialGrid::from_rows("33333/33333/33333/33333/33333")?;
    for task in EvoGymTask::ALL {
        let mut env = EvoGymEnv::new(task, &body)?;
        let actions: Vec<Vec<f64>> = (0..20).map(|t| gait(t, env.action_count())).collect();
        let start = env.robot_centre().0;
        let (mut done_at, mut total) = (None, 0.0);
        let clock = Instant::now();
        for t in 0..steps {
            if env.steps() >= task.episode_steps() {
                env.reset(0);
            }
            let r = env.step(&actions[t % 20])?;
            total += r.reward;
            if r.done {
                done_at = Some(t);
                break;
            }
        }
        let elapsed = clock.elapsed().as_secs_f64();
        let taken = done_at.map_or(steps, |t| t + 1);
        println!(
            "{:16} {:8.1} µs/step over {taken} steps; centre x moved {:+.3} (reward sum {:+.3}){}",
            task.name(),
            elapsed / taken as f64 * 1e6,
            env.robot_centre().0 - start,
            total,
            done_at.map_or(String::new(), |t| format!(", ended at step {t}")),
        );
    }
    Ok(())
}
