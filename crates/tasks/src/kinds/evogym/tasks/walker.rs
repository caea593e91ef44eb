//! Walker-v0 (`walk.py:15-84`, class `WalkingFlat`): walk right on flat ground.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{forward, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds;

/// Walker-v0.
pub struct Walker;

/// Walker-v0's names, world, start and length (`walk.py:27`; `envs/__init__.py:19`).
const BASICS: Basics = Basics {
    name: "Walker-v0",
    short_name: "walker",
    world: worlds::walker_v0,
    robot_origin: (1, 1),
    episode_steps: 500,
};

impl TaskDefinition for Walker {
    fn basics(&self) -> &Basics {
        &BASICS
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
