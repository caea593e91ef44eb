//! The jump task: rise as high as possible on flat ground. A small second task that shows what a
//! task is (one module and one registry line); not a thesis experiment.
//!
//! Metrics: `height` (highest centre y over the episode minus the centre y after the first
//! step) and `final_height` (the same at the last step). Fitness: `height`.

use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::locomotion::place_on_ground;
use crate::task::{check_episode, Flow, Metrics, Objective, RigidTask, Scene, StepView, Task, TaskEpisode};
use crate::terrain::{add_ground, Terrain};
use serde::{Deserialize, Serialize};
use vsrlab_physics::{Vec2, WorldBuilder, WorldSettings};

/// x of the robot's left edge at the start: mid-terrain, far from the border walls (a robot
/// next to a wall could climb it and "jump" by walking).
pub const START_X: f64 = 1000.0;

/// The metrics of a jump episode.
pub const METRICS: &[&str] = &["height", "final_height"];

/// Jump task settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Jump {
    /// Episode length (simulated seconds).
    pub duration: f64,
    /// Which metrics are the fitness values (default `height`).
    pub fitness: Fitness,
    /// Physics engine settings.
    pub physics: WorldSettings,
}

impl Default for Jump {
    fn default() -> Self {
        Jump {
            duration: 10.0,
            fitness: Fitness::maximize("height"),
            physics: WorldSettings::default(),
        }
    }
}

impl Task for Jump {
    fn kind(&self) -> &'static str {
        "jump"
    }

    fn validate(&self) -> Result<(), EpisodeError> {
        check_episode(self.duration, &self.fitness.0, METRICS, &self.physics)
    }

    fn duration(&self) -> f64 {
        self.duration
    }

    fn metric_names(&self) -> &'static [&'static str] {
        METRICS
    }

    fn objectives(&self) -> &[Objective] {
        &self.fitness.0
    }

    fn rigid(&self) -> Option<&dyn RigidTask> {
        Some(self)
    }
}

impl RigidTask for Jump {
    fn physics(&self) -> &WorldSettings {
        &self.physics
    }

    fn build_world(&self, builder: &mut WorldBuilder, seed: u64) -> Scene {
        let terrain = Terrain::Flat.profile(seed);
        add_ground(builder, &terrain);
        Scene::ground(terrain)
    }

    fn place(&self, scene: &Scene, footprint: &[Vec2]) -> Vec2 {
        place_on_ground(&scene.terrain, footprint, START_X, 0.0)
    }

    fn start(&self) -> Box<dyn TaskEpisode> {
        Box::new(JumpEpisode::default())
    }
}

/// Start, highest and last centre height.
#[derive(Debug, Default)]
struct JumpEpisode {
    start: Option<f64>,
    highest: f64,
    last: f64,
}

impl TaskEpisode for JumpEpisode {
    fn observe(&mut self, step: &StepView) -> Flow {
        let y = step.center.y;
        let start = *self.start.get_or_insert(y);
        self.highest = self.highest.max(y - start);
        self.last = y - start;
        Flow::Continue
    }

    fn metrics(&self) -> Metrics {
        [("height", self.highest), ("final_height", self.last)]
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::episode;
    use crate::kinds::voxel::robot::RobotSpec;
    use crate::outcome::TraceLevel;
    use vsrlab_body::sensors::SensorConfig;
    use vsrlab_body::{Morphology, Preset};
    use vsrlab_brain::BrainSpec;

    fn robot(brain: &str) -> RobotSpec {
        RobotSpec {
            body: Morphology::parse("biped-4x3").unwrap(),
            preset: Preset::Y2021,
            voxel: None,
            sensors: SensorConfig::parse("uniform-a+vxy+t-0").unwrap(),
            brain: BrainSpec::parse(brain).unwrap(),
        }
    }

    #[test]
    fn height_is_the_highest_rise_of_the_centre() {
        let task = Jump {
            duration: 4.0,
            ..Jump::default()
        };
        let still = episode::run(&robot("constant:0"), &task, 0, TraceLevel::Center).unwrap();
        let trace = still.trace.as_ref().unwrap();
        let start = trace.centers[0].y;
        let highest = trace.centers.iter().map(|c| c.y - start).fold(0.0, f64::max);
        assert_eq!(still.metric("height"), highest);
        assert_eq!(still.fitness, vec![highest]);
        // a robot at rest does not rise; a pulsing one does
        assert!(highest < 0.05, "{highest}");
        let pulsing = episode::run(&robot("phase"), &task, 0, TraceLevel::None).unwrap();
        assert!(pulsing.metric("height") > highest, "{:?}", pulsing.metrics);
    }

    #[test]
    fn unknown_fitness_metrics_are_rejected_by_name() {
        let task = Jump {
            fitness: Fitness::maximize("distance"),
            ..Jump::default()
        };
        let err = task.validate().unwrap_err().to_string();
        assert!(
            err.contains("task.fitness[0]") && err.contains("height, final_height"),
            "{err}"
        );
    }
}
