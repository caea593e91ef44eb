//! The one episode loop, shared by every task and every robot: build the world, place the robot,
//! then step physics → sense → control → actuate (vsr-model.md §2.2) until the task's duration
//! or until the task stops the episode. Pure: the same inputs give bit-identical outcomes.

use crate::agent::{Agent, Robot};
use crate::outcome::{DamageRecord, Outcome, Trace, TraceLevel};
use crate::task::{fitness_values, Flow, Scene, StepView, Task};
use vsrlab_physics::{PhysicsError, Vec2, World, WorldBuilder};

/// Why an episode could not be run or completed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EpisodeError {
    /// The description is invalid; the message names the field.
    #[error("{0}")]
    Invalid(String),
    /// The simulation produced non-finite values.
    #[error("episode failed at t = {time:.4} s: {source}")]
    Physics {
        /// Simulated time when it happened.
        time: f64,
        /// The engine's report.
        source: PhysicsError,
    },
}

/// Runs one episode of `robot` on `task` with episode seed `seed`, recording a trace at `level`.
pub fn run(robot: &dyn Robot, task: &dyn Task, seed: u64, level: TraceLevel) -> Result<Outcome, EpisodeError> {
    run_observed(robot, task, seed, level, &mut |_, _| {})
}

/// [`run`], calling `observe(t, agent)` after every step (after the task has seen it): the hook of
/// analyses that look inside the robot during the episode, such as weight snapshots.
pub fn run_observed(
    robot: &dyn Robot,
    task: &dyn Task,
    seed: u64,
    level: TraceLevel,
    observe: &mut dyn FnMut(f64, &dyn Agent),
) -> Result<Outcome, EpisodeError> {
    task.validate()?;
    let mut builder = WorldBuilder::new(task.physics().clone());
    let scene = task.build_world(&mut builder, seed);
    let origin = task.place(&scene, &robot.footprint());
    let mut agent = robot.assemble(&mut builder, origin, seed)?;
    let mut world = builder.build().map_err(|e| EpisodeError::Invalid(e.to_string()))?;
    let mut episode = task.start();
    let mut recorder = Recorder::new(level, task, &scene, agent.as_mut());
    let dt = task.physics().dt;
    let mut damage = task
        .damage()
        .map(|d| (d.at, d.mask(agent.body().actuator_count(), seed)));
    let mut t = 0.0;
    while t < task.duration() {
        t += dt;
        world
            .step()
            .map_err(|source| EpisodeError::Physics { time: t, source })?;
        // half a step of tolerance: t accumulates rounding errors
        if damage.as_ref().is_some_and(|(at, _)| t >= at - 0.5 * dt) {
            let (_, broken) = damage.take().expect("checked");
            agent.break_actuators(&broken)?;
            recorder.damaged(t, broken);
        }
        agent.act(&mut world, t);
        let center = agent.body().center(&world);
        if !center.is_finite() {
            return Err(EpisodeError::Physics {
                time: t,
                source: PhysicsError::NonFinite {
                    step: world.step_count(),
                    body: 0,
                },
            });
        }
        let flow = episode.observe(&StepView {
            t,
            world: &world,
            body: agent.body(),
            center,
            scene: &scene,
        });
        recorder.record(t, center, &world, &scene, agent.as_ref());
        observe(t, agent.as_ref());
        if flow == Flow::Stop {
            break;
        }
    }
    let metrics = episode.metrics();
    Ok(Outcome {
        fitness: fitness_values(task.objectives(), &metrics),
        metrics,
        steps: world.step_count(),
        units: agent.body().actuator_count(),
        trace: recorder.finish(),
    })
}

/// Accumulates the trace at the requested level.
struct Recorder {
    level: TraceLevel,
    trace: Trace,
}

impl Recorder {
    fn new(level: TraceLevel, task: &dyn Task, scene: &Scene, agent: &mut dyn Agent) -> Recorder {
        let steps = (task.duration() / task.physics().dt).ceil() as usize + 1;
        let mut trace = Trace {
            dt: task.physics().dt,
            ..Default::default()
        };
        if level != TraceLevel::None {
            trace.times.reserve(steps);
            trace.centers.reserve(steps);
            agent.describe(&mut trace);
        }
        if level == TraceLevel::Full {
            trace.terrain = scene.terrain.clone();
            trace.obstacles = scene.obstacles.clone();
            trace.object_radii = scene.objects.iter().map(|o| o.radius).collect();
            trace.outline_corners = agent.body().outline_corners();
            trace.outlines.reserve(steps * trace.corners_per_step());
        }
        Recorder { level, trace }
    }

    fn record(&mut self, t: f64, center: Vec2, world: &World, scene: &Scene, agent: &dyn Agent) {
        if self.level == TraceLevel::None {
            return;
        }
        self.trace.times.push(t);
        self.trace.centers.push(center);
        if self.level != TraceLevel::Full {
            return;
        }
        agent.body().outline(world, &mut self.trace.outlines);
        for o in &scene.objects {
            self.trace
                .objects
                .push((world.part_position(o.part), world.part_angle(o.part)));
        }
        agent.record(&mut self.trace);
    }

    /// Notes the damage of this step (traces of every level but `None`).
    fn damaged(&mut self, t: f64, broken: Vec<bool>) {
        if self.level != TraceLevel::None {
            self.trace.damage = Some(DamageRecord { time: t, broken });
        }
    }

    fn finish(self) -> Option<Trace> {
        (self.level != TraceLevel::None).then_some(self.trace)
    }
}
