//! The walking tasks of `traverse.py` on class `StairsBase`: UpStepper-v0 (`StepsUp`),
//! DownStepper-v0 (`StepsDown`), ObstacleTraverser-v0 and -v1 (`WalkingBumpy`,
//! `WalkingBumpy2`), Hurdler-v0 (`VerticalBarrier`), PlatformJumper-v0 (`FloatingPlatform`) and
//! GapJumper-v0 (`Gaps`), Traverser-v0 (`BlockSoup`): walk right over uneven ground; each ends on its own mix of a goal (+2),
//! a fall (−3) and a flip (−3).

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;
use std::f64::consts::PI;

/// The goal bonus of this family (the walkers of `walk.py` give +1).
const STAIRS_GOAL_BONUS: f64 = 2.0;
/// Subtracted for a flip or a fall.
const STAIRS_PENALTY: f64 = 3.0;

/// A task of the family.
pub struct Stairs {
    basics: Basics,
    /// The goal: the centre's x beyond this many cells (+2, the end).
    goal_cells: Option<f64>,
    /// The fall: the centre's y below this (−3, the end).
    fall_below: Option<f64>,
    /// The flip: the robot's orientation strictly inside this band (−3, the end).
    flip: Option<(f64, f64)>,
}

/// Upside down: between a quarter and three quarters of a turn (`math.pi/2`, `3*math.pi/2`).
const UPSIDE_DOWN: (f64, f64) = (PI / 2.0, 3.0 * PI / 2.0);

/// UpStepper-v0 (`traverse.py:51`): up a staircase.
pub const UP_STEPPER: Stairs = Stairs {
    basics: Basics {
        name: "UpStepper-v0",
        short_name: "up-stepper",
        world: worlds::up_stepper_v0,
        robot_origin: (1, 1),
        episode_steps: 600,
    },
    goal_cells: Some(69.0),
    fall_below: None,
    flip: Some((PI / 2.0 - PI / 12.0, 3.0 * PI / 2.0 + PI / 12.0)),
};

/// DownStepper-v0 (`traverse.py:116`): down a staircase, starting a cell above its top.
pub const DOWN_STEPPER: Stairs = Stairs {
    basics: Basics {
        name: "DownStepper-v0",
        short_name: "down-stepper",
        world: worlds::down_stepper_v0,
        robot_origin: (1, 11),
        episode_steps: 500,
    },
    goal_cells: Some(74.0),
    fall_below: None,
    flip: Some(UPSIDE_DOWN),
};

/// ObstacleTraverser-v0 (`traverse.py:181`): over bumps one or two cells high.
pub const OBSTACLE_TRAVERSER_V0: Stairs = Stairs {
    basics: Basics {
        name: "ObstacleTraverser-v0",
        short_name: "obstacle-traverser",
        world: worlds::obstacle_traverser_v0,
        robot_origin: (2, 1),
        episode_steps: 1000,
    },
    goal_cells: Some(79.0),
    fall_below: None,
    flip: Some(UPSIDE_DOWN),
};

/// ObstacleTraverser-v1 (`traverse.py:247`): over rugged ground; no flip test.
pub const OBSTACLE_TRAVERSER_V1: Stairs = Stairs {
    basics: Basics {
        name: "ObstacleTraverser-v1",
        short_name: "obstacle-traverser-v1",
        world: worlds::obstacle_traverser_v1,
        robot_origin: (2, 4),
        episode_steps: 1000,
    },
    goal_cells: Some(59.0),
    fall_below: None,
    flip: None,
};

/// Hurdler-v0 (`traverse.py:310`): over hurdles; no goal.
pub const HURDLER: Stairs = Stairs {
    basics: Basics {
        name: "Hurdler-v0",
        short_name: "hurdler",
        world: worlds::hurdler_v0,
        robot_origin: (2, 4),
        episode_steps: 1000,
    },
    goal_cells: None,
    fall_below: None,
    flip: Some(UPSIDE_DOWN),
};

/// PlatformJumper-v0 (`traverse.py:371`): from platform to floating platform; no goal.
pub const PLATFORM_JUMPER: Stairs = Stairs {
    basics: Basics {
        name: "PlatformJumper-v0",
        short_name: "platform-jumper",
        world: worlds::platform_jumper_v0,
        robot_origin: (1, 6),
        episode_steps: 1000,
    },
    goal_cells: None,
    fall_below: Some(0.4),
    flip: Some(UPSIDE_DOWN),
};

/// GapJumper-v0 (`traverse.py:456`): over gaps between platforms; no goal, no flip test.
pub const GAP_JUMPER: Stairs = Stairs {
    basics: Basics {
        name: "GapJumper-v0",
        short_name: "gap-jumper",
        world: worlds::gap_jumper_v0,
        robot_origin: (1, 6),
        episode_steps: 1000,
    },
    goal_cells: None,
    fall_below: Some(4.0 * 0.1),
    flip: None,
};

/// Traverser-v0 (`traverse.py:536`, `BlockSoup`): over a pit filled with 27 free rigid blocks.
pub const TRAVERSER: Stairs = Stairs {
    basics: Basics {
        name: "Traverser-v0",
        short_name: "traverser",
        world: worlds::traverser_v0,
        robot_origin: (1, 9),
        episode_steps: 600,
    },
    goal_cells: Some(59.0),
    fall_below: None,
    flip: None,
};

impl TaskDefinition for Stairs {
    fn basics(&self) -> &Basics {
        &self.basics
    }

    /// Centre velocity, the robot's orientation, relative positions, the floor with a sight of 5.
    fn observation(&self) -> &'static [Piece] {
        &[
            Piece::RobotVelocity,
            Piece::RobotOrientation,
            Piece::RobotPositions,
            Piece::Floor(5),
        ]
    }

    /// The centre's x gain; then, in the file's order, the goal, the fall and the flip.
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = after.robot.0 - before.robot.0;
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        let mut ends = false;
        if self.goal_cells.is_some_and(|cells| after.robot.0 > cells * 0.1) {
            value += STAIRS_GOAL_BONUS;
            ends = true;
        }
        if self.fall_below.is_some_and(|y| after.robot.1 < y) {
            value -= STAIRS_PENALTY;
            ends = true;
        }
        if self
            .flip
            .is_some_and(|(lo, hi)| after.robot_angle > lo && after.robot_angle < hi)
        {
            value -= STAIRS_PENALTY;
            ends = true;
        }
        Reward { value, ends }
    }
}
