//! Jumper-v0 (`jump.py:15`, class `StationaryJump`): jump as high as possible without moving
//! sideways, between two walls.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;

/// Jumper-v0.
pub struct Jumper;

/// Jumper-v0's names, world, start and length (On the floor, mid-way between the walls (`jump.py:27`).).
const BASICS: Basics = Basics {
    name: "Jumper-v0",
    short_name: "jumper",
    world: jumper_v0,
    robot_origin: (32, 1),
    episode_steps: 500,
};

impl TaskDefinition for Jumper {
    fn basics(&self) -> &Basics {
        &BASICS
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

/// Jumper-v0's world (`Jumper-v0.json`, 60 × 8): `ground`, a floor with a wall at each end.
fn jumper_v0() -> worlds::World {
    worlds::laid_out("ground", &[(0, 0, "0-59"), (1, 7, "0, 59")])
}
