//! EvoGym's multi-material voxel robots and four of its tasks (Bhatia et al., 2021), over the
//! mass-spring engine [`vsrlab_physics::mass_spring`].
//!
//! Data flows one way: a [`MaterialGrid`] (text rows such as `"33333/31113"`, or EvoGym's JSON
//! via [`robot_from_json`]) is checked ([`MaterialGrid::validate_robot`]), planned into points,
//! springs, quads, tight limits and actuators exactly as EvoGym builds objects
//! ([`plan_object`]), and placed with the task's world objects ([`EvoGymTask::world`]) into an
//! [`EvoGymEnv`], which steps with one action per actuator voxel and answers with EvoGym's
//! observation and reward. `docs/evogym-envs.md` lists every task's world, observation, reward
//! and episode with its source line; `docs/evogym-model.md` the physics.

mod action_stream;
mod assemble;
mod env;
mod env_lanes;
mod error;
mod grid;
mod kind;
mod materials;
mod npz_file;
mod observe;
mod rewards;
mod robot;
mod sim;
mod task;
mod tasks;
mod world_file;
mod worlds;

pub use action_stream::ActionStream;
pub use assemble::{plan_object, ObjectPlan, PlacedObject, PlannedPoint, PlannedQuad, PlannedSpring, CELL, RIGID_BAND};
pub use env::{EvoGymEnv, StepResult};
pub use env_lanes::{EnvLanes, LaneStep, LANES};
pub use error::EvoGymError;
pub use grid::{ConnectionError, MaterialGrid, MAX_ROBOT_SIDE, MAX_SIDE};
pub use kind::{EvoGymTable, KIND};
pub use materials::{Material, ACTUATOR_SIDE, RIGID_SIDE, SOFT_SIDE};
pub use npz_file::{is_npz, robot_from_npz, robot_to_npz, NpyArray};
pub use observe::{numpy_sum, relative_positions, terrain_distances, Centre, Look, Orientation};
pub use rewards::{forward, topple, Reward, RobotAndBeam, GOAL_BONUS, UNSTABLE_PENALTY};
pub use robot::{action_of, EvoGymRobot, TARGET_CENTRE, TARGET_HALF_RANGE, TARGET_RANGE};
pub use sim::{EvoGymSim, SimObject};
pub use task::{frame, sim_frame, EvoGym, STEP_SECONDS};
pub use tasks::{EvoGymTask, Piece, TaskDefinition, CAVE_SIGHT, SIGHT_RANGE};
pub use world_file::{robot_from_json, robot_to_json, world_from_json};
pub use worlds::{beam_toppler_v0, bridge_walker_v0, cave_crawler_v0, walker_v0, World, WorldObject};
