//! The manipulation tasks of `manipulate.py` on class `PackageBase` with a free object:
//! Carrier-v0 (`CarrySmallRect`), Carrier-v1 (`CarrySmallRectToTable`), Pusher-v0
//! (`PushSmallRect`), Pusher-v1 (`PushSmallRectOnOppositeSide`), Thrower-v0 (`ThrowSmallRect`),
//! Lifter-v0 (`LiftSmallRect`) and BeamSlider-v0 (`SlideBeam`). Each is a table of constants
//! and a reward formula on the centres of the robot (`c`) and the object (`p`) before (`⁻`) and
//! after (`⁺`) a step. (BeamToppler-v0 and Catcher-v0, whose world is drawn at every reset, have
//! their own modules.)

use super::{Basics, Piece, TaskDefinition, OBJECT_THEN_ROBOT};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, GOAL_BONUS, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;

/// A manipulation task.
pub struct PackageTask {
    basics: Basics,
    /// The free object's name: `package` or `beam`.
    object: &'static str,
    observation: &'static [Piece],
    /// The reward before the instability penalty and the goal bonus.
    reward: fn(RobotAndBeam, RobotAndBeam) -> f64,
    /// The goal (+1, the end) from the centres after the step, if the task has one.
    goal: Option<fn(RobotAndBeam) -> bool>,
}

/// `PackageBase.get_obs` (`K6`: the robot's velocity, the package's centre minus the robot's,
/// the package's velocity), then the robot's relative positions.
const K6: &[Piece] = &[
    Piece::RobotVelocity,
    Piece::ObjectOffset,
    Piece::ObjectVelocity,
    Piece::RobotPositions,
];

/// Carrier-v0 (`manipulate.py:84`): carry a soft package, resting on the robot, to the right.
pub const CARRIER_V0: PackageTask = PackageTask {
    basics: Basics {
        name: "Carrier-v0",
        short_name: "carrier",
        world: carrier_v0,
        robot_origin: (1, 1),
        episode_steps: 500,
    },
    object: "package",
    observation: K6,
    reward: |b, a| carry(b, a, 3.0 * 0.1),
    goal: Some(|a| a.robot.0 > 99.0 * 0.1),
};

/// Carrier-v1 (`manipulate.py:168`): carry a rigid package from a shelf to a table. As EvoGym
/// writes it, the package's approach to the table is computed and then overwritten
/// (`manipulate.py:204-205`), so only the robot's approach to x = 4 counts.
pub const CARRIER_V1: PackageTask = PackageTask {
    basics: Basics {
        name: "Carrier-v1",
        short_name: "carrier-v1",
        world: carrier_v1,
        robot_origin: (1, 4),
        episode_steps: 1000,
    },
    object: "package",
    observation: K6,
    reward: |b, a| {
        let target = 40.0 * 0.1;
        let mut value = (target - b.robot.0).abs() - (target - a.robot.0).abs();
        let height = if a.beam.0 > 20.0 * 0.1 { 4.0 * 0.1 } else { 6.0 * 0.1 };
        if a.beam.1 < height {
            value += 10.0 * (a.beam.1 - b.beam.1);
        }
        value
    },
    goal: None,
};

/// Pusher-v0 (`manipulate.py:250`): push a soft package to the right.
pub const PUSHER_V0: PackageTask = PackageTask {
    basics: Basics {
        name: "Pusher-v0",
        short_name: "pusher",
        world: pusher_v0,
        robot_origin: (1, 1),
        episode_steps: 500,
    },
    object: "package",
    observation: K6,
    reward: |b, a| push(b, a, 0.0 * 0.1),
    goal: Some(|a| a.robot.0 > 99.0 * 0.1),
};

/// Pusher-v1 (`manipulate.py:316`): push a rigid package from its other side (the robot starts
/// to its right).
pub const PUSHER_V1: PackageTask = PackageTask {
    basics: Basics {
        name: "Pusher-v1",
        short_name: "pusher-v1",
        world: pusher_v1,
        robot_origin: (13, 1),
        episode_steps: 600,
    },
    object: "package",
    observation: K6,
    reward: |b, a| push(b, a, 0.0 * 0.1),
    goal: Some(|a| a.robot.0 > 69.0 * 0.1),
};

