//! BridgeWalker-v0 (`walk.py:86-157`, class `SoftBridge`): walk right on a soft bridge.

use super::{Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{forward, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds::{self, World};

/// BridgeWalker-v0.
pub struct BridgeWalker;

impl TaskDefinition for BridgeWalker {
    fn name(&self) -> &'static str {
        "BridgeWalker-v0"
    }

    fn short_name(&self) -> &'static str {
        "bridge-walker"
    }

    fn world(&self) -> World {
        worlds::bridge_walker_v0()
    }

    /// `walk.py:98`.
    fn robot_origin(&self) -> (usize, usize) {
        (2, 5)
    }

    /// `envs/__init__.py:25`.
    fn episode_steps(&self) -> usize {
        500
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
