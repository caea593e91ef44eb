//! Balancer-v0 (`balance.py:15`, class `Balance`) and Balancer-v1 (`balance.py:97`, class
//! `BalanceJump`): get the robot's centre to a point over a thin pole and stay there; in v0 the
//! robot starts on the pole, in v1 beside it.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{approach, Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;

/// A balancing task: its world, start and the target point (cells).
pub struct Balancer {
    basics: Basics,
    /// The target's x and y in cells, as EvoGym writes them (times 0.1 in the reward).
    target: (f64, f64),
}

/// Balancer-v0: the robot starts on the pole (column 17, two cells high).
pub const BALANCER_V0: Balancer = Balancer {
    basics: Basics {
        name: "Balancer-v0",
        short_name: "balancer",
        world: balancer_v0,
        robot_origin: (15, 3),
        episode_steps: 600,
    },
    target: (17.0, 5.0),
};

/// Balancer-v1: the robot starts on the floor beside a pole three cells high.
pub const BALANCER_V1: Balancer = Balancer {
    basics: Basics {
        name: "Balancer-v1",
        short_name: "balancer-v1",
        world: balancer_v1,
        robot_origin: (10, 1),
        episode_steps: 600,
    },
    target: (17.5, 6.0),
};

impl TaskDefinition for Balancer {
    /// (`envs/__init__.py`: 600 steps for both.)
    fn basics(&self) -> &Basics {
        &self.basics
    }

    /// The robot's orientation and relative positions, no velocity (`balance.py:50-54`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotOrientation, Piece::RobotPositions]
    }

    /// The centre's approach to the target along x, plus along y; no goal (`balance.py:33-39`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let (tx, ty) = (self.target.0 * 0.1, self.target.1 * 0.1);
        let mut value = approach(tx, before.robot.0, after.robot.0);
        value += approach(ty, before.robot.1, after.robot.1);
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        Reward { value, ends: false }
    }
}

/// Balancer-v0's world (`Balancer-v0.json`, 30 × 5): `ground`, a floor, walls at the ends and a
/// pole two cells high in column 17.
fn balancer_v0() -> worlds::World {
    worlds::laid_out("ground", &[(0, 0, "0-29"), (1, 2, "0, 17, 29"), (3, 4, "0, 29")])
}

/// Balancer-v1's world (`Balancer-v1.json`): as Balancer-v0's, the pole three cells high.
fn balancer_v1() -> worlds::World {
    worlds::laid_out("ground", &[(0, 0, "0-29"), (1, 3, "0, 17, 29"), (4, 4, "0, 29")])
}
