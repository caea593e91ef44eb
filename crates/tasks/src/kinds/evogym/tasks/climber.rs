//! Climber-v0 (`climb.py:39`, class `Climb0`) and Climber-v1 (`climb.py:97`, class `Climb1`):
//! climb up a vertical pipe five cells wide, with fixed walls (v0) or walls with soft stretches
//! (v1).

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, GOAL_BONUS, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;

/// A climbing task: its world, length and goal height.
pub struct Climber {
    basics: Basics,
    /// The goal: the centre above this many cells.
    goal_cells: f64,
}

/// Climber-v0: fixed walls, a cap in row 89, the goal above 86 cells.
pub const CLIMBER_V0: Climber = Climber {
    basics: Basics {
        name: "Climber-v0",
        short_name: "climber",
        world: worlds::climber_v0,
        robot_origin: (1, 1),
        episode_steps: 400,
    },
    goal_cells: 86.0,
};

/// Climber-v1: walls with soft stretches, a cap in row 69, the goal above 65 cells.
pub const CLIMBER_V1: Climber = Climber {
    basics: Basics {
        name: "Climber-v1",
        short_name: "climber-v1",
        world: worlds::climber_v1,
        robot_origin: (1, 1),
        episode_steps: 600,
    },
    goal_cells: 65.0,
};

impl TaskDefinition for Climber {
    /// (The robot inside the pipe, on its floor.)
    fn basics(&self) -> &Basics {
        &self.basics
    }

    /// Centre velocity and relative positions (`climb.py:74-77`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotVelocity, Piece::RobotPositions]
    }

    /// The centre's rise; +1 and the end once the centre is above the goal (`climb.py:80-92`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = after.robot.1 - before.robot.1;
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        let goal = after.robot.1 > self.goal_cells * 0.1;
        if goal {
            value += GOAL_BONUS;
        }
        Reward { value, ends: goal }
    }
}

/// Climber-v2's names, world, start and length.
const CLIMBER_V2: Basics = Basics {
    name: "Climber-v2",
    short_name: "climber-v2",
    world: worlds::climber_v2,
    robot_origin: (1, 1),
    episode_steps: 1000,
};

/// Climber-v2 (`climb.py:155`, class `Climb2`): up a pipe that slants and turns right into a
/// tunnel; rewarded for height and, a fifth as much, for going right; no goal.
pub struct Climber2;

impl TaskDefinition for Climber2 {
    fn basics(&self) -> &Basics {
        &CLIMBER_V2
    }

    /// Centre velocity, the robot's orientation, relative positions, the ceiling with a sight of
    /// 3 (`climb.py:173`, `:192-197`).
    fn observation(&self) -> &'static [Piece] {
        &[
            Piece::RobotVelocity,
            Piece::RobotOrientation,
            Piece::RobotPositions,
            Piece::Ceiling(3),
        ]
    }

    /// The centre's rise plus 0.2 × its x gain (`climb.py:200-202`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = (after.robot.1 - before.robot.1) + (after.robot.0 - before.robot.0) * 0.2;
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        Reward { value, ends: false }
    }
}
