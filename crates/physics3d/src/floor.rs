//! The floor: a penalty spring under every voxel below z = −s/2, a dashpot on vertical speed,
//! and Coulomb friction with a static state that breaks when the horizontal force exceeds
//! μs·N and returns when kinetic friction would stop the voxel within the step
//! (`docs/voxelyze-model.md` §7).

use glam::DVec3;

/// What the floor did to one voxel this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FloorContact {
    /// Whether the voxel touches the floor (penetration ≥ 0).
    pub touching: bool,
    /// The horizontal friction force added (zero while static or breaking free).
    pub friction: DVec3,
}

/// Adds the floor's force to `force` (everything else already summed) for a voxel at height
/// `z` with velocity `v`, rest size `size` on a lattice of size `lattice`; updates its static flag.
#[allow(clippy::too_many_arguments)]
pub(crate) fn floor_force(
    force: &mut DVec3,
    z: f64,
    v: DVec3,
    size: f64,
    lattice: f64,
    stiffness: f64,
    collision_damping: f64,
    static_friction: f64,
    kinetic_friction: f64,
    is_static: &mut bool,
) -> FloorContact {
    let penetration = size / 2.0 - lattice / 2.0 - z;
    if penetration < 0.0 {
        *is_static = false;
        return FloorContact {
            touching: false,
            friction: DVec3::ZERO,
        };
    }
    let normal = stiffness * penetration;
    force.z += normal - collision_damping * v.z;
    let mut friction = DVec3::ZERO;
    if *is_static {
        let limit = static_friction * normal;
        if force.x * force.x + force.y * force.y > limit * limit {
            *is_static = false;
        }
    } else {
        let horizontal = DVec3::new(v.x, v.y, 0.0);
        let speed = horizontal.length();
        if speed > 0.0 {
            friction = -kinetic_friction * normal * horizontal / speed;
            *force += friction;
        }
    }
    FloorContact {
        touching: true,
        friction,
    }
}
