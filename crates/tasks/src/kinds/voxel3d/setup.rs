//! What every 3D task does before and during its episodes: the robot behind a `dyn Robot`, its
//! body grid, sensors and brain (a template brain gets seeded random parameters), and every
//! voxel's readings each step.

use super::grid::BodyGrid3;
use super::robot::Voxel3dRobot;
use super::sensors::{Sensor3, VoxelSense};
use super::worlds::Worlds;
use crate::agent::Robot;
use crate::episode::EpisodeError;
use vsrlab_brain::Controller;
use vsrlab_field::FieldError;
use vsrlab_physics3d::VoxelId;

/// A 3D robot ready for an episode.
pub(crate) struct Prepared<'a> {
    /// The robot's description.
    pub robot: &'a Voxel3dRobot,
    /// Its body.
    pub grid: BodyGrid3,
    /// Its sensors, the same on every voxel.
    pub sensors: Vec<Sensor3>,
    /// Its brain, built.
    pub brain: Box<dyn Controller>,
}

/// The 3D robot behind `robot`, its body, sensors and built brain; errors name the field
/// (`robot.…`), or the task's kind (`task_kind`) for a robot of another kind.
pub(crate) fn prepare<'a>(robot: &'a dyn Robot, task_kind: &str) -> Result<Prepared<'a>, EpisodeError> {
    let robot = robot
        .description()
        .and_then(|d| d.as_any().downcast_ref::<Voxel3dRobot>())
        .ok_or_else(|| {
            EpisodeError::Field(FieldError::new(
                "task.kind",
                format!("{task_kind} runs 3D voxel robots (a body `3d:…`, or a robot file with \"voxel3d\")"),
            ))
        })?;
    let at_robot = |e: FieldError| EpisodeError::Field(e.at("robot"));
    let grid = robot.grid().map_err(at_robot)?;
    let sensors = robot.sensor_list().map_err(at_robot)?;
    let shape = robot.brain_shape().map_err(at_robot)?;
    let at_brain = |e: vsrlab_brain::BrainError| EpisodeError::Field(FieldError::from(e).at("robot.brain"));
    let spec = crate::kinds::filled_brain(&robot.brain, &shape).map_err(at_brain)?;
    let brain = spec.build(&shape).map_err(at_brain)?;
    Ok(Prepared {
        robot,
        grid,
        sensors,
        brain,
    })
}

/// Episodes a 3D task steps together in population lanes (8 with AVX-512, else 4).
pub(crate) use vsrlab_physics3d::laned_worlds::lanes;

/// The robots of a batch ready for one laned world: `None` unless every one is a 3D robot of the
/// same body grid and sensors (the caller then runs them one by one, which names any error).
pub(crate) fn prepare_batch<'a>(robots: &[&'a dyn Robot], task_kind: &str) -> Option<Vec<Prepared<'a>>> {
    let prepared = robots
        .iter()
        .map(|r| prepare(*r, task_kind))
        .collect::<Result<Vec<Prepared>, _>>()
        .ok()?;
    let first = prepared.first()?;
    let same = prepared
        .iter()
        .all(|p| p.grid == first.grid && p.sensors == first.sensors);
    same.then_some(prepared)
}

/// Every voxel's readings in lane `lane` at time `t`, voxel after voxel.
pub(crate) fn sense<W: Worlds + ?Sized>(
    world: &W,
    lane: usize,
    body: &[VoxelId],
    sensors: &[Sensor3],
    t: f64,
    readings: &mut [f64],
) {
    if sensors.is_empty() {
        return;
    }
    for (&v, out) in body.iter().zip(readings.chunks_mut(sensors.len())) {
        let sense = VoxelSense {
            time: t,
            touches_voxel: world.touches_voxel(v, lane),
            touches_floor: world.touches_floor(v, lane),
            velocity: world.velocity(v, lane),
        };
        for (r, s) in out.iter_mut().zip(sensors) {
            *r = s.read(&sense);
        }
    }
}
