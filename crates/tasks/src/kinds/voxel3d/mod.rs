//! 3D voxel robots on the Voxelyze model ([`vsrlab_physics3d`]): a body grid of cubic voxels
//! ([`BodyGrid3`]), the affordance study's sensors on every voxel ([`Sensor3`]), a brain over the
//! 3D grid layout (each voxel's unit with six face neighbours), thermal actuation, and the
//! [`Locomotion3d`] task with fixed obstacle voxels, and the affordance study's [`Affordance`] task
//! (walls with apertures, votes, its scores and penalties). `docs/voxels3d.md` describes the model and
//! every choice.

mod affordance;
mod aperture;
mod grid;
mod kind;
mod physics;
mod population;
mod recorder;
mod robot;
mod sensors;
mod setup;
mod task;
mod worlds;

pub use affordance::{decision, Affordance, Scores};
pub use aperture::{aperture_world, random_aperture_world, shape_length, ApertureWorld, Environment};
pub use grid::{shape_names, BodyGrid3, MAX_SIDE};
pub use kind::{Voxel3dTable, DEFAULT_BRAIN, KIND};
pub use physics::{Built, Physics3d, MAX_STEPS};
pub use robot::Voxel3dRobot;
pub use sensors::{Sensor3, VoxelSense, DEFAULT_SENSORS};
pub use task::Locomotion3d;
