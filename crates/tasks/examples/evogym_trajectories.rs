//! Replays the random action sequences of `bench/evogym/trajectories.py` in vsrlab's EvoGym model
//! and compares, per task, the robot's centre-of-mass trajectory and per-step rewards with the
//! ones EvoGym recorded: the largest deviations over the first steps and over whole episodes,
//! how many runs stay together to the end, and, where chaos makes single runs part, the mean and
//! spread of the summed rewards.
//!
//! `cargo run --release -p vsrlab-tasks --example evogym_trajectories FILE.json [TASK STEPS]`; with
//! a task name, also prints the first STEPS steps of that task's first run side by side.

use serde::Deserialize;
use vsrlab_tasks::kinds::evogym::{ActionStream, EvoGymEnv, EvoGymTask, MaterialGrid};

#[derive(Deserialize)]
struct Recording {
    action_range: (f64, f64),
    tasks: Vec<TaskRuns>,
}

#[derive(Deserialize)]
struct TaskRuns {
    task: String,
    body: String,
    runs: Vec<Run>,
}

#[derive(Deserialize)]
struct Run {
    seed: u64,
    com: Vec<(f64, f64)>,
    reward: Vec<f64>,
    end: Option<End>,
}

#[derive(Deserialize)]
struct End {
    terminated: bool,
}

/// What vsrlab did with one run's actions.
struct Replay {
    com: Vec<(f64, f64)>,
    reward: Vec<f64>,
    terminated: bool,
}

fn replay(task: EvoGymTask, body: &MaterialGrid, seed: u64, low: f64, high: f64) -> Result<Replay, String> {
    let mut env = EvoGymEnv::new(task, body).map_err(|e| e.to_string())?;
    env.reset(0);
    let mut rng = ActionStream::new(seed);
    let mut actions = vec![0.0; env.action_count()];
    let (mut com, mut reward) = (vec![env.robot_centre()], Vec::new());
    let mut terminated = false;
    for _ in 0..task.episode_steps() {
        rng.fill_uniform(&mut actions, low, high);
        let r = env.step(&actions).map_err(|e| e.to_string())?;
        let (step_reward, done, truncated) = (r.reward, r.done, r.truncated);
        reward.push(step_reward);
        com.push(env.robot_centre());
        if done || truncated {
            terminated = done;
            break;
        }
    }
    Ok(Replay {
        com,
        reward,
        terminated,
    })
}

/// Largest centre distance over steps `0..=upto` (both trajectories as long as that).
fn max_com_gap(a: &[(f64, f64)], b: &[(f64, f64)], upto: usize) -> f64 {
    a.iter()
        .zip(b)
        .take(upto + 1)
        .map(|(p, q)| (p.0 - q.0).hypot(p.1 - q.1))
        .fold(0.0, f64::max)
}

fn max_reward_gap(a: &[f64], b: &[f64], upto: usize) -> f64 {
    a.iter()
        .zip(b)
        .take(upto)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn mean_sd(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, var.sqrt())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: evogym_trajectories FILE.json (written by bench/evogym/trajectories.py)")?;
    let rec: Recording = serde_json::from_str(&std::fs::read_to_string(&path)?)?;
    let (low, high) = rec.action_range;
    if let Some(name) = std::env::args().nth(2) {
        let steps: usize = std::env::args().nth(3).map_or(Ok(20), |s| s.parse())?;
        let t = rec
            .tasks
            .iter()
            .find(|t| t.task == name)
            .ok_or("no such task in the file")?;
        let task = EvoGymTask::from_name(&t.task).ok_or("unknown task")?;
        let run = &t.runs[0];
        let ours = replay(task, &MaterialGrid::from_rows(&t.body)?, run.seed, low, high)?;
        println!("step  EvoGym x, y, reward  |  vsrlab x, y, reward");
        for k in 0..steps.min(run.com.len()).min(ours.com.len()) {
            let r = |v: &[f64]| if k == 0 { f64::NAN } else { v[k - 1] };
            let (e, o) = (run.com[k], ours.com[k]);
            println!(
                "{k:4}  {:.9} {:.9} {:+.3e}  |  {:.9} {:.9} {:+.3e}",
                e.0,
                e.1,
                r(&run.reward),
                o.0,
                o.1,
                r(&ours.reward)
            );
        }
    }
    println!("com@N: largest centre-of-mass gap |Δ| in m over the first N steps of every run (a cell is 0.1 m);");
    println!("rew@N: largest gap in one step's reward; same: runs whose centres stay within 1e-9 m to the end;");
    println!("Δtotal: largest gap in a run's summed reward; ends: episodes ended early (EvoGym/vsrlab)");
    println!(
        "{:16} {:>4} {:>9} {:>9} {:>9} {:>9} {:>10} {:>10} {:>19} {:>19} {:>5} {:>9} {:>6}",
        "task",
        "runs",
        "com@10",
        "com@50",
        "com@100",
        "com@end",
        "rew@50",
        "rew@end",
        "total EvoGym",
        "total vsrlab",
        "same",
        "Δtotal",
        "ends"
    );
    for t in &rec.tasks {
        let task = EvoGymTask::from_name(&t.task).ok_or_else(|| format!("unknown task {}", t.task))?;
        let body = MaterialGrid::from_rows(&t.body)?;
        let (mut gaps, mut rgaps) = ([0.0f64; 4], [0.0f64; 2]);
        let (mut tot_e, mut tot_v, mut same, mut total_gap) = (vec![], vec![], 0, 0.0f64);
        let (mut ends_e, mut ends_v) = (0, 0);
        for run in &t.runs {
            let ours = replay(task, &body, run.seed, low, high)?;
            let common = ours.com.len().min(run.com.len()) - 1;
            for (g, upto) in gaps.iter_mut().zip([10, 50, 100, common]) {
                *g = g.max(max_com_gap(&run.com, &ours.com, upto.min(common)));
            }
            for (g, upto) in rgaps.iter_mut().zip([50, common]) {
                *g = g.max(max_reward_gap(&run.reward, &ours.reward, upto.min(common)));
            }
            tot_e.push(run.reward.iter().sum());
            tot_v.push(ours.reward.iter().sum());
            let (te, tv): (f64, f64) = (run.reward.iter().sum(), ours.reward.iter().sum());
            total_gap = total_gap.max((te - tv).abs());
            let same_length = run.com.len() == ours.com.len();
            same += usize::from(same_length && max_com_gap(&run.com, &ours.com, common) < 1e-9);
            ends_e += usize::from(run.end.as_ref().is_some_and(|e| e.terminated));
            ends_v += usize::from(ours.terminated);
        }
        let ((me, se), (mv, sv)) = (mean_sd(&tot_e), mean_sd(&tot_v));
        println!(
            "{:16} {:>4} {:>9.2e} {:>9.2e} {:>9.2e} {:>9.2e} {:>10.2e} {:>10.2e} {:>+9.4}±{:<9.4} {:>+9.4}±{:<9.4} {:>5} {:>9.2e} {:>3}/{:<3}",
            t.task,
            t.runs.len(),
            gaps[0],
            gaps[1],
            gaps[2],
            gaps[3],
            rgaps[0],
            rgaps[1],
            me,
            se,
            mv,
            sv,
            same,
            total_gap,
            ends_e,
            ends_v
        );
    }
    Ok(())
}
