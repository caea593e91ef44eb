//! [`Task`]: what a robot is asked to do. A task builds its world, says where the robot starts,
//! watches every step, may end the episode early, and turns what it saw into named metrics and
//! fitness values. The one episode loop ([`crate::episode::run`]) drives every task.
//!
//! A new task is one module with a settings struct that implements [`Task`], plus one line in
//! the registry ([`crate::registry`]).

use crate::agent::{Agent, Robot};
use crate::damage::Damage;
use crate::episode::EpisodeError;
use crate::outcome::{Outcome, TraceLevel};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use vsrlab_body::Body;
use vsrlab_field::FieldError;
use vsrlab_physics::{PartHandle, Vec2, World, WorldBuilder, WorldSettings};

/// Named figures a task measured in one episode (e.g. `distance`, `velocity`).
pub type Metrics = BTreeMap<String, f64>;

/// Whether larger or smaller values of an objective are better.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sense {
    /// Larger is better (velocity, distance, height).
    #[default]
    Maximize,
    /// Smaller is better (energy, voxel count).
    Minimize,
}

/// One fitness value of a task: which metric, and whether to maximise or minimise it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Objective {
    /// The metric's name (one of the task's [`Task::metric_names`]).
    pub metric: String,
    /// Maximise (default) or minimise.
    #[serde(default)]
    pub sense: Sense,
}

impl Objective {
    /// An objective to maximise.
    pub fn maximize(metric: &str) -> Self {
        Self {
            metric: metric.to_string(),
            sense: Sense::Maximize,
        }
    }
}

/// The world a task built: what placement, the task's episode and drawing need to know of it.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Scene {
    /// The ground's polyline, (x, y) with increasing x.
    pub terrain: Vec<Vec2>,
    /// Static polygons besides the ground (walls, a cage's roof), for drawing.
    pub obstacles: Vec<Vec<Vec2>>,
    /// Loose bodies the task added (a ball to carry).
    pub objects: Vec<SceneObject>,
}

/// A loose circular body of a task's world.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneObject {
    /// Its part in the world.
    pub part: PartHandle,
    /// Its radius.
    pub radius: f64,
}

impl Scene {
    /// A scene of just a ground polyline.
    pub fn ground(terrain: Vec<Vec2>) -> Scene {
        Scene {
            terrain,
            ..Scene::default()
        }
    }
}

/// What a task sees after each step (physics → sense → control → actuate, vsr-model.md §2.2).
pub struct StepView<'a> {
    /// Simulated time at the end of the step.
    pub t: f64,
    /// The world.
    pub world: &'a World,
    /// The robot's body.
    pub body: &'a dyn Body,
    /// The body's centre ([`Body::center`]), already checked to be finite.
    pub center: Vec2,
    /// What the task built.
    pub scene: &'a Scene,
}

/// Whether the episode goes on after a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Go on until the task's duration.
    Continue,
    /// End the episode now (e.g. the goal was reached or the robot fell).
    Stop,
}

/// A task's state during one episode: the per-step hook and the final metrics.
pub trait TaskEpisode: Send {
    /// Called after every step; may end the episode.
    fn observe(&mut self, step: &StepView) -> Flow;
    /// The metrics of the episode so far.
    fn metrics(&self) -> Metrics;
}

