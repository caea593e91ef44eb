//! The rewards of EvoGym's tasks, as pure functions of centres of mass before and after a step
//! (simulator units, a cell is 0.1). Sources: `evogym/envs/walk.py` and
//! `evogym/envs/manipulate.py`, commit `f63c649`.

/// Subtracted when the step was unstable (`walk.py:62-64`, `manipulate.py:698-700`).
pub const UNSTABLE_PENALTY: f64 = 3.0;
/// Added when the goal is reached (`walk.py:67-69`, `manipulate.py:702-704`).
pub const GOAL_BONUS: f64 = 1.0;

/// A step's reward and whether it ends the episode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reward {
    /// The reward.
    pub value: f64,
    /// The task ends the episode: its goal was reached (with the bonus), or, in some tasks, the
    /// robot fell or flipped (with a penalty).
    pub ends: bool,
}

/// Walker-v0, BridgeWalker-v0, CaveCrawler-v0 (`walk.py:56-69`, `:128-141`, `:203-216`): the
/// robot centre's x gain, minus [`UNSTABLE_PENALTY`] when unstable, plus [`GOAL_BONUS`] once the
/// centre's x is beyond `goal_x`. EvoGym reads positions from the snapshot of the last stable
/// step, so an unstable step has `x_after == x_before` (`Sim.cpp:105-115`).
pub fn forward(x_before: f64, x_after: f64, goal_x: f64, unstable: bool) -> Reward {
    let mut value = x_after - x_before;
    if unstable {
        value -= UNSTABLE_PENALTY;
    }
    let goal = x_after > goal_x;
    if goal {
        value += GOAL_BONUS;
    }
    Reward { value, ends: goal }
}

/// How much closer `q` came to `target` in a step: `|target − q before| − |target − q after|`
/// (the balancers, `balance.py:37-38`).
pub fn approach(target: f64, before: f64, after: f64) -> f64 {
    (target - before).abs() - (target - after).abs()
}

/// Centres of the robot and of the task's object (BeamToppler's beam) at one time.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RobotAndBeam {
    /// The robot's centre (x, y).
    pub robot: (f64, f64),
    /// The task's object's centre (x, y); (0, 0) in a task without one.
    pub beam: (f64, f64),
    /// The robot's orientation since the start (`observe::Orientation`), in tasks that observe
    /// it; 0 in the others.
    pub robot_angle: f64,
    /// The task's own measure of the robot's shape (`TaskDefinition::measure`): a hull's area,
    /// a span; 0 in tasks without one.
    pub own: f64,
}

/// BeamToppler-v0 (`manipulate.py:647-669`, `:695-704`): the robot's approach to the beam along
/// x, plus the beam's displacement `|Δx| + 3 |Δy|`, plus 10 × its drop; minus
/// [`UNSTABLE_PENALTY`] when unstable; plus [`GOAL_BONUS`] when the beam's centre x is below
/// 0.2 (two cells from the origin).
pub fn topple(before: RobotAndBeam, after: RobotAndBeam, unstable: bool) -> Reward {
    let approach = (before.beam.0 - before.robot.0).abs() - (after.beam.0 - after.robot.0).abs();
    let moved = (after.beam.0 - before.beam.0).abs() + 3.0 * (after.beam.1 - before.beam.1).abs();
    let drop = 10.0 * (before.beam.1 - after.beam.1);
    let mut value = approach + moved + drop;
    if unstable {
        value -= UNSTABLE_PENALTY;
    }
    let goal = after.beam.0 < 2.0 * 0.1;
    if goal {
        value += GOAL_BONUS;
    }
    Reward { value, ends: goal }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn approach_is_the_distance_lost() {
        assert_eq!(approach(1.5, 0.5, 1.25), 0.75);
        assert_eq!(approach(1.5, 2.0, 2.5), -0.5);
        assert_eq!(approach(1.5, 1.0, 2.0), 0.0, "passing the target");
    }

    #[test]
    fn forward_reward_is_the_x_gain_with_penalty_and_bonus() {
        assert_eq!(
            forward(0.25, 0.375, 9.9, false),
            Reward {
                value: 0.125,
                ends: false
            }
        );
        assert_eq!(forward(0.5, 0.25, 9.9, false).value, -0.25);
        assert_eq!(
            forward(0.5, 0.5, 9.9, true),
            Reward {
                value: -3.0,
                ends: false
            }
        );
        assert_eq!(
            forward(9.875, 10.0, 9.9, false),
            Reward {
                value: 1.125,
                ends: true
            }
        );
        assert!(!forward(9.9, 9.9, 9.9, false).ends, "strictly beyond");
    }

    /// Robot from x 1 to 1.5 while the beam (x 3.5) moves 0.25 right and drops 0.5:
    /// approach |3.5 − 1| − |3.75 − 1.5| = 2.5 − 2.25 = 0.25; moved 0.25 + 3 × 0.5 = 1.75;
    /// drop 10 × 0.5 = 5; total 7.
    #[test]
    fn topple_reward_by_hand() {
        let before = RobotAndBeam {
            robot: (1.0, 0.25),
            beam: (3.5, 0.625),
            robot_angle: 0.0,
            own: 0.0,
        };
        let after = RobotAndBeam {
            robot: (1.5, 0.25),
            beam: (3.75, 0.125),
            robot_angle: 0.0,
            own: 0.0,
        };
        assert_eq!(
            topple(before, after, false),
            Reward {
                value: 7.0,
                ends: false
            }
        );
        assert_eq!(topple(before, before, true).value, -3.0);
        let far = RobotAndBeam {
            robot: (1.5, 0.25),
            beam: (0.125, 0.125),
            robot_angle: 0.0,
            own: 0.0,
        };
        assert!(topple(before, far, false).ends);
    }
}
