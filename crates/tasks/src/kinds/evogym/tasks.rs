//! The EvoGym tasks this module implements: their worlds, where the robot starts, how long an
//! episode lasts, what ends it and what is observed. Sources (commit `f63c649`):
//! `evogym/envs/__init__.py` (names, episode lengths), `evogym/envs/walk.py` (Walker-v0 is
//! `WalkingFlat`, BridgeWalker-v0 `SoftBridge`, CaveCrawler-v0 `Duck`) and
//! `evogym/envs/manipulate.py` (BeamToppler-v0 is `ToppleBeam`). `docs/evogym-envs.md` has the
//! details and where the thesis differs.

use super::worlds::{self, World};

/// Cells seen to each side by CaveCrawler's floor and ceiling observations, and how far
/// (`walk.py:179`, default `sight_range = 5` at `base.py:281`).
pub const CAVE_SIGHT: (usize, f64) = (5, 5.0);

/// One of EvoGym's tasks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EvoGymTask {
    /// Walker-v0: walk right on flat ground.
    Walker,
    /// BridgeWalker-v0: walk right on a soft bridge.
    BridgeWalker,
    /// BeamToppler-v0: push a beam off two pegs.
    BeamToppler,
    /// CaveCrawler-v0: crawl right through a low cave.
    CaveCrawler,
}

impl EvoGymTask {
    /// Every task.
    pub const ALL: [EvoGymTask; 4] = [
        EvoGymTask::Walker,
        EvoGymTask::BridgeWalker,
        EvoGymTask::BeamToppler,
        EvoGymTask::CaveCrawler,
    ];

    /// EvoGym's name (`Walker-v0`, …).
    pub fn name(self) -> &'static str {
        match self {
            EvoGymTask::Walker => "Walker-v0",
            EvoGymTask::BridgeWalker => "BridgeWalker-v0",
            EvoGymTask::BeamToppler => "BeamToppler-v0",
            EvoGymTask::CaveCrawler => "CaveCrawler-v0",
        }
    }

    /// Its short name on vsrlab's command line (`walker`, `bridge-walker`, …).
    pub fn short_name(self) -> &'static str {
        match self {
            EvoGymTask::Walker => "walker",
            EvoGymTask::BridgeWalker => "bridge-walker",
            EvoGymTask::BeamToppler => "beam-toppler",
            EvoGymTask::CaveCrawler => "cave-crawler",
        }
    }

    /// The task named `name`: EvoGym's name in any case (`BridgeWalker-v0`, `bridgewalker-v0`)
    /// or the short name with or without the version (`bridge-walker`, `bridge-walker-v0`).
    pub fn from_name(name: &str) -> Option<EvoGymTask> {
        let short = name.strip_suffix("-v0").unwrap_or(name);
        EvoGymTask::ALL
            .into_iter()
            .find(|t| t.name().eq_ignore_ascii_case(name) || t.short_name().eq_ignore_ascii_case(short))
    }

    /// Its world, without the robot.
    pub fn world(self) -> World {
        match self {
            EvoGymTask::Walker => worlds::walker_v0(),
            EvoGymTask::BridgeWalker => worlds::bridge_walker_v0(),
            EvoGymTask::BeamToppler => worlds::beam_toppler_v0(),
            EvoGymTask::CaveCrawler => worlds::cave_crawler_v0(),
        }
    }

    /// Cell of the robot's bottom-left corner (`walk.py:27`, `:98`, `:171`, `manipulate.py:621`).
    pub fn robot_origin(self) -> (usize, usize) {
        match self {
            EvoGymTask::Walker | EvoGymTask::BeamToppler => (1, 1),
            EvoGymTask::BridgeWalker => (2, 5),
            EvoGymTask::CaveCrawler => (1, 2),
        }
    }

    /// Steps per episode (`max_episode_steps`, `evogym/envs/__init__.py:19`, `:25`, `:31`,
    /// `:140`).
    pub fn episode_steps(self) -> usize {
        match self {
            EvoGymTask::Walker | EvoGymTask::BridgeWalker => 500,
            EvoGymTask::BeamToppler | EvoGymTask::CaveCrawler => 1000,
        }
    }

    /// For the walking tasks, the x the robot's centre must pass for the goal (`walk.py:67`:
    /// 99 cells, `:139`: 60, `:214`: 69); `None` for BeamToppler (its goal is on the beam).
    pub fn goal_x(self) -> Option<f64> {
        match self {
            EvoGymTask::Walker => Some(99.0 * 0.1),
            EvoGymTask::BridgeWalker => Some(60.0 * 0.1),
            EvoGymTask::CaveCrawler => Some(69.0 * 0.1),
            EvoGymTask::BeamToppler => None,
        }
    }

    /// Observation length for a robot of `robot_points` points: `2 n` relative positions plus
    /// 2 (Walker: centre velocity), 3 (BridgeWalker: + orientation), 7 (BeamToppler: beam − robot
    /// centre, both centre velocities, beam orientation) or 2 + 2 × 11 (CaveCrawler: + floor and
    /// ceiling distances).
    pub fn observation_size(self, robot_points: usize) -> usize {
        let extra = match self {
            EvoGymTask::Walker => 2,
            EvoGymTask::BridgeWalker => 3,
            EvoGymTask::BeamToppler => 7,
            EvoGymTask::CaveCrawler => 2 + 2 * (2 * CAVE_SIGHT.0 + 1),
        };
        extra + 2 * robot_points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for t in EvoGymTask::ALL {
            assert_eq!(EvoGymTask::from_name(t.name()), Some(t));
        }
        assert_eq!(EvoGymTask::from_name("Walker-v1"), None);
    }

    /// A full 5 × 5 robot has 36 points: 2 + 72 = 74, 75, 79 and 2 + 72 + 22 = 96.
    #[test]
    fn observation_sizes_for_36_points() {
        let sizes = EvoGymTask::ALL.map(|t| t.observation_size(36));
        assert_eq!(sizes, [74, 75, 79, 96]);
    }
}
