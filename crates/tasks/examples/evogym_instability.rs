//! Replays the runs of `bench/evogym/instability.py` (random bodies under held extreme actions)
//! in vsrlab's EvoGym model and compares where each episode ended: unstable at the same step as in
//! EvoGym, unstable at another step, or only in one of the two.
//!
//! `cargo run --release -p vsrlab-tasks --example evogym_instability FILE.json`

use serde::Deserialize;
use vsrlab_tasks::kinds::evogym::{ActionStream, EvoGymEnv, EvoGymTask, MaterialGrid};

#[derive(Deserialize)]
struct Recording {
    task: String,
    steps: usize,
    hold: usize,
    actions: (f64, f64),
    runs: Vec<Run>,
}

#[derive(Deserialize)]
struct Run {
    seed: u64,
    body: String,
    unstable_step: Option<usize>,
}

/// The step at which vsrlab ends the run as unstable, if it does, and that step's reward.
fn unstable_step(rec: &Recording, task: EvoGymTask, run: &Run) -> Result<Option<(usize, f64)>, String> {
    let body = MaterialGrid::from_rows(&run.body).map_err(|e| e.to_string())?;
    let mut env = EvoGymEnv::new(task, &body).map_err(|e| e.to_string())?;
    let mut stream = ActionStream::new(run.seed);
    let mut actions = vec![0.0; env.action_count()];
    for t in 0..rec.steps {
        if t % rec.hold == 0 {
            stream.fill_extremes(&mut actions, rec.actions.0, rec.actions.1);
        }
        let r = env.step(&actions).map_err(|e| e.to_string())?;
        if r.unstable {
            return Ok(Some((t + 1, r.reward)));
        }
        if r.done || r.truncated {
            break;
        }
    }
    Ok(None)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: evogym_instability FILE.json (written by bench/evogym/instability.py)")?;
    let rec: Recording = serde_json::from_str(&std::fs::read_to_string(&path)?)?;
    let task = EvoGymTask::from_name(&rec.task).ok_or("unknown task")?;
    let (mut same, mut other_step, mut only_evogym, mut only_vsrlab, mut neither) = (0, 0, 0, 0, 0);
    for run in &rec.runs {
        let ours = unstable_step(&rec, task, run)?;
        match (run.unstable_step, ours) {
            (Some(e), Some((v, reward))) if e == v => {
                same += 1;
                println!(
                    "run {:3} {}: unstable at step {e} in both (reward {reward})",
                    run.seed, run.body
                );
            }
            (Some(e), Some((v, _))) => {
                other_step += 1;
                println!(
                    "run {:3} {}: unstable at step {e} in EvoGym, {v} in vsrlab",
                    run.seed, run.body
                );
            }
            (Some(e), None) => {
                only_evogym += 1;
                println!("run {:3} {}: unstable at step {e} in EvoGym only", run.seed, run.body);
            }
            (None, Some((v, _))) => {
                only_vsrlab += 1;
                println!("run {:3} {}: unstable at step {v} in vsrlab only", run.seed, run.body);
            }
            (None, None) => neither += 1,
        }
    }
    println!(
        "{}: {} runs; unstable at the same step {same}, at another step {other_step}, only in EvoGym {only_evogym}, only in vsrlab {only_vsrlab}; stable in both {neither}",
        rec.task,
        rec.runs.len()
    );
    Ok(())
}