/// Thrower-v0 (`manipulate.py:382`): throw a soft package to the right without following it.
pub const THROWER: PackageTask = PackageTask {
    basics: Basics {
        name: "Thrower-v0",
        short_name: "thrower",
        world: thrower_v0,
        robot_origin: (1, 1),
        episode_steps: 300,
    },
    object: "package",
    observation: K6,
    reward: |b, a| {
        let mut motion = (b.robot.0 - a.robot.0) * 0.25;
        if a.robot.0 < 0.0 {
            motion *= -1.0;
        }
        a.beam.0 - b.beam.0 + motion
    },
    goal: None,
};

/// Lifter-v0 (`manipulate.py:843`): lift a small rigid package out of a pit.
pub const LIFTER: PackageTask = PackageTask {
    basics: Basics {
        name: "Lifter-v0",
        short_name: "lifter",
        world: lifter_v0,
        robot_origin: (2, 3),
        episode_steps: 300,
    },
    object: "package",
    observation: &[
        Piece::RobotVelocity,
        Piece::ObjectOffset,
        Piece::ObjectVelocity,
        Piece::ObjectOrientation,
        Piece::RobotPositions,
    ],
    reward: |b, a| {
        let mut value = (a.beam.1 - b.beam.1) * 10.0;
        let goal = 5.5 * 0.1;
        value += ((goal - b.beam.0).abs() - (goal - a.beam.0).abs()) * 10.0;
        if a.robot.1 < 3.0 * 0.1 {
            value += 20.0 * (a.robot.1 - b.robot.1);
        }
        value
    },
    goal: None,
};

/// BeamSlider-v0 (`manipulate.py:728`): slide a beam along five pegs.
pub const BEAM_SLIDER: PackageTask = PackageTask {
    basics: Basics {
        name: "BeamSlider-v0",
        short_name: "beam-slider",
        world: beam_slider_v0,
        robot_origin: (1, 1),
        episode_steps: 1000,
    },
    object: "beam",
    observation: OBJECT_THEN_ROBOT,
    reward: |b, a| {
        let mut value = (b.beam.0 - b.robot.0).abs() - (a.beam.0 - a.robot.0).abs();
        value += (a.beam.0 - b.beam.0) * 1.0;
        value
    },
    goal: Some(|a| a.beam.0 < 2.0 * 0.1),
};

/// `get_reward_carry` (`manipulate.py:111-127`): half the package's and half the robot's x
/// gain, and 10 × the package's rise while it is below `height`.
fn carry(b: RobotAndBeam, a: RobotAndBeam, height: f64) -> f64 {
    let mut value = (a.beam.0 - b.beam.0) * 0.5;
    value += (a.robot.0 - b.robot.0) * 0.5;
    if a.beam.1 < height {
        value += 10.0 * (a.beam.1 - b.beam.1);
    }
    value
}

/// `PackageBase.get_reward` (`manipulate.py:44-63`): 0.75 × the package's x gain, 0.5 × the
/// robot's, the robot's approach to the package along x, and 10 × the package's rise while it
/// is below `height`.
fn push(b: RobotAndBeam, a: RobotAndBeam, height: f64) -> f64 {
    let mut value = (a.beam.0 - b.beam.0) * 0.75;
    value += (a.robot.0 - b.robot.0) * 0.5;
    value += (b.robot.0 - b.beam.0).abs() - (a.robot.0 - a.beam.0).abs();
    if a.beam.1 < height {
        value += 10.0 * (a.beam.1 - b.beam.1);
    }
    value
}

impl TaskDefinition for PackageTask {
    fn basics(&self) -> &Basics {
        &self.basics
    }

