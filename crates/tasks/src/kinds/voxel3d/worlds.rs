//! What a 3D episode loop needs of its world, whether one episode (`World`) or N episodes of one
//! body shape stepped together in population lanes (`LanedWorlds`, bit for bit the scalar world
//! in every lane): so that one loop serves both.

use glam::DVec3;
use vsrlab_physics3d::laned_worlds::LanedWorlds;
use vsrlab_physics3d::{Physics3dError, VoxelId, World};

/// One or several episodes of one body in one world.
pub(crate) trait Worlds {
    /// Lane `lane`'s divergence, if it diverged while the others stepped on.
    fn diverged(&self, lane: usize) -> Option<Physics3dError>;
    /// Voxel `v`'s centre in lane `lane`.
    fn position(&self, v: VoxelId, lane: usize) -> DVec3;
    /// Voxel `v`'s velocity in lane `lane`.
    fn velocity(&self, v: VoxelId, lane: usize) -> DVec3;
    /// Whether voxel `v` touched another voxel in lane `lane` in the last step.
    fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool;
    /// Whether voxel `v` reaches into the floor in lane `lane`.
    fn touches_floor(&self, v: VoxelId, lane: usize) -> bool;
    /// Sets voxel `v`'s temperature in lane `lane`.
    fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64);
    /// Whether some pair of voxels that touched in lane `lane` in the last step passes `test`.
    fn any_contact(&self, lane: usize, test: &dyn Fn(VoxelId, VoxelId) -> bool) -> bool;
}

impl Worlds for World {
    fn diverged(&self, _lane: usize) -> Option<Physics3dError> {
        None
    }

    fn position(&self, v: VoxelId, _lane: usize) -> DVec3 {
        World::position(self, v)
    }

    fn velocity(&self, v: VoxelId, _lane: usize) -> DVec3 {
        World::velocity(self, v)
    }

    fn touches_voxel(&self, v: VoxelId, _lane: usize) -> bool {
        World::touches_voxel(self, v)
    }

    fn touches_floor(&self, v: VoxelId, _lane: usize) -> bool {
        World::touches_floor(self, v)
    }

    fn set_temperature(&mut self, v: VoxelId, _lane: usize, temperature: f64) {
        World::set_temperature(self, v, temperature)
    }

    fn any_contact(&self, _lane: usize, test: &dyn Fn(VoxelId, VoxelId) -> bool) -> bool {
        self.contacts().any(|(a, b)| test(a, b))
    }
}

impl Worlds for LanedWorlds {
    fn diverged(&self, lane: usize) -> Option<Physics3dError> {
        LanedWorlds::diverged(self, lane)
    }

    fn position(&self, v: VoxelId, lane: usize) -> DVec3 {
        LanedWorlds::position(self, v, lane)
    }

    fn velocity(&self, v: VoxelId, lane: usize) -> DVec3 {
        LanedWorlds::velocity(self, v, lane)
    }

    fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool {
        LanedWorlds::touches_voxel(self, v, lane)
    }

    fn touches_floor(&self, v: VoxelId, lane: usize) -> bool {
        LanedWorlds::touches_floor(self, v, lane)
    }

    fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64) {
        LanedWorlds::set_temperature(self, v, lane, temperature)
    }

    fn any_contact(&self, lane: usize, test: &dyn Fn(VoxelId, VoxelId) -> bool) -> bool {
        LanedWorlds::any_contact(self, lane, test)
    }
}
