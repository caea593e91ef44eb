//! Worlds of one body stepped together, the form the tasks and the runner use: a [`WorldLanes`]
//! of the count this CPU runs best ([`lanes`]: eight with AVX-512, one register per value; four
//! elsewhere) behind functions that are not generic, so that its kernels are compiled once, in
//! this crate, instead of again in every crate (and test build) that steps populations.

use crate::world_lanes::WorldLanes;
use crate::{Physics3dError, VoxelId, World};
use glam::{DQuat, DVec3};

/// How many episodes a [`LanedWorlds`] steps together at most (on CPUs with AVX-512).
pub const MAX_LANES: usize = 8;

/// How many episodes a [`LanedWorlds`] steps together on this CPU: eight where it has AVX-512
/// (one register per value), four elsewhere (one AVX2 register, or plain arrays). Eight lanes in
/// two AVX2 registers measured slower than four with collisions (docs/performance.md, step 3):
/// their union of candidate pairs is larger.
pub fn lanes() -> usize {
    if wide() {
        8
    } else {
        4
    }
}

/// Whether this CPU steps eight lanes in AVX-512 registers.
fn wide() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        vsrlab_lanes::avx512::available()
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}

/// [`lanes`] copies of one world in lanes, each lane the bits of the scalar world
/// (see [`WorldLanes`], whose methods these are).
#[derive(Debug, Clone)]
pub struct LanedWorlds(Count);

/// The lane count, chosen for the CPU.
#[derive(Debug, Clone)]
enum Count {
    Four(WorldLanes<4>),
    Eight(WorldLanes<8>),
}

/// `$call` on the laned world, whichever its count.
macro_rules! each {
    ($self:expr, $w:ident => $call:expr) => {
        match $self {
            Count::Four($w) => $call,
            Count::Eight($w) => $call,
        }
    };
}

impl LanedWorlds {
    /// [`lanes`] copies of `world`, which must not have stepped ([`WorldLanes::of`]).
    pub fn of(world: &World) -> Result<LanedWorlds, Physics3dError> {
        Ok(LanedWorlds(if wide() {
            Count::Eight(WorldLanes::of(world)?)
        } else {
            Count::Four(WorldLanes::of(world)?)
        }))
    }

    /// How many episodes these worlds step together ([`lanes`]).
    pub fn lane_count(&self) -> usize {
        match self.0 {
            Count::Four(_) => 4,
            Count::Eight(_) => 8,
        }
    }

    /// One step of `dt` seconds in every lane ([`WorldLanes::step`]).
    pub fn step(&mut self, dt: f64) -> Result<(), Physics3dError> {
        each!(&mut self.0, w => w.step(dt))
    }

    /// Lane `lane`'s first divergence, if it diverged ([`WorldLanes::diverged`]).
    pub fn diverged(&self, lane: usize) -> Option<Physics3dError> {
        each!(&self.0, w => w.diverged(lane))
    }

    /// Starts lane `lane` over from the world's first state ([`WorldLanes::restart`]).
    pub fn restart(&mut self, lane: usize) {
        each!(&mut self.0, w => w.restart(lane))
    }

    /// Sets voxel `v`'s temperature in lane `lane`.
    pub fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64) {
        each!(&mut self.0, w => w.set_temperature(v, lane, temperature))
    }

    /// Voxel `v`'s centre in lane `lane` (m).
    pub fn position(&self, v: VoxelId, lane: usize) -> DVec3 {
        each!(&self.0, w => w.position(v, lane))
    }

    /// Voxel `v`'s velocity in lane `lane` (m/s).
    pub fn velocity(&self, v: VoxelId, lane: usize) -> DVec3 {
        each!(&self.0, w => w.velocity(v, lane))
    }

    /// Voxel `v`'s orientation in lane `lane`.
    pub fn orientation(&self, v: VoxelId, lane: usize) -> DQuat {
        each!(&self.0, w => w.orientation(v, lane))
    }

    /// Whether voxel `v` reaches into the floor in lane `lane`.
    pub fn touches_floor(&self, v: VoxelId, lane: usize) -> bool {
        each!(&self.0, w => w.touches_floor(v, lane))
    }

    /// Whether voxel `v` touched another voxel in lane `lane` in the last step.
    pub fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool {
        each!(&self.0, w => w.touches_voxel(v, lane))
    }

    /// Whether some pair of voxels that touched in lane `lane` in the last step passes `test`
    /// (pairs in [`WorldLanes::contacts`]'s order, stopping at the first that passes).
    pub fn any_contact(&self, lane: usize, test: &dyn Fn(VoxelId, VoxelId) -> bool) -> bool {
        each!(&self.0, w => w.contacts(lane).any(|(a, b)| test(a, b)))
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        each!(&self.0, w => w.voxel_count())
    }
}
