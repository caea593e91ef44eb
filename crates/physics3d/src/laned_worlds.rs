//! [`LANES`] worlds of one body stepped together, the form the tasks and the runner use: a
//! [`WorldLanes`] of that count behind functions that are not generic, so that its kernels are
//! compiled once, in this crate, instead of again in every crate (and test build) that steps
//! populations.

use crate::world_lanes::WorldLanes;
use crate::{Physics3dError, VoxelId, World};
use glam::{DQuat, DVec3};

/// How many episodes a [`LanedWorlds`] steps together.
pub const LANES: usize = 4;

/// [`LANES`] copies of one world in lanes, each lane the bits of the scalar world
/// (see [`WorldLanes`], whose methods these are).
#[derive(Debug, Clone)]
pub struct LanedWorlds(WorldLanes<LANES>);

impl LanedWorlds {
    /// [`LANES`] copies of `world`, which must not have stepped ([`WorldLanes::of`]).
    pub fn of(world: &World) -> Result<LanedWorlds, Physics3dError> {
        WorldLanes::of(world).map(LanedWorlds)
    }

    /// One step of `dt` seconds in every lane ([`WorldLanes::step`]).
    pub fn step(&mut self, dt: f64) -> Result<(), Physics3dError> {
        self.0.step(dt)
    }

    /// Lane `lane`'s first divergence, if it diverged ([`WorldLanes::diverged`]).
    pub fn diverged(&self, lane: usize) -> Option<Physics3dError> {
        self.0.diverged(lane)
    }

    /// Sets voxel `v`'s temperature in lane `lane`.
    pub fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64) {
        self.0.set_temperature(v, lane, temperature)
    }

    /// Sets voxel `v`'s temperature in every lane at once.
    pub fn set_temperatures(&mut self, v: VoxelId, temperatures: [f64; LANES]) {
        self.0.set_temperatures(v, temperatures)
    }

    /// Voxel `v`'s centre in lane `lane` (m).
    pub fn position(&self, v: VoxelId, lane: usize) -> DVec3 {
        self.0.position(v, lane)
    }

    /// Voxel `v`'s velocity in lane `lane` (m/s).
    pub fn velocity(&self, v: VoxelId, lane: usize) -> DVec3 {
        self.0.velocity(v, lane)
    }

    /// Voxel `v`'s orientation in lane `lane`.
    pub fn orientation(&self, v: VoxelId, lane: usize) -> DQuat {
        self.0.orientation(v, lane)
    }

    /// Whether voxel `v` reaches into the floor in lane `lane`.
    pub fn touches_floor(&self, v: VoxelId, lane: usize) -> bool {
        self.0.touches_floor(v, lane)
    }

    /// Whether voxel `v` touched another voxel in lane `lane` in the last step.
    pub fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool {
        self.0.touches_voxel(v, lane)
    }

    /// Whether some pair of voxels that touched in lane `lane` in the last step passes `test`
    /// (pairs in [`WorldLanes::contacts`]'s order, stopping at the first that passes).
    pub fn any_contact(&self, lane: usize, test: &dyn Fn(VoxelId, VoxelId) -> bool) -> bool {
        self.0.contacts(lane).any(|(a, b)| test(a, b))
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.0.voxel_count()
    }
}
