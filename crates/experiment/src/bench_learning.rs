//! `vsrlab bench`'s learning rows: PPO iterations (collection of 4 × 128 steps, then the update
//! of 4 epochs × 4 minibatches; the EvoGym examples' settings) on an EvoGym task with the full
//! 5 × 5 body of horizontal actuators, the inner loop of ch. 5.2's co-design. Compared with
//! EvoGym 2.0's own PPO (stable-baselines3 2.8.0, one torch thread, the same settings), timed in
//! the same session by `bench/evogym/ppo.sh` (docs/learning.md).

use crate::bench::{BenchError, BenchOptions, Measured, Measurement, Mode, OriginalSpeed, Row};
use crate::cpu_time::{process_cpu_seconds, thread_cpu_seconds};
use crate::learning_env::EvoGymLearning;
use std::time::Instant;
use vsrlab_learning::{Environment, Ppo, PpoConfig};
use vsrlab_tasks::kinds::evogym::{EvoGymTask, MaterialGrid, STEP_SECONDS};

/// One learning row: a name (what `--robots` selects), its task and EvoGym's PPO's milliseconds
/// per iteration on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LearningCase {
    /// The row's name.
    pub name: &'static str,
    /// EvoGym's task name.
    pub task: &'static str,
    /// EvoGym's PPO, ms per iteration (bench/evogym/ppo.sh, this project's 2-core machine,
    /// 2026-11-27/28).
    pub evogym_ms_per_iteration: f64,
}

/// The learning rows, after the simulation rows.
pub const LEARNING_CASES: [LearningCase; 2] = [
    LearningCase {
        name: "ppo-walker",
        task: "Walker-v0",
        evogym_ms_per_iteration: 1122.0,
    },
    LearningCase {
        name: "ppo-bridge-walker",
        task: "BridgeWalker-v0",
        evogym_ms_per_iteration: 2040.0,
    },
];

/// The body of every learning row.
const BODY: &str = "33333/33333/33333/33333/33333";

impl LearningCase {
    /// A single-threaded row and, with `options.parallel`, one on `pool` (PPO steps its four
    /// environments in parallel; the update is sequential).
    pub fn rows(&self, options: &BenchOptions, pool: &rayon::ThreadPool) -> Result<Vec<Row>, BenchError> {
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
        let single = one.install(|| self.measure(options, thread_cpu_seconds))?;
        let mut rows = vec![self.row(Mode::Single, 1, single)];
        if options.parallel {
            let parallel = pool.install(|| self.measure(options, process_cpu_seconds))?;
            rows.push(self.row(Mode::Parallel, pool.current_num_threads(), parallel));
        }
        Ok(rows)
    }

    /// One warm-up iteration (none when `min_cpu_seconds` is 0: a quick look), then iterations of
    /// one training until `min_cpu_seconds` of `cpu_seconds` (at least one). An iteration
    /// collects at most `duration` simulated seconds per environment (the examples' 128 steps are
    /// 0.384 s, so shorter durations only shorten the rollouts).
    fn measure(&self, options: &BenchOptions, cpu_seconds: fn() -> f64) -> Result<Measurement, BenchError> {
        let failed = |e: String| BenchError::Learning(format!("{}: {e}", self.name));
        let task = EvoGymTask::from_name(self.task).ok_or_else(|| failed("unknown task".into()))?;
        let body = MaterialGrid::from_rows(BODY).map_err(|e| failed(e.to_string()))?;
        let defaults = PpoConfig::default();
        let config = PpoConfig {
            iterations: 1,
            steps_per_environment: rollout_steps(options.duration, defaults.steps_per_environment),
            ..defaults
        };
        let make = || EvoGymLearning::new(task, &body).map_err(|e| failed(e.to_string()));
        let mut envs = (0..config.environments)
            .map(|_| make())
            .collect::<Result<Vec<_>, _>>()?;
        let (observations, actions) = (envs[0].observation_size(), envs[0].action_size());
        let steps_per_iteration = (config.environments * config.steps_per_environment) as u64;
        let mut ppo = Ppo::new(observations, actions, config, 1).map_err(|e| failed(e.to_string()))?;
        if options.min_cpu_seconds > 0.0 {
            ppo.train(&mut envs).map_err(|e| failed(e.to_string()))?;
        }
        let (c0, w0) = (cpu_seconds(), Instant::now());
        let mut iterations = 0;
        while iterations == 0 || cpu_seconds() - c0 < options.min_cpu_seconds {
            ppo.train(&mut envs).map_err(|e| failed(e.to_string()))?;
            iterations += 1;
        }
        Ok(Measurement {
            episodes: iterations,
            steps: iterations as u64 * steps_per_iteration,
            cpu_seconds: cpu_seconds() - c0,
            wall_seconds: w0.elapsed().as_secs_f64(),
        })
    }

