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
        world: climber_v0,
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
        world: climber_v1,
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
    world: climber_v2,
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

/// Climber-v0's world (`Climber-v0.json`, 7 × 90): `pipe`, fixed walls in columns 0 and 6, a
/// floor and a cap.
fn climber_v0() -> worlds::World {
    worlds::laid_out("pipe", &[(0, 0, "0-6"), (1, 88, "0, 6"), (89, 89, "0-6")])
}

/// Climber-v1's world (`Climber-v1.json`, 7 × 70): `pipe`, as Climber-v0's with the cap in row 69
/// and 42 soft wall cells in stretches on either side.
fn climber_v1() -> worlds::World {
    worlds::laid_out(
        "pipe",
        &[
            (0, 0, "0-6"),
            (1, 7, "0, 6"),
            (8, 8, "0, 6[2]"),
            (9, 10, "0, 6"),
            (11, 12, "0[2], 6"),
            (13, 14, "0, 6"),
            (15, 17, "0, 6[2]"),
            (18, 20, "0, 6"),
            (21, 22, "0[2], 6"),
            (23, 24, "0, 6[2]"),
            (25, 26, "0, 6"),
            (27, 27, "0[2], 6"),
            (28, 28, "0[2], 6[2]"),
            (29, 29, "0, 6[2]"),
            (30, 30, "0, 6"),
            (31, 32, "0[2], 6"),
            (33, 34, "0, 6"),
            (35, 35, "0[2], 6[2]"),
            (36, 37, "0, 6[2]"),
            (38, 38, "0, 6"),
            (39, 41, "0[2], 6"),
            (42, 44, "0, 6"),
            (45, 46, "0[2], 6[2]"),
            (47, 50, "0, 6"),
            (51, 53, "0[2], 6[2]"),
            (54, 55, "0, 6"),
            (56, 59, "0, 6[2]"),
            (60, 64, "0[2], 6"),
            (65, 68, "0, 6"),
            (69, 69, "0-6"),
        ],
    )
}

/// Climber-v2's world (`Climber-v2.json`, 27 × 42): `pipe`, fixed, rising straight, then stepping
/// right cell by cell, then turning right into a tunnel that ends at column 26.
fn climber_v2() -> worlds::World {
    worlds::laid_out(
        "pipe",
        &[
            (0, 0, "0-6"),
            (1, 18, "0, 6"),
            (19, 19, "0, 6-7"),
            (20, 22, "0, 7"),
            (23, 23, "0-1, 7"),
            (24, 26, "1, 7"),
            (27, 27, "1, 7-8"),
            (28, 29, "1, 8"),
            (30, 30, "1-2, 8"),
            (31, 31, "2, 8"),
            (32, 32, "2, 8-9"),
            (33, 33, "2, 9-10"),
            (34, 34, "2-3, 10-11"),
            (35, 35, "3, 11-26"),
            (36, 36, "3, 26"),
            (37, 37, "3-4, 26"),
            (38, 38, "4-5, 26"),
            (39, 39, "5-6, 26"),
            (40, 40, "6-7, 26"),
            (41, 41, "7-26"),
        ],
    )
}
