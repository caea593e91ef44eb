//! The carrier task (thesis §6.3.3.3, psa-model.md "Carrier"): walk right on flat ground with a
//! ball on top; the episode ends as soon as the ball is no longer above the robot (its centre
//! outside the x range of the robot's sensing units) or touches the ground.
//!
//! Metrics: `distance` (x displacement of the robot's centre), `velocity` (`distance` over the
//! full duration, as the original: a robot that drops the ball early scores low), `carried` (how
//! long the ball stayed on).

use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::locomotion::place_on_ground;
use crate::task::{
    check_episode, task_field, Flow, Metrics, Objective, RigidTask, Scene, SceneObject, StepView, Task, TaskEpisode,
};
use crate::terrain::{add_ground, height_at};
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics::{PartDesc, Polygon, Vec2, WorldBuilder, WorldSettings};

/// The metrics of a carrier episode.
pub const METRICS: &[&str] = &["distance", "velocity", "carried"];

/// Collision group of the ball (not the robot's, so the robot's masses feel it as touch).
const BALL_GROUP: u32 = 7;

/// The ball to carry.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Ball {
    /// Radius (the original: r/4 of the PSA, 1.875 for medium).
    pub radius: f64,
    /// Initial centre x (the original: r).
    pub x: f64,
    /// Initial centre y (the original: 2.5 r + 1).
    pub y: f64,
    /// Mass per unit area.
    pub density: f64,
    /// Coulomb friction coefficient.
    pub friction: f64,
}

impl Default for Ball {
    fn default() -> Self {
        Ball {
            radius: 1.875,
            x: 7.5,
            y: 19.75,
            density: 500.0,
            friction: 10.0,
        }
    }
}

/// Carrier task settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Carrier {
    /// Episode length (simulated seconds).
    pub duration: f64,
    /// x of the robot's left edge at the start.
    pub initial_x: f64,
    /// Gap between the robot's lowest point and the ground at the start.
    pub initial_gap: f64,
    /// The ball.
    pub ball: Ball,
    /// Which metrics are the fitness values (default `velocity`).
    pub fitness: Fitness,
    /// Physics engine settings (default: PSA worlds, gravity −10).
    pub physics: WorldSettings,
}

impl Default for Carrier {
    fn default() -> Self {
        Carrier {
            duration: 30.0,
            initial_x: 0.0,
            initial_gap: 0.5,
            ball: Ball::default(),
            fitness: Fitness::maximize("velocity"),
            physics: crate::kinds::psa::inflation::psa_physics(),
        }
    }
}

impl Task for Carrier {
    fn kind(&self) -> &'static str {
        "carrier"
    }

    fn validate(&self) -> Result<(), EpisodeError> {
        check_episode(self.duration, &self.fitness.0, METRICS, &self.physics)?;
        let b = &self.ball;
        let ball = |e: FieldError| Err(task_field(e.at("ball")));
        for (name, v) in [("radius", b.radius), ("density", b.density)] {
            if !(v.is_finite() && v > 0.0) {
                return ball(FieldError::sentence(name, format!("must be finite and > 0, got {v}")));
            }
        }
        if !(b.friction.is_finite() && b.friction >= 0.0) {
            return ball(FieldError::sentence(
                "friction",
                format!("must be finite and ≥ 0, got {}", b.friction),
            ));
        }
        if !(b.x.is_finite() && b.y.is_finite() && b.y > b.radius) {
            return ball(FieldError::message(format!(
                "x and y must be finite and the ball above the ground (y > radius), got ({}, {})",
                b.x, b.y
            )));
        }
        if !(self.initial_x.is_finite() && self.initial_gap.is_finite() && self.initial_gap >= 0.0) {
            return Err(task_field(FieldError::sentence(
                "initial_x",
                "and task.initial_gap must be finite (gap ≥ 0)",
            )));
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

impl RigidTask for Carrier {
    fn physics(&self) -> &WorldSettings {
        &self.physics
    }

    fn build_world(&self, builder: &mut WorldBuilder, _seed: u64) -> Scene {
        let terrain = vec![Vec2::new(-500.0, 0.0), Vec2::new(500.0, 0.0)];
        add_ground(builder, &terrain);
        let b = &self.ball;
        let circle = Polygon::circle(Vec2::ZERO, b.radius).expect("validated radius");
        let part = builder.add_part(
            PartDesc::new(Vec2::new(b.x, b.y), circle)
                .density(b.density)
                .friction(b.friction)
                .group(BALL_GROUP, false),
        );
        Scene {
            terrain,
            obstacles: Vec::new(),
            objects: vec![SceneObject { part, radius: b.radius }],
        }
    }

    fn place(&self, scene: &Scene, footprint: &[Vec2]) -> Vec2 {
        place_on_ground(&scene.terrain, footprint, self.initial_x, self.initial_gap)
    }

    fn start(&self) -> Box<dyn TaskEpisode> {
        Box::new(CarrierEpisode {
            duration: self.duration,
            tolerance: self.physics.touch_tolerance,
            ..Default::default()
        })
    }
}

#[derive(Default)]
struct CarrierEpisode {
    duration: f64,
    tolerance: f64,
    first_x: Option<f64>,
    last_x: f64,
    carried: f64,
}

impl TaskEpisode for CarrierEpisode {
    fn observe(&mut self, step: &StepView) -> Flow {
        self.first_x.get_or_insert(step.center.x);
        self.last_x = step.center.x;
        self.carried = step.t;
        let Some(ball) = step.scene.objects.first() else {
            return Flow::Continue;
        };
        let at = step.world.part_position(ball.part);
        let ground = height_at(&step.scene.terrain, at.x).unwrap_or(f64::NEG_INFINITY);
        let on_ground = at.y - ball.radius <= ground + self.tolerance;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..step.body.sensing_units() {
            let x = step.body.unit_state(step.world, i).center.x;
            lo = lo.min(x);
            hi = hi.max(x);
        }
        if on_ground || at.x < lo || at.x > hi {
            return Flow::Stop;
        }
        Flow::Continue
    }

    fn metrics(&self) -> Metrics {
        let distance = self.last_x - self.first_x.unwrap_or(self.last_x);
        [
            ("distance", distance),
            ("velocity", distance / self.duration),
            ("carried", self.carried),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect()
    }
}
