//! The manipulation tasks of `manipulate.py` on class `PackageBase` with a free object:
//! Carrier-v0 (`CarrySmallRect`), Carrier-v1 (`CarrySmallRectToTable`), Pusher-v0
//! (`PushSmallRect`), Pusher-v1 (`PushSmallRectOnOppositeSide`), Thrower-v0 (`ThrowSmallRect`),
//! Lifter-v0 (`LiftSmallRect`) and BeamSlider-v0 (`SlideBeam`). Each is a table of constants
//! and a reward formula on the centres of the robot (`c`) and the object (`p`) before (`⁻`) and
//! after (`⁺`) a step. (BeamToppler-v0 has its own module; Catcher-v0, whose start is random, is
//! not implemented yet.)

use super::{Basics, Piece, TaskDefinition};
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
        world: worlds::carrier_v0,
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
        world: worlds::carrier_v1,
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
        world: worlds::pusher_v0,
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
        world: worlds::pusher_v1,
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
        world: worlds::thrower_v0,
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
        world: worlds::lifter_v0,
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
        world: worlds::beam_slider_v0,
        robot_origin: (1, 1),
        episode_steps: 1000,
    },
    object: "beam",
    observation: &[
        Piece::ObjectOffset,
        Piece::RobotVelocity,
        Piece::ObjectVelocity,
        Piece::ObjectOrientation,
        Piece::RobotPositions,
    ],
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
