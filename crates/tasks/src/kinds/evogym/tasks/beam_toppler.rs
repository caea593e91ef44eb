//! BeamToppler-v0 (`manipulate.py:609-726`, class `ToppleBeam`): push a beam off two pegs.

use super::{Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{topple, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds::{self, World};

/// BeamToppler-v0.
pub struct BeamToppler;

impl TaskDefinition for BeamToppler {
    fn name(&self) -> &'static str {
        "BeamToppler-v0"
    }

    fn short_name(&self) -> &'static str {
        "beam-toppler"
    }

    fn world(&self) -> World {
        worlds::beam_toppler_v0()
    }

    /// `manipulate.py:621`.
    fn robot_origin(&self) -> (usize, usize) {
        (1, 1)
    }

    /// `envs/__init__.py:31`.
    fn episode_steps(&self) -> usize {
        1000
    }

    fn object(&self) -> Option<&'static str> {
        Some("beam")
    }

    /// The beam's centre minus the robot's, both centre velocities, the beam's orientation,
    /// then the robot's relative positions (`manipulate.py:636-645`).
    fn observation(&self) -> &'static [Piece] {
        &[
            Piece::ObjectOffset,
            Piece::RobotVelocity,
            Piece::ObjectVelocity,
            Piece::ObjectOrientation,
            Piece::RobotPositions,
        ]
    }

    /// Approach, the beam's displacement and drop; the goal when the beam's centre is below
    /// x = 2 cells (`manipulate.py:647-704`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        topple(before, after, unstable)
    }
}