/// A task: what a robot is asked to do, how long, and how it is scored; and the loop that runs
/// its episodes. Tasks on the 2D rigid-body engine (locomotion, jump, escape, carrier) are
/// [`RigidTask`]s and run the one loop of [`crate::episode`]; a task on another engine (EvoGym's
/// mass-spring voxels) runs its own loop in [`Task::run_episode`].
pub trait Task: Send + Sync + std::fmt::Debug {
    /// The task's kind, as in configs (`locomotion`, `jump`).
    fn kind(&self) -> &'static str;
    /// Checks the settings; errors name the field.
    fn validate(&self) -> Result<(), EpisodeError>;
    /// Longest episode, in simulated seconds.
    fn duration(&self) -> f64;
    /// Simulated seconds per step of an episode (the unit of speed benchmarks). Default: the
    /// rigid engine's time step; 0 for a task of no engine.
    fn step_seconds(&self) -> f64 {
        self.rigid().map_or(0.0, |t| t.physics().dt)
    }
    /// The metrics this task reports.
    fn metric_names(&self) -> &'static [&'static str];
    /// The fitness values, in order (one for single-objective tasks).
    fn objectives(&self) -> &[Objective];
    /// The task as its own type, for robot kinds that adapt to the tasks of their family
    /// (`RobotDescription::for_task`). Default: none.
    fn as_any(&self) -> Option<&dyn std::any::Any> {
        None
    }
    /// Body parts that break during the episode, if any ([`Damage`]). Default: none.
    fn damage(&self) -> Option<&Damage> {
        None
    }
    /// The task as a task of the 2D rigid-body engine, when it is one: what stepping an episode
    /// from outside (Python, Gymnasium) needs. Default: none.
    fn rigid(&self) -> Option<&dyn RigidTask> {
        None
    }
    /// Runs one episode of `robot` with episode seed `seed`, recording a trace at `level` and
    /// calling `observe(t, agent)` after every step of a rigid-body episode. Default: the rigid
    /// engine's loop ([`crate::episode::run_rigid`]) for a [`RigidTask`]; a task on another
    /// engine runs its own.
    fn run_episode(
        &self,
        robot: &dyn Robot,
        seed: u64,
        level: TraceLevel,
        observe: &mut dyn FnMut(f64, &dyn Agent),
    ) -> Result<Outcome, EpisodeError> {
        match self.rigid() {
            Some(task) => crate::episode::run_rigid(robot, task, seed, level, observe),
            None => Err(EpisodeError::Invalid(format!(
                "task {} has no episode loop",
                self.kind()
            ))),
        }
    }
    /// The group of `robot` for [`Task::run_episodes`]: robots of one group may share a batch
    /// (a task that steps several episodes at once needs them to have the same body shape);
    /// `None`, the default: the robot runs alone.
    fn episode_group(&self, _robot: &dyn Robot) -> Option<String> {
        None
    }
    /// How many robots of one group [`Task::run_episodes`] steps together at best (1, the
    /// default: one at a time, so evaluators do not batch).
    fn episode_batch(&self) -> usize {
        1
    }
    /// Runs one episode per robot (`robots[i]` with seed `seeds[i]`, all of one
    /// [`Task::episode_group`]), summaries only, in order: the batch form evaluators call. A task
    /// may step them together (population lanes) as long as every outcome and error has the bits
    /// of [`Task::run_episode`]. Default: one after the other.
    fn run_episodes(&self, robots: &[&dyn Robot], seeds: &[u64]) -> Vec<Result<Outcome, EpisodeError>> {
        one_by_one(self, robots, seeds)
    }
}

/// Test helper: runs `robots` through [`Task::run_episodes`] and each alone through
/// [`Task::run_episode`], asserts that every batch outcome has the bits of its episode alone
/// (steps, fitness, every metric), and returns the outcomes alone.
#[cfg(test)]
pub(crate) fn assert_batch_is_alone(task: &dyn Task, robots: &[&dyn Robot], seeds: &[u64]) -> Vec<Outcome> {
    let bits = |values: &[f64]| values.iter().map(|v| v.to_bits()).collect::<Vec<u64>>();
    let batch = task.run_episodes(robots, seeds);
    let mut alone_outcomes = Vec::with_capacity(robots.len());
    for ((robot, &seed), laned) in robots.iter().zip(seeds).zip(&batch) {
        let alone = task
            .run_episode(*robot, seed, TraceLevel::None, &mut |_, _| {})
            .unwrap();
        let laned = laned.as_ref().unwrap();
        assert_eq!(laned.steps, alone.steps);
        assert_eq!(bits(&laned.fitness), bits(&alone.fitness));
        for (name, value) in &alone.metrics {
            assert_eq!(laned.metrics[name].to_bits(), value.to_bits(), "{name}");
        }
        alone_outcomes.push(alone);
    }
    alone_outcomes
}

/// One summary episode per robot, one after the other: [`Task::run_episodes`]'s default, and
/// what a task that steps batches together falls back to.
pub fn one_by_one<T: Task + ?Sized>(
    task: &T,
    robots: &[&dyn Robot],
    seeds: &[u64],
) -> Vec<Result<Outcome, EpisodeError>> {
    robots
        .iter()
        .zip(seeds)
        .map(|(robot, &seed)| task.run_episode(*robot, seed, TraceLevel::None, &mut |_, _| {}))
        .collect()
}

/// A task on the 2D rigid-body engine: it builds its world, places the robot, and watches every
/// step through a [`TaskEpisode`].
pub trait RigidTask: Task {
    /// Physics engine settings.
    fn physics(&self) -> &WorldSettings;
    /// Adds the static world (ground, obstacles) to `builder`; `seed` is the episode seed.
    fn build_world(&self, builder: &mut WorldBuilder, seed: u64) -> Scene;
    /// Where the robot's origin goes, given the underside points of its body relative to its
    /// origin ([`crate::Robot::footprint`]).
    fn place(&self, scene: &Scene, footprint: &[Vec2]) -> Vec2;
    /// A fresh per-episode state.
    fn start(&self) -> Box<dyn TaskEpisode>;
}

/// Steps of an episode of `duration` seconds at `dt` seconds per step: the fewest whose total
/// reaches the duration, at least one. A duration within a millionth of a step of a whole number
/// of steps is that number, whatever the float rounding of `duration / dt` (5 s at 1/60 s is 300
/// steps, 1 s is 60, 10 s is 600); docs/experiments.md.
pub fn episode_steps(duration: f64, dt: f64) -> u64 {
    ((duration / dt) - 1e-6).ceil().max(1.0) as u64
}

