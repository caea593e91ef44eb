//! Start-shift ensembles (docs/fidelity.md): one robot on one task, run from starts moved right
//! by k·δ (k = ±1 … ±n/2). Soft-robot gaits are chaotic, and a 10⁻⁶ shift can change a 30 s
//! velocity across a wide range. A single run says little, so we compare distributions over such
//! starts with the original simulator's (vsr-model.md §9.1).

use crate::agent::Robot;
use crate::episode::{self, EpisodeError};
use crate::outcome::TraceLevel;
use crate::registry::{FieldError, TaskSpec};
use rayon::prelude::*;
use serde::Serialize;

/// Median, quartiles, mean, standard deviation and range of an ensemble's values.
///
/// The quartiles are the sorted values at ranks round(0.25·(n − 1)) and round(0.75·(n − 1))
/// (0-based): the 8th and 23rd of 30, as in vsr-model.md §9.1. The median is the middle value, or
/// the mean of the two middle ones. The sd divides by n − 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Summary {
    /// Number of values.
    pub n: usize,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation (0 for one value).
    pub sd: f64,
    /// Median.
    pub median: f64,
    /// Lower quartile.
    pub q1: f64,
    /// Upper quartile.
    pub q3: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Summary {
    /// The summary of `values` (`None` when empty or when one is not finite).
    pub fn of(values: &[f64]) -> Option<Summary> {
        if values.is_empty() || values.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let mut v = values.to_vec();
        v.sort_by(f64::total_cmp);
        let n = v.len();
        let rank = |p: f64| v[((n - 1) as f64 * p).round() as usize];
        let median = if n % 2 == 1 {
            v[n / 2]
        } else {
            (v[n / 2 - 1] + v[n / 2]) / 2.0
        };
        let mean = v.iter().sum::<f64>() / n as f64;
        let sd = if n > 1 {
            (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        } else {
            0.0
        };
        Some(Summary {
            n,
            mean,
            sd,
            median,
            q1: rank(0.25),
            q3: rank(0.75),
            min: v[0],
            max: v[n - 1],
        })
    }
}

/// Why an ensemble could not be run.
#[derive(Debug, thiserror::Error)]
pub enum EnsembleError {
    /// The task has no start position to shift, or a bad one.
    #[error("{0}")]
    Task(String),
    /// An episode failed.
    #[error("start shifted by {shift:e}: {error}")]
    Episode {
        /// The shift of the failed start.
        shift: f64,
        /// What failed.
        error: EpisodeError,
    },
}

/// The shifts k·δ for k = −n/2 … −1, 1 … n/2 (no unshifted start), plus k = 0 when n is odd.
pub fn shifts(n: usize, delta: f64) -> Vec<f64> {
    let half = (n / 2) as i64;
    let mut ks: Vec<i64> = (-half..0).chain(1..=half).collect();
    if n % 2 == 1 {
        ks.insert(half as usize, 0);
    }
    ks.into_iter().map(|k| k as f64 * delta).collect()
}

/// `task` with its start (`initial_x`, the robot's left edge) moved right by `shift`.
pub fn shifted_task(task: &TaskSpec, shift: f64) -> Result<TaskSpec, EnsembleError> {
    let value = serde_json::to_value(task).map_err(|e| EnsembleError::Task(e.to_string()))?;
    let x = value.get("initial_x").and_then(|x| x.as_f64()).ok_or_else(|| {
        EnsembleError::Task(format!(
            "a {} task has no start position (initial_x) to shift",
            task.kind()
        ))
    })?;
    task.with_settings(&[("initial_x", serde_json::json!(x + shift))])
        .map_err(|e: FieldError| EnsembleError::Task(e.to_string()))
}

/// The metric `metric` of the episode from every shifted start, in the order of `shifts`, on
/// every core (each episode is independent and deterministic, so the order and the values do not
/// depend on the threads).
pub fn run_shifted(
    robot: &dyn Robot,
    task: &TaskSpec,
    shifts: &[f64],
    seed: u64,
    metric: &str,
) -> Result<Vec<f64>, EnsembleError> {
    let tasks = shifts
        .iter()
        .map(|&s| shifted_task(task, s))
        .collect::<Result<Vec<_>, _>>()?;
    tasks
        .par_iter()
        .zip(shifts.par_iter())
        .map(|(t, &shift)| {
            episode::run(robot, t.task(), seed, TraceLevel::None)
                .map(|o| o.metric(metric))
                .map_err(|error| EnsembleError::Episode { shift, error })
        })
        .collect()
}

/// The first simulated time at which the robot's centre x from the start shifted by `delta`
/// differs from the unshifted one by more than `tolerance`; `None` if they never part.
pub fn parting_time(
    robot: &dyn Robot,
    task: &TaskSpec,
    delta: f64,
    tolerance: f64,
    seed: u64,
) -> Result<Option<f64>, EnsembleError> {
    let run = |shift: f64| -> Result<crate::Trace, EnsembleError> {
        let t = shifted_task(task, shift)?;
        let outcome = episode::run(robot, t.task(), seed, TraceLevel::Center)
            .map_err(|error| EnsembleError::Episode { shift, error })?;
        Ok(outcome.trace.unwrap_or_default())
    };
    let (a, b) = rayon::join(|| run(0.0), || run(delta));
    let (a, b) = (a?, b?);
    Ok(a.centers
        .iter()
        .zip(&b.centers)
        .zip(&a.times)
        .find(|((p, q), _)| (p.x - q.x).abs() > tolerance)
        .map(|(_, &t)| t))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quartiles_follow_the_reference_convention() {
        let values: Vec<f64> = (1..=30).rev().map(f64::from).collect();
        let s = Summary::of(&values).unwrap();
        assert_eq!((s.q1, s.median, s.q3), (8.0, 15.5, 23.0), "8th, 15.5th and 23rd of 30");
        assert_eq!((s.min, s.max, s.mean, s.n), (1.0, 30.0, 15.5, 30));
        assert!((s.sd - 8.803408430829505).abs() < 1e-12, "{}", s.sd);
        let odd = Summary::of(&[3.0, 1.0, 2.0]).unwrap();
        assert_eq!((odd.median, odd.sd), (2.0, 1.0));
        assert!(Summary::of(&[]).is_none() && Summary::of(&[1.0, f64::NAN]).is_none());
    }

    #[test]
    fn shifts_are_symmetric_and_skip_zero_for_even_counts() {
        assert_eq!(shifts(4, 0.5), vec![-1.0, -0.5, 0.5, 1.0]);
        assert_eq!(shifts(3, 1.0), vec![-1.0, 0.0, 1.0]);
        assert_eq!(shifts(30, 1e-6).len(), 30);
    }

    #[test]
    fn a_shifted_task_moves_only_the_start() {
        let task = TaskSpec::parse("locomotion:flat").unwrap();
        let moved = shifted_task(&task, 0.25).unwrap();
        let (a, b) = (
            serde_json::to_value(&task).unwrap(),
            serde_json::to_value(&moved).unwrap(),
        );
        assert_eq!(
            b["initial_x"].as_f64().unwrap(),
            a["initial_x"].as_f64().unwrap() + 0.25
        );
        let mut b = b;
        b["initial_x"] = a["initial_x"].clone();
        assert_eq!(a, b);
        let jump = TaskSpec::parse("jump").unwrap();
        let e = shifted_task(&jump, 0.1).unwrap_err().to_string();
        assert!(e.contains("no start position"), "{e}");
    }
}
