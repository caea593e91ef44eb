//! Actuators: each step's target values become the goal lengths of the springs they drive.

use super::springs::Springs;
use super::MassSpringError;

/// Which springs each actuator drives (compressed rows), and how many actuators drive each spring.
#[derive(Debug, Clone, Default)]
pub(crate) struct Actuators {
    /// Actuator `i` drives `springs[offsets[i]..offsets[i + 1]]`.
    pub offsets: Vec<u32>,
    pub springs: Vec<u32>,
    /// Springs driven by at least one actuator, ascending, with their driver counts.
    pub driven: Vec<u32>,
    pub drivers: Vec<u32>,
}

impl Actuators {
    /// Builds the rows from one spring list per actuator.
    pub fn new(lists: &[Vec<u32>], spring_count: usize) -> Self {
        let mut offsets = vec![0u32];
        let mut springs = Vec::new();
        let mut count = vec![0u32; spring_count];
        for list in lists {
            for &s in list {
                springs.push(s);
                count[s as usize] += 1;
            }
            offsets.push(springs.len() as u32);
        }
        let driven: Vec<u32> = (0..spring_count as u32).filter(|&s| count[s as usize] > 0).collect();
        let drivers = driven.iter().map(|&s| count[s as usize]).collect();
        Self {
            offsets,
            springs,
            driven,
            drivers,
        }
    }

    /// Number of actuators.
    pub fn len(&self) -> usize {
        self.offsets.len() - 1
    }

    /// Checks `targets` (one finite value per actuator) before anything is changed.
    pub fn check(&self, targets: &[f64]) -> Result<(), MassSpringError> {
        if targets.len() != self.len() {
            return Err(MassSpringError::TargetCount {
                expected: self.len(),
                got: targets.len(),
            });
        }
        match targets.iter().position(|t| !t.is_finite()) {
            Some(actuator) => Err(MassSpringError::NonFiniteTarget {
                actuator,
                value: targets[actuator],
            }),
            None => Ok(()),
        }
    }

    /// Sets the goal of every driven spring to its initial length times the mean of its
    /// actuators' targets, each clipped into `range` first (EvoGym clips, then averages).
    pub fn set_goals(&self, targets: &[f64], range: (f64, f64), springs: &mut Springs) {
        for &s in &self.driven {
            springs.goal[s as usize] = 0.0;
        }
        for (i, &t) in targets.iter().enumerate() {
            let t = t.clamp(range.0, range.1);
            let (lo, hi) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
            for &s in &self.springs[lo..hi] {
                springs.goal[s as usize] += t;
            }
        }
        for (&s, &n) in self.driven.iter().zip(&self.drivers) {
            let s = s as usize;
            springs.goal[s] *= springs.initial[s] / f64::from(n);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::runs::Runs;
    use super::*;

    fn springs(n: usize) -> Springs {
        Springs {
            a: vec![0; n],
            b: vec![1; n],
            stiffness: vec![1.0; n],
            rest: vec![0.1; n],
            initial: vec![0.1; n],
            goal: vec![0.1; n],
            band: vec![0.25; n],
            active: Runs::where_(n, |_| true),
            stages: std::array::from_fn(|_| Runs::where_(n, |_| true)),
            tracked_length: vec![0.0; n],
        }
    }

    #[test]
    fn shared_springs_take_the_mean_of_clipped_targets_and_others_keep_their_goal() {
        // Actuator 0 drives springs 0 and 1, actuator 1 drives springs 1 and 2; spring 3 is passive.
        let act = Actuators::new(&[vec![0, 1], vec![1, 2]], 4);
        let mut s = springs(4);
        act.set_goals(&[2.0, 1.0], (0.6, 1.6), &mut s);
        // Spring 0: 1.6 (clipped) × 0.1; spring 1: (1.6 + 1.0) / 2 × 0.1; spring 2: 1.0 × 0.1.
        assert!((s.goal[0] - 0.16).abs() < 1e-15);
        assert!((s.goal[1] - 0.13).abs() < 1e-15);
        assert!((s.goal[2] - 0.10).abs() < 1e-15);
        assert_eq!(s.goal[3], 0.1);
        act.set_goals(&[0.0, 0.0], (0.6, 1.6), &mut s);
        assert!(
            (s.goal[1] - 0.06).abs() < 1e-15,
            "clipped up to 0.6 and not accumulated"
        );
    }

    #[test]
    fn wrong_target_count_and_nan_targets_are_refused() {
        let act = Actuators::new(&[vec![0]], 1);
        assert_eq!(
            act.check(&[]),
            Err(MassSpringError::TargetCount { expected: 1, got: 0 })
        );
        assert!(matches!(
            act.check(&[f64::NAN]),
            Err(MassSpringError::NonFiniteTarget { actuator: 0, .. })
        ));
        assert_eq!(act.check(&[1.0]), Ok(()));
    }
}