/// Steps of an episode as the original 2D simulator counts them: it steps while its time, a
/// float sum of `dt`, is below `duration` (at least one step). The rounding of that sum decides
/// the last step: at 1/60 s, 5 s → 301, 10 s → 600, 30 s → 1801, 60 s → 3601 (docs/model.md).
/// The 2D voxel robots and PSAs, which reproduce the original, count this way; the sum costs one
/// addition per step of the episode, which [`check_episode`] bounds (at most 100,000 s).
pub fn original_episode_steps(duration: f64, dt: f64) -> u64 {
    let (mut t, mut steps) = (0.0, 0u64);
    // the whole-number count plus a margin bounds the loop whatever the inputs
    let bound = episode_steps(duration, dt).saturating_mul(2).saturating_add(2);
    while t < duration && steps < bound {
        t += dt;
        steps += 1;
    }
    steps.max(1)
}

/// The fitness values of `objectives` read from `metrics` (NaN for a missing metric, which
/// [`Task::validate`] rules out).
pub fn fitness_values(objectives: &[Objective], metrics: &Metrics) -> Vec<f64> {
    objectives
        .iter()
        .map(|o| metrics.get(&o.metric).copied().unwrap_or(f64::NAN))
        .collect()
}

/// Checks that every objective names one of `names`; the error names the field.
pub fn check_objectives(objectives: &[Objective], names: &[&str]) -> Result<(), EpisodeError> {
    let at_fitness = |e: FieldError| task_field(e.at("fitness"));
    if objectives.is_empty() {
        return Err(at_fitness(FieldError::message("give at least one objective")));
    }
    for (i, o) in objectives.iter().enumerate() {
        if !names.contains(&o.metric.as_str()) {
            let message = format!("unknown metric '{}': expected one of {}", o.metric, names.join(", "));
            return Err(at_fitness(FieldError::message(message).at_index(i)));
        }
    }
    Ok(())
}

/// Checks what every task has: an episode length in (0, 100000] simulated seconds, objectives
/// among the task's metrics, and physics settings; the error names the field.
pub fn check_episode(
    duration: f64,
    objectives: &[Objective],
    metrics: &[&str],
    physics: &WorldSettings,
) -> Result<(), EpisodeError> {
    if !(duration.is_finite() && duration > 0.0 && duration <= 1e5) {
        return Err(task_field(FieldError::sentence(
            "duration",
            format!("must be in (0, 100000] seconds, got {duration}"),
        )));
    }
    check_objectives(objectives, metrics)?;
    physics.validate().map_err(|e| task_field(e.at("physics")))
}

/// An error on a field of the task's table, placed under `task`.
pub fn task_field(error: FieldError) -> EpisodeError {
    EpisodeError::Field(error.at("task"))
}

#[cfg(test)]
mod tests {
    use super::episode_steps;

    #[test]
    fn whole_numbers_of_steps_do_not_depend_on_float_rounding() {
        let dt = 1.0 / 60.0;
        // 300 steps of dt add up to less than 5 s in floats (the old rule took a 301st step)
        assert!((0..300).fold(0.0, |t, _| t + dt) < 5.0);
        for (duration, steps) in [(1.0, 60), (5.0, 300), (10.0, 600), (30.0, 1800), (0.1, 6)] {
            assert_eq!(episode_steps(duration, dt), steps, "{duration} s");
        }
        // a duration between steps rounds up, and an episode has at least one step
        assert_eq!(episode_steps(1.01, dt), 61);
        assert_eq!(episode_steps(1e-9, dt), 1);
    }

    #[test]
    fn the_original_count_follows_the_float_sum_of_its_time() {
        use super::original_episode_steps;
        let dt = 1.0 / 60.0;
        // the counts of 2D-VSR-Sim's loop `while (t < T) { t += dt; ... }`, written out
        for (duration, steps) in [
            (1.0, 60),
            (4.0, 241),
            (5.0, 301),
            (10.0, 600),
            (20.0, 1200),
            (30.0, 1801),
            (60.0, 3601),
        ] {
            assert_eq!(original_episode_steps(duration, dt), steps, "{duration} s");
        }
        // each count is the loop's: one step fewer leaves the sum below the duration
        for duration in [0.1, 2.0, 3.0, 7.5, 30.0, 100.0] {
            let n = original_episode_steps(duration, dt);
            let sum = |k: u64| (0..k).fold(0.0, |t, _| t + dt);
            assert!(sum(n) >= duration && sum(n - 1) < duration, "{duration} s: {n}");
        }
        assert_eq!(original_episode_steps(1e-9, dt), 1);
    }
}
