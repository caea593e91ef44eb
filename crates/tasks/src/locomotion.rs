//! The locomotion task (vsr-model.md §5.1): walk as far right as possible in a given time.
//!
//! Metrics: `distance` (x displacement over the evaluated window, which starts after `transient`
//! seconds, of the body's [`Body::outcome_center`](vsrlab_body::Body::outcome_center): a voxel
//! robot's mean voxel-polygon centre, as 2D-VSR-Sim's `Outcome` measures it), `velocity`
//! (distance ÷ the window's duration), `elapsed` (the window's duration) and `voxels` (actuated units of the body). Fitness: `velocity` unless
//! `fitness` says otherwise.

use crate::damage::Damage;
use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::task::{check_episode, task_field, Flow, Metrics, Objective, RigidTask, Scene, StepView, Task, TaskEpisode};
use crate::terrain::{add_ground, height_at, Terrain};
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics::{Vec2, WorldBuilder, WorldSettings};

/// The metrics of a locomotion episode.
pub const METRICS: &[&str] = &["distance", "velocity", "elapsed", "voxels"];

/// Locomotion task settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Locomotion {
    /// The ground.
    pub terrain: Terrain,
    /// Episode length (simulated seconds).
    pub duration: f64,
    /// Initial period (s) excluded from distance and velocity.
    pub transient: f64,
    /// x of the robot's left edge at the start (the original's x₁ + 1 = 11).
    pub initial_x: f64,
    /// Gap between the lowest voxel and the ground below it at the start.
    pub initial_gap: f64,
    /// Which metrics are the fitness values (default `velocity`).
    pub fitness: Fitness,
    /// Physics engine settings.
    pub physics: WorldSettings,
    /// Voxels that break during the episode (thesis §5.3: `{ at = 30.0, probability = 0.5 }`);
    /// absent = none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damage: Option<Damage>,
}

impl Default for Locomotion {
    fn default() -> Self {
        Locomotion {
            terrain: Terrain::Flat,
            duration: 30.0,
            transient: 0.0,
            initial_x: 11.0,
            initial_gap: 1.0,
            fitness: Fitness::maximize("velocity"),
            physics: WorldSettings::default(),
            damage: None,
        }
    }
}

impl Task for Locomotion {
    fn kind(&self) -> &'static str {
        "locomotion"
    }

    fn validate(&self) -> Result<(), EpisodeError> {
        check_episode(self.duration, &self.fitness.0, METRICS, &self.physics)?;
        if !(self.transient.is_finite() && self.transient >= 0.0 && self.transient < self.duration) {
            return Err(task_field(FieldError::sentence(
                "transient",
                format!(
                    "must be ≥ 0 and shorter than the duration ({}), got {}",
                    self.duration, self.transient
                ),
            )));
        }
        if !(self.initial_x.is_finite() && self.initial_gap.is_finite() && self.initial_gap >= 0.0) {
            return Err(task_field(FieldError::sentence(
                "initial_x",
                "and task.initial_gap must be finite (gap ≥ 0)",
            )));
        }
        self.damage.as_ref().map_or(Ok(()), Damage::validate)
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

    fn damage(&self) -> Option<&Damage> {
        self.damage.as_ref()
    }

    fn rigid(&self) -> Option<&dyn RigidTask> {
        Some(self)
    }
}

impl RigidTask for Locomotion {
    fn physics(&self) -> &WorldSettings {
        &self.physics
    }

    fn build_world(&self, builder: &mut WorldBuilder, seed: u64) -> Scene {
        let terrain = self.terrain.profile(seed);
        add_ground(builder, &terrain);
        Scene::ground(terrain)
    }

    fn place(&self, scene: &Scene, footprint: &[Vec2]) -> Vec2 {
        place_on_ground(&scene.terrain, footprint, self.initial_x, self.initial_gap)
    }

    fn start(&self) -> Box<dyn TaskEpisode> {
        Box::new(LocomotionEpisode {
            transient: self.transient,
            ..Default::default()
        })
    }
}

/// The origin that puts the body's left edge at `x0` and its lowest footprint point `gap` above
/// the ground beneath it (vsr-model.md §2.4).
pub fn place_on_ground(terrain: &[Vec2], footprint: &[Vec2], x0: f64, gap: f64) -> Vec2 {
    let y0 = footprint
        .iter()
        .map(|p| height_at(terrain, x0 + p.x).unwrap_or(0.0) - p.y)
        .fold(f64::NEG_INFINITY, f64::max)
        + gap;
    Vec2::new(x0, y0)
}

/// First and last observation of the evaluated window.
#[derive(Debug, Default)]
struct LocomotionEpisode {
    transient: f64,
    voxels: usize,
    started: bool,
    first_t: f64,
    first_x: f64,
    last_t: f64,
    last_x: f64,
}

impl TaskEpisode for LocomotionEpisode {
    fn observe(&mut self, step: &StepView) -> Flow {
        if self.voxels == 0 {
            // the body's size does not change: read it once, not at every step
            self.voxels = step.body.actuator_count();
        }
        if step.t >= self.transient {
            let x = step.body.outcome_center(step.world).x;
            if !self.started {
                self.started = true;
                self.first_t = step.t;
                self.first_x = x;
            }
            self.last_t = step.t;
            self.last_x = x;
        }
        Flow::Continue
    }

    fn metrics(&self) -> Metrics {
        let elapsed = self.last_t - self.first_t;
        let distance = self.last_x - self.first_x;
        let velocity = if elapsed > 0.0 { distance / elapsed } else { 0.0 };
        [
            ("distance", distance),
            ("velocity", velocity),
            ("elapsed", elapsed),
            ("voxels", self.voxels as f64),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }
}
