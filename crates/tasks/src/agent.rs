//! [`Robot`] and [`Agent`]: a robot as the episode loop sees it, before and after it is put in a
//! world. The voxel robot of a robot file ([`crate::RobotSpec`]) is one implementation; a body
//! that is not a voxel grid is another type implementing these two traits.

use crate::body_summary::BodySummary;
use crate::episode::EpisodeError;
use crate::kinds::RobotDescription;
use crate::outcome::Trace;
use vsrlab_body::Body;
use vsrlab_brain::Controller;
use vsrlab_physics::{Vec2, World, WorldBuilder};

/// A robot description that can be put in a world.
pub trait Robot: Send + Sync {
    /// Points of the body's underside relative to its origin: the task places the robot so that
    /// the lowest of them clears the ground.
    fn footprint(&self) -> Vec<Vec2>;
    /// Adds the body to `builder` with its origin at `origin`, and builds its sensors and brain.
    /// `seed` is the episode seed (sensor noise).
    fn assemble(&self, builder: &mut WorldBuilder, origin: Vec2, seed: u64) -> Result<Box<dyn Agent>, EpisodeError>;
    /// The body summarised by its kind (its text form for records, its morphology descriptors),
    /// `None` when the kind has none.
    fn summary(&self) -> Option<BodySummary> {
        None
    }
    /// The robot as its kind describes it (robot file, brain, labels), when it is of a
    /// registered kind.
    fn description(&self) -> Option<&dyn RobotDescription> {
        None
    }
}

/// A robot in a world: its body, and what it does at every step.
pub trait Agent: Send {
    /// The body, for tasks, traces and drawing.
    fn body(&self) -> &dyn Body;
    /// One control step at time `t`, right after the physics step: sense, think, set the
    /// actuation for the next physics step (vsr-model.md §2.2).
    fn act(&mut self, world: &mut World, t: f64);
    /// The first half of [`Agent::act`] for a controller outside the robot: reads the sensors at
    /// time `t` into [`Agent::readings`]. Default: a body without sensors reads nothing.
    fn sense(&mut self, _world: &World, _t: f64) {}
    /// The sensor readings of the last [`Agent::sense`] (or [`Agent::act`]): what the brain sees.
    fn readings(&self) -> &[f64] {
        &[]
    }
    /// Number of values an outside controller gives [`Agent::actuate`] (the brain's outputs).
    /// Default: one per actuator of the body.
    fn action_count(&self) -> usize {
        self.body().actuator_count()
    }
    /// The second half of [`Agent::act`] for a controller outside the robot: sets the actuation
    /// from `actions` (one per [`Agent::action_count`], in [-1, 1]) in place of the brain's outputs.
    /// Default: the values go to the body's actuators as they are.
    fn actuate(&mut self, world: &mut World, actions: &[f64]) {
        self.body().actuate(world, actions);
    }
    /// Writes what does not change during the episode into a trace: the part size and fixed
    /// channels (grid cells, sensor layout). The brain's own are added by the episode loop.
    fn describe(&mut self, trace: &mut Trace);
    /// Publishes this step's channels (states, readings, actuations) into a trace; the brain's
    /// are added by the episode loop.
    fn record(&self, trace: &mut Trace);
    /// The brain, whose channels ([`Controller::describe`], [`Controller::publish`]) the episode
    /// loop records and observers read (plastic weights). Default: none.
    fn brain(&self) -> Option<&dyn Controller> {
        None
    }
    /// Breaks the actuated units marked `true` (one flag per [`Body::actuator_count`] unit): their
    /// actuation stays 0 from the next step on ([`crate::Damage`]). Default: an error, for bodies
    /// that cannot be damaged.
    fn break_actuators(&mut self, _broken: &[bool]) -> Result<(), EpisodeError> {
        Err(EpisodeError::Field(vsrlab_field::FieldError::new(
            "task.damage",
            "this robot's body cannot be damaged",
        )))
    }
}