    fn object(&self) -> Option<&'static str> {
        Some(self.object)
    }

    fn observation(&self) -> &'static [Piece] {
        self.observation
    }

    /// The task's formula, −3 if unstable, then +1 and the end at the goal.
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = (self.reward)(before, after);
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        let ends = self.goal.is_some_and(|goal| goal(after));
        if ends {
            value += GOAL_BONUS;
        }
        Reward { value, ends }
    }
}

/// Carrier-v0's world (`Carrier-v0.json`, 100 × 8): `ground`, a row of 100 fixed cells, and
/// `package`, 3 × 2 soft cells at (3, 6), on top of the robot.
fn carrier_v0() -> worlds::World {
    worlds::laid_out_objects(&[("ground", &[(0, 0, "0-99")]), ("package", &[(6, 7, "3-5[2]")])])
}

/// Carrier-v1's world (`Carrier-v1.json`, 60 × 12): `ground`, a shelf, a step, a lower floor and
/// a table post, and `package`, 3 × 2 rigid cells at (3, 10), above the robot.
fn carrier_v1() -> worlds::World {
    worlds::laid_out_objects(&[
        (
            "ground",
            &[
                (1, 1, "26-59"),
                (2, 2, "23-26, 48-49"),
                (3, 3, "0-23, 48-49"),
                (4, 4, "48-49"),
            ],
        ),
        ("package", &[(10, 11, "3-5[1]")]),
    ])
}

/// Pusher-v0's world (`Pusher-v0.json`, 100 × 3): `ground`, a row of 100 fixed cells, and
/// `package`, 3 × 2 soft cells at (8, 1).
fn pusher_v0() -> worlds::World {
    worlds::laid_out_objects(&[("ground", &[(0, 0, "0-99")]), ("package", &[(1, 2, "8-10[2]")])])
}

/// Pusher-v1's world (`Pusher-v1.json`): as Pusher-v0's, the package rigid.
fn pusher_v1() -> worlds::World {
    worlds::laid_out_objects(&[("ground", &[(0, 0, "0-99")]), ("package", &[(1, 2, "8-10[1]")])])
}

/// Thrower-v0's world (`Thrower-v0.json`, 70 × 10): `ground`, a floor with posts of rising
/// heights and an end wall, and `package`, 3 × 2 soft cells at (3, 7), above the robot.
fn thrower_v0() -> worlds::World {
    worlds::laid_out_objects(&[
        (
            "ground",
            &[
                (0, 0, "0-69"),
                (1, 2, "10, 14, 18, 23, 28, 39, 69"),
                (3, 3, "14, 18, 23, 28, 39, 69"),
                (4, 4, "18, 23, 28, 39, 69"),
                (5, 6, "23, 28, 39, 69"),
                (7, 7, "28, 39, 69"),
                (8, 9, "39, 69"),
            ],
        ),
        ("package", &[(7, 8, "3-5[2]")]),
    ])
}

/// Lifter-v0's world (`Lifter-v0.json`, 11 × 5): `ground`, a pit between two ledges, and
/// `package`, 1 × 2 rigid cells standing in the pit at (5, 1).
fn lifter_v0() -> worlds::World {
    worlds::laid_out_objects(&[
        (
            "ground",
            &[(0, 0, "3-7"), (1, 1, "3, 7"), (2, 2, "0-3, 7-10"), (3, 4, "0, 10")],
        ),
        ("package", &[(1, 2, "5[1]")]),
    ])
}

/// BeamSlider-v0's world (`BeamSlider-v0.json`, 70 × 7): `ground`, five fixed pegs in row 4 and
/// `beam`, 10 × 2 rigid cells at (22, 5) on the first peg.
fn beam_slider_v0() -> worlds::World {
    worlds::laid_out_objects(&[
        ("beam", &[(5, 6, "22-31[1]")]),
        ("ground", &[(0, 0, "0-69")]),
        ("peg1", &[(4, 4, "20-24")]),
        ("peg2", &[(4, 4, "29-31")]),
        ("peg3", &[(4, 4, "35-37")]),
        ("peg4", &[(4, 4, "41-43")]),
        ("peg5", &[(4, 4, "49-51")]),
    ])
}
