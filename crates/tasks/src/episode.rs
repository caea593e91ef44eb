//! The one episode loop, shared by every task and every robot: build the world, place the robot,
//! then step physics → sense → control → actuate (vsr-model.md §2.2) until the task's duration
//! or until the task stops the episode. Pure: the same inputs give bit-identical outcomes.

use crate::agent::{Agent, Robot};
use crate::channels::{BALL_ANGLE, BALL_RADII, BALL_XY, OBSTACLES, OBSTACLE_CORNERS};
use crate::outcome::{DamageRecord, Outcome, Trace, TraceLevel};
use crate::task::{fitness_values, Flow, Objective, RigidTask, Scene, StepView, Task, TaskEpisode};
use vsrlab_body::Probe;
use vsrlab_field::FieldError;
use vsrlab_physics::{PhysicsError, Vec2, World, WorldBuilder};

/// Why an episode could not be run or completed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EpisodeError {
    /// A field of the task or the robot holds a wrong value (`task.physics.dt`, `robot.brain.…`);
    /// shown as the [`FieldError`].
    #[error(transparent)]
    Field(#[from] FieldError),
    /// The description is invalid in a way no single field names (a world the engine refuses).
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
/// analyses that look inside the robot during the episode, such as weight snapshots. The task
/// runs the episode on its engine ([`Task::run_episode`]); only rigid-body episodes call
/// `observe`.
pub fn run_observed(
    robot: &dyn Robot,
    task: &dyn Task,
    seed: u64,
    level: TraceLevel,
    observe: &mut dyn FnMut(f64, &dyn Agent),
) -> Result<Outcome, EpisodeError> {
    task.run_episode(robot, seed, level, observe)
}

/// The episode loop of the 2D rigid-body engine: what [`Task::run_episode`] runs for a
/// [`RigidTask`].
pub fn run_rigid(
    robot: &dyn Robot,
    task: &dyn RigidTask,
    seed: u64,
    level: TraceLevel,
    observe: &mut dyn FnMut(f64, &dyn Agent),
) -> Result<Outcome, EpisodeError> {
    let mut episode = Episode::new(robot, task, seed, level)?;
    while !episode.is_over() {
        episode.step(None)?;
        observe(episode.time(), episode.agent());
    }
    Ok(episode.finish())
}

/// One episode that advances a step at a time: the loop of [`run`], opened for controllers that
/// live outside the robot (a Python policy, a Gymnasium environment). It owns its world, so it
/// outlives the robot and task it was built from.
pub struct Episode {
    world: World,
    agent: Box<dyn Agent>,
    state: Box<dyn TaskEpisode>,
    scene: Scene,
    recorder: Recorder,
    objectives: Vec<Objective>,
    damage: Option<(f64, Vec<bool>)>,
    dt: f64,
    duration: f64,
    /// Steps of the whole episode, counted as the original does
    /// ([`crate::task::original_episode_steps`]), and steps taken.
    steps: u64,
    taken: u64,
    t: f64,
    center: Vec2,
    stopped: bool,
}

impl Episode {
    /// Builds the world, places the robot and reads its sensors once (time 0).
    pub fn new(robot: &dyn Robot, task: &dyn RigidTask, seed: u64, level: TraceLevel) -> Result<Episode, EpisodeError> {
        task.validate()?;
        let mut builder = WorldBuilder::new(task.physics().clone());
        let scene = task.build_world(&mut builder, seed);
        let origin = task.place(&scene, &robot.footprint());
        let mut agent = robot.assemble(&mut builder, origin, seed)?;
        let world = builder.build().map_err(|e| EpisodeError::Invalid(e.to_string()))?;
        let recorder = Recorder::new(level, task, &scene, agent.as_mut());
        let damage = task
            .damage()
            .map(|d| (d.at, d.mask(agent.body().actuator_count(), seed)));
        let center = agent.body().center(&world);
        Ok(Episode {
            world,
            agent,
            state: task.start(),
            scene,
            recorder,
            objectives: task.objectives().to_vec(),
            damage,
            dt: task.physics().dt,
            duration: task.duration(),
            steps: crate::task::original_episode_steps(task.duration(), task.physics().dt),
            taken: 0,
            t: 0.0,
            center,
            stopped: false,
        })
    }

    /// One step: physics, then sense → control → actuate, with the robot's own brain when
    /// `actions` is `None`; with `Some`, the actions set the actuation of the *next* physics step
    /// and are applied first (the outside controller chose them from the agent's [`Agent::readings`]).
    /// Returns whether the task stopped the episode.
    pub fn step(&mut self, actions: Option<&[f64]>) -> Result<Flow, EpisodeError> {
        if let Some(a) = actions {
            if a.len() != self.agent.action_count() {
                return Err(EpisodeError::Field(FieldError::new(
                    "actions",
                    format!(
                        "{} values for a robot with {} actuators",
                        a.len(),
                        self.agent.action_count()
                    ),
                )));
            }
            self.agent.actuate(&mut self.world, a);
        }
        let dt = self.dt;
        self.t += dt;
        self.taken += 1;
        let t = self.t;
        self.world
            .step()
            .map_err(|source| EpisodeError::Physics { time: t, source })?;
        // half a step of tolerance: t accumulates rounding errors
        if self.damage.as_ref().is_some_and(|(at, _)| t >= at - 0.5 * dt) {
            let (_, broken) = self.damage.take().expect("checked");
            self.agent.break_actuators(&broken)?;
            self.recorder.damaged(t, broken);
        }
        match actions {
            None => self.agent.act(&mut self.world, t),
            Some(_) => self.agent.sense(&self.world, t),
        }
        let center = self.agent.body().center(&self.world);
        if !center.is_finite() {
            return Err(EpisodeError::Physics {
                time: t,
                source: PhysicsError::NonFinite {
                    step: self.world.step_count(),
                    body: 0,
                },
            });
        }
        self.center = center;
        let flow = self.state.observe(&StepView {
            t,
            world: &self.world,
            body: self.agent.body(),
            center,
            scene: &self.scene,
        });
        self.recorder
            .record(t, center, &self.world, &self.scene, self.agent.as_ref());
        if flow == Flow::Stop {
            self.stopped = true;
        }
        Ok(flow)
    }

    /// Whether the episode is over: the task stopped it, or its duration has passed.
    pub fn is_over(&self) -> bool {
        self.stopped || self.taken >= self.steps
    }

    /// Whether the task stopped the episode before its duration (e.g. a robot that escaped).
    pub fn stopped_by_task(&self) -> bool {
        self.stopped
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The episode's length (s).
    pub fn duration(&self) -> f64 {
        self.duration
    }

    /// Simulated seconds per step.
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// The body's centre after the last step.
    pub fn center(&self) -> Vec2 {
        self.center
    }

    /// The point whose displacement locomotion measures, after the last step
    /// ([`vsrlab_body::Body::outcome_center`]).
    pub fn outcome_center(&self) -> Vec2 {
        self.agent.body().outcome_center(&self.world)
    }

    /// The robot in its world.
    pub fn agent(&self) -> &dyn Agent {
        self.agent.as_ref()
    }

    /// The world (for drawing).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The terrain, obstacles and objects of the task.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Reads the sensors now (the first observation of an outside controller, before any step).
    pub fn sense(&mut self) {
        self.agent.sense(&self.world, self.t);
    }

    /// The trace so far (`None` for [`TraceLevel::None`]): what a frame of the episode is drawn
    /// from.
    pub fn trace(&self) -> Option<&Trace> {
        (self.recorder.level != TraceLevel::None).then_some(&self.recorder.trace)
    }

    /// The task's metrics so far (distance, velocity, …).
    pub fn metrics(&self) -> crate::Metrics {
        self.state.metrics()
    }

    /// The outcome: metrics, fitness values, steps and the trace.
    pub fn finish(self) -> Outcome {
        let metrics = self.state.metrics();
        Outcome {
            fitness: fitness_values(&self.objectives, &metrics),
            metrics,
            steps: self.world.step_count(),
            units: self.agent.body().actuator_count(),
            trace: self.recorder.finish(),
        }
    }
}

/// Writes the scene's obstacles and balls into a trace's fixed channels.
fn describe_scene(scene: &Scene, trace: &mut Trace) {
    if !scene.obstacles.is_empty() {
        let corners: Vec<f64> = scene.obstacles.iter().map(|o| o.len() as f64).collect();
        trace.fixed(&OBSTACLE_CORNERS, 1, &corners);
        let points: Vec<f64> = scene.obstacles.iter().flatten().flat_map(|p| [p.x, p.y]).collect();
        trace.fixed(&OBSTACLES, 2, &points);
    }
    if !scene.objects.is_empty() {
        let radii: Vec<f64> = scene.objects.iter().map(|o| o.radius).collect();
        trace.fixed(&BALL_RADII, 1, &radii);
    }
}

/// Accumulates the trace at the requested level.
struct Recorder {
    level: TraceLevel,
    trace: Trace,
}

impl Recorder {
    fn new(level: TraceLevel, task: &dyn RigidTask, scene: &Scene, agent: &mut dyn Agent) -> Recorder {
        let steps = crate::task::original_episode_steps(task.duration(), task.physics().dt) as usize + 1;
        let mut trace = Trace {
            dt: task.physics().dt,
            ..Default::default()
        };
        if level != TraceLevel::None {
            trace.times.reserve(steps);
            trace.centers.reserve(steps);
            agent.describe(&mut trace);
            if let Some(brain) = agent.brain() {
                brain.describe(&mut trace);
            }
        }
        if level == TraceLevel::Full {
            trace.terrain = scene.terrain.clone();
            describe_scene(scene, &mut trace);
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
        if !scene.objects.is_empty() {
            let xy = scene.objects.iter().flat_map(|o| {
                let p = world.part_position(o.part);
                [p.x, p.y]
            });
            self.trace.step_from(&BALL_XY, &mut xy.into_iter());
            let angles = scene.objects.iter().map(|o| world.part_angle(o.part));
            self.trace.step_from(&BALL_ANGLE, &mut angles.into_iter());
        }
        agent.record(&mut self.trace);
        if let Some(brain) = agent.brain() {
            brain.publish(&mut self.trace);
        }
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
