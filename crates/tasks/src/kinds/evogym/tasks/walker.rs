//! Walker-v0 (`walk.py:15-84`, class `WalkingFlat`): walk right on flat ground.

use super::{Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{forward, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds::{self, World};

/// Walker-v0.
pub struct Walker;

impl TaskDefinition for Walker {
    fn name(&self) -> &'static str {
        "Walker-v0"
    }

    fn short_name(&self) -> &'static str {
        "walker"
    }

    fn world(&self) -> World {
        worlds::walker_v0()
    }

    /// `walk.py:27`.
    fn robot_origin(&self) -> (usize, usize) {
        (1, 1)
    }

    /// `envs/__init__.py:19`.
    fn episode_steps(&self) -> usize {
        500
    }

    /// Centre velocity and relative positions (`walk.py:51-54`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotVelocity, Piece::RobotPositions]
    }

    /// The centre's x gain; the goal beyond 99 cells (`walk.py:57-69`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        forward(before.robot.0, after.robot.0, 99.0 * 0.1, unstable)
    }
}
