//! Flipper-v0 (`flip.py:16`, class `Flipping`): roll over and over, counter-clockwise (to the
//! left), on flat ground.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;
use std::f64::consts::PI;

/// Flipper-v0.
pub struct Flipper;

/// Flipper-v0's names, world, start and length (Near the right end of the ground, rolling left.).
const BASICS: Basics = Basics {
    name: "Flipper-v0",
    short_name: "flipper",
    world: flipper_v0,
    robot_origin: (60, 1),
    episode_steps: 600,
};

impl TaskDefinition for Flipper {
    fn basics(&self) -> &Basics {
        &BASICS
    }

    /// The robot's orientation and relative positions (`flip.py:47-50`).
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotOrientation, Piece::RobotPositions]
    }

    /// The gain of the unwrapped orientation: `memory[0]` counts whole turns (−1 when the angle
    /// wraps from below π/3 to above 5π/3, +1 the other way); the episode ends, without a bonus,
    /// once the centre's x is below one cell (`flip.py:52-71`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, memory: &mut [f64]) -> Reward {
        let (old, new, turns) = (before.robot_angle, after.robot_angle, &mut memory[0]);
        let unwrapped_before = *turns * 2.0 * PI + old;
        if old < PI / 3.0 && new > 5.0 * PI / 3.0 {
            *turns -= 1.0;
        }
        if old > 5.0 * PI / 3.0 && new < PI / 3.0 {
            *turns += 1.0;
        }
        let unwrapped_after = *turns * 2.0 * PI + new;
        let mut value = unwrapped_after - unwrapped_before;
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        Reward {
            value,
            ends: after.robot.0 < 1.0 * 0.1,
        }
    }
}

/// Flipper-v0's world (`Flipper-v0.json`): `new_object_1`, a row of 70 fixed cells at (0, 0).
fn flipper_v0() -> worlds::World {
    worlds::laid_out("new_object_1", &[(0, 0, "0-69")])
}
