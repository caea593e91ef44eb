//! BidirectionalWalker-v0 (`multi_goal.py:98`, class `BiWalk` on `GoalBase`): walk to a
//! sequence of goals on a line, left and right, drawn at every reset.
//!
//! EvoGym draws the goals from Python's unseeded global `random` (reference sheet §2.3), so no
//! two of its episodes share them; vsrlab draws them from the episode's seed (the same seed, the
//! same goals), with EvoGym's rule: from x = 35 cells, goals uniform in 20 … 49 cells until their
//! summed distances reach 100 cells.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, GOAL_BONUS, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;
use rand::{Rng, SeedableRng};

/// BidirectionalWalker-v0. Its memory: the current goal's index, then the goals (cells).
pub struct BidirectionalWalker;

/// Where the goal draw starts, and the summed distance it stops at (cells).
const START_CELLS: f64 = 35.0;
const DISTANCE_CELLS: f64 = 100.0;
/// A goal is reached within this distance of the centre.
const REACHED: f64 = 2.0 * 0.1;

/// BidirectionalWalker-v0's names, world, start and length (Mid-line: a 5-wide robot's centre at 35.5 cells.).
const BASICS: Basics = Basics {
    name: "BidirectionalWalker-v0",
    short_name: "bidirectional-walker",
    world: bidirectional_walker_v0,
    robot_origin: (33, 1),
    episode_steps: 1000,
};

impl TaskDefinition for BidirectionalWalker {
    fn basics(&self) -> &Basics {
        &BASICS
    }

    /// Centre velocity, relative positions, then the current goal's index, its x and its x
    /// minus the centre's (`multi_goal.py:143-155`, `:79-81`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotVelocity, Piece::RobotPositions, Piece::Task(3)]
    }

    /// The goals, drawn from `seed` (`multi_goal.py:118-127`).
    fn start(&self, seed: u64, memory: &mut Vec<f64>) {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        memory.clear();
        memory.push(0.0);
        let (mut at, mut distance) = (START_CELLS, 0.0);
        while distance < DISTANCE_CELLS {
            let goal = f64::from(rng.random_range(20u32..50));
            distance += (at - goal).abs();
            at = goal;
            memory.push(goal);
        }
    }

    fn observe(&self, now: RobotAndBeam, memory: &[f64], out: &mut [f64]) {
        let index = memory[0];
        let goal = memory.get(1 + index as usize).map_or(0.0, |g| g * 0.1);
        out.copy_from_slice(&[index, goal, goal - now.robot.0]);
    }

    /// The approach to the current goal; a goal reached (the centre within 2 cells) gives way to
    /// the next, whose approach over the same step replaces the reward; +1 and the end when the
    /// last is reached (`multi_goal.py:30-46`, `:62-72`, `:157-171`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, memory: &mut [f64]) -> Reward {
        let goals = memory.len() - 1;
        let mut value = 0.0;
        let mut reached = true;
        while reached && (memory[0] as usize) < goals {
            let goal = memory[1 + memory[0] as usize] * 0.1;
            let far = (goal - after.robot.0).abs();
            value = (goal - before.robot.0).abs() - far;
            reached = far < REACHED;
            if reached {
                memory[0] += 1.0;
            }
        }
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        let ends = memory[0] as usize == goals;
        if ends {
            value += GOAL_BONUS;
        }
        Reward { value, ends }
    }
}

/// BidirectionalWalker-v0's world (`BidirectionalWalker-v0.json`): `new_object_1`, a row of 70
/// fixed cells at (0, 0).
fn bidirectional_walker_v0() -> worlds::World {
    worlds::laid_out("new_object_1", &[(0, 0, "0-69")])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The goals: the same for a seed, others for another, each in 20 … 49 cells, drawn until
    /// their summed distances from x = 35 first reach 100 cells.
    #[test]
    fn goals_are_drawn_from_the_seed_by_evogyms_rule() {
        let (mut a, mut b, mut c) = (Vec::new(), Vec::new(), Vec::new());
        BidirectionalWalker.start(7, &mut a);
        BidirectionalWalker.start(7, &mut b);
        BidirectionalWalker.start(8, &mut c);
        assert_eq!(a, b);
        assert_ne!(a, c);
        for memory in [&a, &c] {
            assert_eq!(memory[0], 0.0);
            let goals = &memory[1..];
            assert!(goals.iter().all(|&g| (20.0..=49.0).contains(&g) && g.fract() == 0.0));
            let legs: Vec<f64> = std::iter::once(35.0).chain(goals.iter().copied()).collect();
            let distances: Vec<f64> = legs.windows(2).map(|w| (w[1] - w[0]).abs()).collect();
            let total: f64 = distances.iter().sum();
            assert!(total >= 100.0 && total - distances.last().unwrap() < 100.0, "{goals:?}");
        }
    }

    /// Goals at 3 and 4 (cells 30, 40): a step from x 2.9 to 2.95 reaches the first (0.05 from
    /// it), so the second's approach over the same step is the reward, 0.05; a step from 3.7 to
    /// 3.9 then reaches the last: its approach 0.2, +1, the end.
    #[test]
    fn a_reached_goal_gives_way_to_the_next_on_the_same_step() {
        let at = |x: f64| RobotAndBeam {
            robot: (x, 0.3),
            ..RobotAndBeam::default()
        };
        let mut memory = vec![0.0, 30.0, 40.0];
        let r = BidirectionalWalker.reward(at(2.9), at(2.95), false, &mut memory);
        assert!((r.value - 0.05).abs() < 1e-12 && !r.ends, "{r:?}");
        assert_eq!(memory[0], 1.0);
        let mut observed = [0.0; 3];
        BidirectionalWalker.observe(at(2.95), &memory, &mut observed);
        assert_eq!(observed[..2], [1.0, 40.0 * 0.1]);
        let r = BidirectionalWalker.reward(at(3.7), at(3.9), false, &mut memory);
        assert!((r.value - (0.2 + 1.0)).abs() < 1e-12 && r.ends, "{r:?}");
    }
}
