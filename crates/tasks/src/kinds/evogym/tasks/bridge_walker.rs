//! BridgeWalker-v0 (`walk.py:86-157`, class `SoftBridge`): walk right on a soft bridge.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{forward, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds;

/// BridgeWalker-v0.
pub struct BridgeWalker;

/// BridgeWalker-v0's names, world, start and length (`walk.py:98`; `envs/__init__.py:25`).
const BASICS: Basics = Basics {
    name: "BridgeWalker-v0",
    short_name: "bridge-walker",
    world: worlds::bridge_walker_v0,
    robot_origin: (2, 5),
    episode_steps: 500,
};

impl TaskDefinition for BridgeWalker {
    fn basics(&self) -> &Basics {
        &BASICS
    }

    /// Centre velocity, the robot's orientation, relative positions (`walk.py:121-126`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotVelocity, Piece::RobotOrientation, Piece::RobotPositions]
    }

    /// The centre's x gain; the goal beyond 60 cells (`walk.py:128-141`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        forward(before.robot.0, after.robot.0, 60.0 * 0.1, unstable)
    }
}
