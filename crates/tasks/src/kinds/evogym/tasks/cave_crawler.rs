//! CaveCrawler-v0 (`walk.py:159-233`, class `Duck`): crawl right through a low cave.

use super::{Basics, Piece, TaskDefinition, CAVE_SIGHT};
use crate::kinds::evogym::rewards::{forward, Reward, RobotAndBeam};
use crate::kinds::evogym::worlds;

/// CaveCrawler-v0.
pub struct CaveCrawler;

/// CaveCrawler-v0's names, world, start and length (`walk.py:171`; `envs/__init__.py:140`).
const BASICS: Basics = Basics {
    name: "CaveCrawler-v0",
    short_name: "cave-crawler",
    world: worlds::cave_crawler_v0,
    robot_origin: (1, 2),
    episode_steps: 1000,
};

impl TaskDefinition for CaveCrawler {
    fn basics(&self) -> &Basics {
        &BASICS
    }

    /// Centre velocity, relative positions, floor and ceiling distances with a sight of 5
    /// (`walk.py:179`, `:196-201`), the centre placed as vsrlab first did (it differs from
    /// EvoGym in bins whose points lie on a border, at reset; docs/evogym-envs.md).
    fn observation(&self) -> &'static [Piece] {
        &[
            Piece::RobotVelocity,
            Piece::RobotPositions,
            Piece::FloorMeanFirst(CAVE_SIGHT.0),
            Piece::CeilingMeanFirst(CAVE_SIGHT.0),
        ]
    }

    /// The centre's x gain; the goal beyond 69 cells (`walk.py:203-216`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        forward(before.robot.0, after.robot.0, 69.0 * 0.1, unstable)
    }
}
