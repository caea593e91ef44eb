//! The channels that the episode loop and the robot kinds record, by name: what traces, videos,
//! replays and analyses read. A kind's own channels live beside its code (the voxel robot's cells
//! and lidar in `kinds/voxel/agent.rs`, the PSA's pressure in `kinds/psa/robot.rs`, a brain's in its
//! controller module); this module re-exports them so that consumers find every name in one place.

use crate::outcome::Trace;
use vsrlab_body::Channel;
use vsrlab_physics::Vec2;

pub use crate::kinds::psa::robot::PRESSURE;
pub use crate::kinds::voxel::agent::{ANGLE, CELLS, LIDAR, RAYS};
pub use vsrlab_brain::controllers::attention::{ATTENTION, ATTENTION_SIDE};
pub use vsrlab_brain::controllers::elman::VOTE;
pub use vsrlab_brain::controllers::graph::{GRAPH_EDGES, GRAPH_NEURONS, GRAPH_OUTPUTS};
pub use vsrlab_brain::PLASTIC_WEIGHTS;

/// Each unit's area over its rest area (a voxel; a PSA's membrane φ, its masses 1), per step.
pub const AREA_RATIO: Channel = Channel::replayed("area_ratio", 1e-3).fallback(1.0);
/// Each unit's actuation after sensing, per step.
pub const ACTUATION: Channel = Channel::replayed("actuation", 1e-3);
/// Whether each unit touches the ground, an obstacle or another body (1 or 0), per step.
pub const TOUCH: Channel = Channel::replayed("touch", 1.0);
/// Sensor readings scaled to [0, 1] by each reading's domain, unit after unit, per step.
pub const READINGS: Channel = Channel::replayed("readings", 1e-2).single();
/// Number of readings of each unit (fixed).
pub const READINGS_PER_UNIT: Channel = Channel::traced("readings_per_unit");
/// For each unit of the brain, the outline polygon it is drawn on, where the two orders differ (a
/// PSA: its masses are polygons 1…n and its gas unit the membrane, polygon 0); absent, unit i is
/// polygon i (fixed).
pub const UNIT_POLYGONS: Channel = Channel::traced("unit_polygons");
/// The fill colour of each outline polygon, `0xRRGGBB` as a number, chosen by the robot's kind
/// (a multi-material body: one colour per material); polygons without one are coloured by their
/// area ratio (fixed).
pub const UNIT_FILL: Channel = Channel::traced("unit_fill");
/// Static polygons besides the ground (a cage): their corners as x, y pairs (fixed).
pub const OBSTACLES: Channel = Channel::traced("obstacles");
/// Corner count of each polygon of [`OBSTACLES`] (fixed).
pub const OBSTACLE_CORNERS: Channel = Channel::traced("obstacle_corners");
/// Radius of each loose ball of the world (fixed).
pub const BALL_RADII: Channel = Channel::traced("ball_radii");
/// Each ball's centre, x, y pairs, per step.
pub const BALL_XY: Channel = Channel::traced("ball_xy").positions();
/// Each ball's angle, per step.
pub const BALL_ANGLE: Channel = Channel::replayed("ball_angle", 1e-3);

/// Each voxel's centre of a 3D body, x, y, z triples (m), per step; z is up.
pub const VOXEL_XYZ: Channel = Channel::replayed("voxel_xyz", 1e-5);
/// Each voxel's orientation of a 3D body, quaternions w, x, y, z, per step.
pub const VOXEL_QUAT: Channel = Channel::replayed("voxel_quat", 1e-4);
/// Each 3D voxel's edge (m), per step (thermal actuation changes it).
pub const VOXEL_EDGE: Channel = Channel::replayed("voxel_edge", 1e-6);
/// Voxels of a 3D world that never move (walls, obstacles): their centres, x, y, z triples, and
/// their edge is the trace's `side_length` (fixed).
pub const FIXED_VOXELS: Channel = Channel::traced("fixed_voxels");

/// The obstacles of a trace ([`OBSTACLES`], [`OBSTACLE_CORNERS`]) as polygons.
pub fn obstacles(trace: &Trace) -> Vec<Vec<Vec2>> {
    let points = trace.fixed_values(OBSTACLES.name);
    let mut start = 0;
    trace
        .fixed_values(OBSTACLE_CORNERS.name)
        .iter()
        .map(|&n| {
            let n = n as usize;
            let polygon = points
                .get(2 * start..2 * (start + n))
                .unwrap_or(&[])
                .chunks(2)
                .map(|p| Vec2::new(p[0], p[1]))
                .collect();
            start += n;
            polygon
        })
        .collect()
}

/// Each loose ball at recorded step `step` ([`BALL_XY`], [`BALL_ANGLE`], [`BALL_RADII`]): its
/// centre, angle and radius; nothing when the step was not recorded.
pub fn balls(trace: &Trace, step: usize) -> Vec<(Vec2, f64, f64)> {
    let (Some(xy), Some(angles)) = (trace.at(BALL_XY.name, step), trace.at(BALL_ANGLE.name, step)) else {
        return Vec::new();
    };
    xy.chunks(2)
        .zip(angles)
        .zip(trace.fixed_values(BALL_RADII.name))
        .map(|((p, &angle), &radius)| (Vec2::new(p[0], p[1]), angle, radius))
        .collect()
}
