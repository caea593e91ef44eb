//! BeamToppler-v0 (`manipulate.py:609-726`, class `ToppleBeam`): push a beam off two pegs.

use super::{Basics, Piece, TaskDefinition, OBJECT_THEN_ROBOT};
use crate::kinds::evogym::rewards::{topple, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds;

/// BeamToppler-v0.
pub struct BeamToppler;

/// BeamToppler-v0's names, world, start and length (`manipulate.py:621`; `envs/__init__.py:31`).
const BASICS: Basics = Basics {
    name: "BeamToppler-v0",
    short_name: "beam-toppler",
    world: worlds::beam_toppler_v0,
    robot_origin: (1, 1),
    episode_steps: 1000,
};

impl TaskDefinition for BeamToppler {
    fn basics(&self) -> &Basics {
        &BASICS
    }

    fn object(&self) -> Option<&'static str> {
        Some("beam")
    }

    /// The beam's centre minus the robot's, both centre velocities, the beam's orientation,
    /// then the robot's relative positions (`manipulate.py:636-645`).
    fn observation(&self) -> &'static [Piece] {
        OBJECT_THEN_ROBOT
    }

    /// Approach, the beam's displacement and drop; the goal when the beam's centre is below
    /// x = 2 cells (`manipulate.py:647-704`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        topple(before, after, unstable)
    }
}