    /// The row: steps are environment steps of the collection, their rate counts the update's
    /// time too; "episodes" are iterations.
    fn row(&self, mode: Mode, threads: usize, m: Measurement) -> Row {
        // EvoGym's iterations were timed at the examples' full length
        let defaults = PpoConfig::default();
        let evogym_steps = (defaults.environments * defaults.steps_per_environment) as f64;
        let evogym = OriginalSpeed {
            steps_per_s: evogym_steps / (self.evogym_ms_per_iteration / 1000.0),
            version: "EvoGym 2.0.0 PPO (SB3 2.8.0)",
        };
        let what = Measured {
            robot: self.name,
            terrain: self.task,
            step_seconds: STEP_SECONDS,
            voxels: 25,
            mode,
            threads,
        };
        Row::measured(what, m, Some(evogym))
    }
}

/// Rollout steps per environment for episodes of `duration` simulated seconds: `default`, or
/// fewer when they would last longer (at least one).
fn rollout_steps(duration: f64, default: usize) -> usize {
    let steps = (duration / STEP_SECONDS).floor();
    if steps >= default as f64 {
        default
    } else {
        (steps as usize).max(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::run_bench;

    #[test]
    fn a_ppo_row_times_whole_iterations_against_evogyms_ppo() {
        let options = BenchOptions {
            min_cpu_seconds: 0.0,
            threads: Some(2),
            robots: Some(vec!["ppo-walker".into()]),
            ..BenchOptions::default()
        };
        let report = run_bench(&options).unwrap();
        assert_eq!(report.rows.len(), 2, "a single and a parallel row");
        let single = &report.rows[0];
        assert_eq!(
            (single.robot.as_str(), single.mode, single.voxels),
            ("ppo-walker", Mode::Single, 25)
        );
        assert!(single.episodes >= 1);
        assert_eq!(
            single.steps,
            single.episodes as u64 * 512,
            "4 environments × 128 steps each"
        );
        // EvoGym's PPO: 512 steps in 1,122 ms
        let evogym = single.original_steps_per_s.unwrap();
        assert!((evogym - 512.0 / 1.122).abs() < 1e-9, "{evogym}");
        assert!(single.ratio_to_original.unwrap() > 0.0);
        assert_eq!(report.rows[1].mode, Mode::Parallel);
        assert_eq!(report.rows[1].ratio_to_original, None);
    }

    #[test]
    fn short_durations_shorten_the_rollouts_but_not_evogyms_reference() {
        assert_eq!(rollout_steps(30.0, 128), 128);
        assert_eq!(rollout_steps(128.0 * STEP_SECONDS, 128), 128);
        assert_eq!(rollout_steps(0.2, 128), 66, "0.2 s of 3 ms steps");
        assert_eq!(rollout_steps(1e-9, 128), 1);
        let options = BenchOptions {
            duration: 0.03,
            min_cpu_seconds: 0.0,
            robots: Some(vec!["ppo-walker".into()]),
            parallel: false,
            ..BenchOptions::default()
        };
        let report = run_bench(&options).unwrap();
        let single = &report.rows[0];
        assert_eq!(single.steps, single.episodes as u64 * 40, "4 environments × 10 steps");
        let evogym = single.original_steps_per_s.unwrap();
        assert!((evogym - 512.0 / 1.122).abs() < 1e-9, "{evogym}");
    }
}
