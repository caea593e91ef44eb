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
        world: up_stepper_v0,
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
        world: down_stepper_v0,
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
        world: obstacle_traverser_v0,
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
        world: obstacle_traverser_v1,
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
        world: hurdler_v0,
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
        world: platform_jumper_v0,
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
        world: gap_jumper_v0,
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
        world: traverser_v0,
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

/// UpStepper-v0's world (`UpStepper-v0.json`, 70 × 9): `ground`, a staircase up from row 0 to
/// row 8, one cell per step.
fn up_stepper_v0() -> worlds::World {
    worlds::laid_out(
        "ground",
        &[
            (0, 0, "0-20"),
            (1, 1, "20-29"),
            (2, 2, "29-36"),
            (3, 3, "36-42"),
            (4, 4, "42-47"),
            (5, 5, "47-51"),
            (6, 6, "51-55"),
            (7, 7, "55-61"),
            (8, 8, "61-69"),
        ],
    )
}

/// DownStepper-v0's world (`DownStepper-v0.json`, 75 × 10): `ground`, a staircase down from row 9
/// to row 0.
fn down_stepper_v0() -> worlds::World {
    worlds::laid_out(
        "ground",
        &[
            (9, 9, "0-20"),
            (8, 8, "20-28"),
            (7, 7, "28-35"),
            (6, 6, "35-41"),
            (5, 5, "41-47"),
            (4, 4, "47-52"),
            (3, 3, "52-57"),
            (2, 2, "57-61"),
            (1, 1, "61-65"),
            (0, 0, "65-74"),
        ],
    )
}

/// ObstacleTraverser-v0's world (`ObstacleTraverser-v0.json`, 80 × 3): `ground`, a floor with
/// bumps one or two cells high.
fn obstacle_traverser_v0() -> worlds::World {
    worlds::laid_out(
        "ground",
        &[
            (0, 0, "0-79"),
            (
                1,
                1,
                "22, 28, 33-34, 39, 42-43, 45, 47, 50-51, 54-57, 59-60, 62-65, 67-68, 72",
            ),
            (2, 2, "55, 60, 64"),
        ],
    )
}

/// ObstacleTraverser-v1's world (`ObstacleTraverser-v1.json`, 60 × 10): `ground`, rugged ground
/// two to four rows thick with a wall at the end.
fn obstacle_traverser_v1() -> worlds::World {
    worlds::laid_out(
        "ground",
        &[
            (0, 0, "0-59"),
            (1, 1, "0-15, 17-59"),
            (
                2,
                2,
                "0-7, 9, 12-13, 17-19, 21-24, 26, 28-29, 31-33, 35-40, 42-50, 53-55, 57-59",
            ),
            (3, 3, "2, 4, 18, 23, 32-33, 36, 38-40, 43-45, 47, 49, 54, 58-59"),
            (4, 4, "44, 58-59"),
            (5, 9, "58-59"),
        ],
    )
}

/// Hurdler-v0's world (`Hurdler-v0.json`, 70 × 6): `ground`, a floor with hurdles one or two cells
/// high and a wall at the end.
fn hurdler_v0() -> worlds::World {
    worlds::laid_out(
        "ground",
        &[
            (0, 0, "0-69"),
            (1, 1, "12, 20, 28, 36-37, 45, 52, 58, 69"),
            (2, 2, "20, 36-37, 52, 58, 69"),
            (3, 5, "69"),
        ],
    )
}

/// GapJumper-v0's world (`GapJumper-v0.json`, 80 × 6): five platforms in row 5 with gaps of five
/// cells, and no ground.
fn gap_jumper_v0() -> worlds::World {
    platforms(&[
        ("platform_1", (0, 5), 20),
        ("platform_2", (25, 5), 10),
        ("platform_3", (40, 5), 10),
        ("platform_4", (55, 5), 10),
        ("platform_5", (70, 5), 10),
    ])
}

/// PlatformJumper-v0's world (`PlatformJumper-v0.json`, 91 × 9): seven platforms at different
/// heights, and no ground.
fn platform_jumper_v0() -> worlds::World {
    platforms(&[
        ("platform_1", (0, 5), 20),
        ("platform_2", (21, 7), 10),
        ("platform_3", (33, 8), 10),
        ("platform_4", (46, 6), 10),
        ("platform_5", (57, 5), 10),
        ("platform_6", (70, 6), 10),
        ("platform_7", (81, 3), 10),
    ])
}

/// Traverser-v0's world (`Traverser-v0.json`, 60 × 9, and `traverse.py:553-580`): `ground`, a
/// left shelf, a pit and a right shelf, and 27 free rigid blocks `block_0` … `block_26` of 3 × 3,
/// 2 × 2 or 1 × 1 cells placed in the pit in three layers, as EvoGym's code places them.
fn traverser_v0() -> worlds::World {
    let mut world = worlds::laid_out(
        "ground",
        &[
            (0, 0, "19-49"),
            (1, 5, "19, 49"),
            (6, 6, "19, 49-59"),
            (7, 7, "19"),
            (8, 8, "0-19"),
        ],
    );
    let mut blocks: Vec<(usize, usize, usize)> = vec![
        (20, 1, 3),
        (24, 1, 3),
        (27, 1, 2),
        (31, 1, 3),
        (34, 1, 3),
        (38, 1, 2),
        (41, 1, 3),
        (45, 1, 3),
        (21, 4, 3),
        (24, 4, 2),
        (26, 4, 1),
        (29, 4, 2),
        (31, 4, 3),
        (34, 4, 2),
        (36, 4, 2),
        (40, 4, 3),
        (43, 4, 2),
        (46, 4, 3),
    ];
    blocks.extend((20..45).step_by(3).map(|x| (x, 7, 2)));
    for (k, &(x, y, side)) in blocks.iter().enumerate() {
        let rows = vec!["1".repeat(side); side].join("/");
        let grid = crate::kinds::evogym::MaterialGrid::from_rows(&rows).expect("a rigid block");
        world
            .add(worlds::WorldObject::new(&format!("block_{k}"), (x, y), grid))
            .expect("the blocks do not overlap");
    }
    world
}

/// A world of one-row fixed platforms, each `(name, origin, length)`.
fn platforms(list: &[(&str, (usize, usize), usize)]) -> worlds::World {
    let mut world = worlds::World::new();
    for &(name, origin, length) in list {
        let grid = crate::kinds::evogym::MaterialGrid::from_rows(&"5".repeat(length)).expect("a row of fixed cells");
        world
            .add(worlds::WorldObject::new(name, origin, grid))
            .expect("platforms apart");
    }
    world
}
