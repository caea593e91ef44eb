//! The one episode loop, shared by every task and every robot: build the world, place the robot,
//! then step physics → sense → control → actuate (vsr-model.md §2.2) until the task's duration
//! or until the task stops the episode. Pure: the same inputs give bit-identical outcomes.

use crate::agent::{Agent, Robot};
use crate::outcome::{Outcome, Trace, TraceLevel};
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
    task.validate()?;
    let mut builder = WorldBuilder::new(task.physics().clone());
    let scene = task.build_world(&mut builder, seed);
    let origin = task.place(&scene, &robot.footprint());
    let mut agent = robot.assemble(&mut builder, origin, seed)?;
    let mut world = builder.build().map_err(|e| EpisodeError::Invalid(e.to_string()))?;
    let mut episode = task.start();
    let mut recorder = Recorder::new(level, task, &scene, agent.as_mut());
    let dt = task.physics().dt;
    let mut t = 0.0;
    while t < task.duration() {
        t += dt;
        world
            .step()
            .map_err(|source| EpisodeError::Physics { time: t, source })?;
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
        });
        recorder.record(t, center, &world, agent.as_ref());
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
            trace.outline_corners = agent.body().outline_corners();
            trace.outlines.reserve(steps * trace.corners_per_step());
        }
        Recorder { level, trace }
    }

    fn record(&mut self, t: f64, center: Vec2, world: &World, agent: &dyn Agent) {
        if self.level == TraceLevel::None {
            return;
        }
        self.trace.times.push(t);
        self.trace.centers.push(center);
        if self.level != TraceLevel::Full {
            return;
        }
        agent.body().outline(world, &mut self.trace.outlines);
        agent.record(&mut self.trace);
    }

    fn finish(self) -> Option<Trace> {
        (self.level != TraceLevel::None).then_some(self.trace)
    }
}
