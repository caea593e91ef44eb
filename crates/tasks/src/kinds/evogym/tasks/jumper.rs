//! Jumper-v0 (`jump.py:15`, class `StationaryJump`): jump as high as possible without moving
//! sideways, between two walls.

use super::{Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds::{self, World};

/// Jumper-v0.
pub struct Jumper;

impl TaskDefinition for Jumper {
    fn name(&self) -> &'static str {
        "Jumper-v0"
    }

    fn short_name(&self) -> &'static str {
        "jumper"
    }

    fn world(&self) -> World {
        worlds::jumper_v0()
    }

    /// On the floor, mid-way between the walls (`jump.py:27`).
    fn robot_origin(&self) -> (usize, usize) {
        (32, 1)
    }

    fn episode_steps(&self) -> usize {
        500
    }

    /// Centre velocity, relative positions, the floor with a sight of 2 (`jump.py:35`, `:53-57`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotVelocity, Piece::RobotPositions, Piece::Floor(2)]
    }

    /// 10 × the centre's rise minus 5 × its sideways move; no goal (`jump.py:60-62`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = (after.robot.1 - before.robot.1) * 10.0 - (after.robot.0 - before.robot.0).abs() * 5.0;
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        Reward { value, ends: false }
    }
}
