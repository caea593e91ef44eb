//! The escape task (thesis §6.3.3.2, psa-model.md "Escape cage"): the robot starts inside a cage
//! open at the bottom of both sides and must get out, in either direction.
//!
//! The cage, for a side s: ground from x = −100 to 100 at y = 0; a roof 1 thick at y = s; two
//! walls 1 thick, inner faces at x = ±s/2, from the roof down to the aperture's top y = a
//! (default s/3). The robot starts with the middle of its footprint at x = 0 and its lowest point
//! `start_height` above the ground (default s/6 − 1/2: the original's centre at s/2 for a PSA of
//! radius s/3). The episode ends when every sensing unit's centre has |x| > s/2 + 1.
//!
//! Metrics: `distance` (|x| of the centre at the end; the original's fitness), `velocity`
//! (`distance` over the full duration, the thesis's v̄, even when the episode ended early),
//! `escaped` (1 when every unit got out), `escape_time` (when, or the duration).

use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::task::{check_episode, task_field, Flow, Metrics, Objective, RigidTask, Scene, StepView, Task, TaskEpisode};
use crate::terrain::add_ground;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics::{Polygon, Vec2, WorldBuilder, WorldSettings};

/// The metrics of an escape episode.
pub const METRICS: &[&str] = &["distance", "velocity", "escaped", "escape_time"];

/// Friction of the cage and its ground (Box2D's default).
const CAGE_FRICTION: f64 = 0.2;

/// Escape task settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Escape {
    /// Episode length (simulated seconds).
    pub duration: f64,
    /// Inner width of the cage and height of its roof (the original: 3r, 22.5 for a medium PSA).
    pub side: f64,
    /// Height of the opening at the bottom of each side; absent: side/3.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aperture: Option<f64>,
    /// Gap between the robot's lowest point and the ground at the start; absent: side/6 − 1/2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub start_height: Option<f64>,
    /// Which metrics are the fitness values (default `distance`).
    pub fitness: Fitness,
    /// Physics engine settings (default: PSA worlds, gravity −10).
    pub physics: WorldSettings,
}

impl Default for Escape {
    fn default() -> Self {
        Escape {
            duration: 30.0,
            side: 22.5,
            aperture: None,
            start_height: None,
            fitness: Fitness::maximize("distance"),
            physics: crate::kinds::psa::inflation::psa_physics(),
        }
    }
}

impl Escape {
    /// The aperture's height.
    pub fn aperture(&self) -> f64 {
        self.aperture.unwrap_or(self.side / 3.0)
    }
    /// The gap under the robot at the start.
    pub fn start_height(&self) -> f64 {
        self.start_height.unwrap_or(self.side / 6.0 - 0.5)
    }
    /// The cage's static boxes: roof, left wall, right wall.
    pub fn cage(&self) -> Vec<Polygon> {
        let (s, a) = (self.side, self.aperture());
        let half = s / 2.0;
        let rect = |x0: f64, y0: f64, x1: f64, y1: f64| {
            Polygon::rect(
                Vec2::new(0.5 * (x0 + x1), 0.5 * (y0 + y1)),
                0.5 * (x1 - x0),
                0.5 * (y1 - y0),
            )
        };
        vec![
            rect(-half - 1.0, s, half + 1.0, s + 1.0),
            rect(-half - 1.0, a, -half, s),
            rect(half, a, half + 1.0, s),
        ]
    }
}

impl Task for Escape {
    fn kind(&self) -> &'static str {
        "escape"
    }

    fn validate(&self) -> Result<(), EpisodeError> {
        check_episode(self.duration, &self.fitness.0, METRICS, &self.physics)?;
        let bad = |field: &str, message: String| Err(task_field(FieldError::sentence(field, message)));
        if !(self.side.is_finite() && self.side > 0.0 && self.side <= 1000.0) {
            return bad("side", format!("must be in (0, 1000], got {}", self.side));
        }
        let a = self.aperture();
        if !(a.is_finite() && a > 0.0 && a < self.side) {
            return bad("aperture", format!("must be in (0, side = {}), got {a}", self.side));
        }
        let h = self.start_height();
        if !(h.is_finite() && h >= 0.0) {
            return bad("start_height", format!("must be finite and ≥ 0, got {h}"));
        }
        Ok(())
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

impl RigidTask for Escape {
    fn physics(&self) -> &WorldSettings {
        &self.physics
    }

    fn build_world(&self, builder: &mut WorldBuilder, _seed: u64) -> Scene {
        let terrain = vec![Vec2::new(-100.0, 0.0), Vec2::new(100.0, 0.0)];
        add_ground(builder, &terrain);
        let cage = self.cage();
        for poly in &cage {
            builder.add_static_polygon(*poly, CAGE_FRICTION, 0.0);
        }
        Scene {
            terrain,
            obstacles: cage.iter().map(|p| p.verts().to_vec()).collect(),
            objects: Vec::new(),
        }
    }

    fn place(&self, _scene: &Scene, footprint: &[Vec2]) -> Vec2 {
        let (min_x, max_x) = footprint
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.x), hi.max(p.x))
            });
        let min_y = footprint.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        Vec2::new(-0.5 * (min_x + max_x), self.start_height() - min_y)
    }

    fn start(&self) -> Box<dyn TaskEpisode> {
        Box::new(EscapeEpisode {
            outside: self.side / 2.0 + 1.0,
            duration: self.duration,
            distance: 0.0,
            escaped_at: None,
        })
    }
}

struct EscapeEpisode {
    outside: f64,
    duration: f64,
    distance: f64,
    escaped_at: Option<f64>,
}

impl TaskEpisode for EscapeEpisode {
    fn observe(&mut self, step: &StepView) -> Flow {
        self.distance = step.center.x.abs();
        let units = step.body.sensing_units();
        let out = (0..units).all(|i| step.body.unit_state(step.world, i).center.x.abs() > self.outside);
        if out {
            self.escaped_at = Some(step.t);
            return Flow::Stop;
        }
        Flow::Continue
    }

    fn metrics(&self) -> Metrics {
        [
            ("distance", self.distance),
            ("velocity", self.distance / self.duration),
            ("escaped", f64::from(u8::from(self.escaped_at.is_some()))),
            ("escape_time", self.escaped_at.unwrap_or(self.duration)),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }
}
