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

/// Every voxel's readings in lane `lane` at time `t`, voxel after voxel. A CPG reads the clock
/// every voxel shares, so it is computed for the first voxel and copied to the others (the
/// same value: one sine per step instead of one per voxel).
pub(crate) fn sense<W: Worlds + ?Sized>(
    world: &W,
    lane: usize,
    body: &[VoxelId],
    sensors: &[Sensor3],
    t: f64,
    readings: &mut [f64],
) {
    if sensors.is_empty() || body.is_empty() {
        return;
    }
    let n = sensors.len();
    let (first, rest) = readings.split_at_mut(n);
    let read_voxel = |v: VoxelId, out: &mut [f64], clock: Option<&[f64]>| {
        let sense = VoxelSense {
            time: t,
            touches_voxel: world.touches_voxel(v, lane),
            touches_floor: world.touches_floor(v, lane),
            velocity: world.velocity(v, lane),
        };
        for (k, (r, s)) in out.iter_mut().zip(sensors).enumerate() {
            *r = match (s, clock) {
                (Sensor3::Cpg(_), Some(clock)) => clock[k],
                _ => s.read(&sense),
            };
        }
    };
    read_voxel(body[0], first, None);
    for (&v, out) in body[1..].iter().zip(rest.chunks_mut(n)) {
        read_voxel(v, out, Some(&*first));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_physics3d::{Material, World, WorldSettings};

    /// Three unlinked voxels pushed along z by different forces, a few steps on.
    fn falling_world() -> (World, Vec<VoxelId>) {
        let mut world = World::new(WorldSettings {
            voxel_size: 0.01,
            gravity: -9.81,
            floor: true,
            collisions: true,
        })
        .unwrap();
        let m = world.add_material(Material::affordance()).unwrap();
        let body: Vec<VoxelId> = [[0, 0, 0], [3, 0, 2], [6, 0, 5]]
            .into_iter()
            .map(|c| world.add_voxel(m, c).unwrap())
            .collect();
        for (i, &v) in body.iter().enumerate() {
            world.set_external(v, glam::DVec3::new(0.0, 0.0, 0.01 * i as f64), glam::DVec3::ZERO);
        }
        let dt = world.recommended_time_step();
        while world.time() < 0.05 {
            world.step(dt).unwrap();
        }
        (world, body)
    }

    #[test]
    fn every_voxel_reads_what_its_sensors_read_the_clock_shared() {
        let (world, body) = falling_world();
        let sensors = Sensor3::parse_list("cpg:2,vz,cpg,floor,touch").unwrap();
        let t = 0.3;
        let mut readings = vec![f64::NAN; body.len() * sensors.len()];
        sense(&world, 0, &body, &sensors, t, &mut readings);
        for (i, &v) in body.iter().enumerate() {
            let alone = VoxelSense {
                time: t,
                touches_voxel: world.touches_voxel(v),
                touches_floor: world.touches_floor(v),
                velocity: world.velocity(v),
            };
            for (k, s) in sensors.iter().enumerate() {
                let got = readings[i * sensors.len() + k];
                assert_eq!(got.to_bits(), s.read(&alone).to_bits(), "voxel {i}, sensor {k}");
            }
        }
        assert_ne!(readings[0], readings[2], "the two clocks have their own frequencies");
        assert_ne!(readings[1], readings[1 + 5], "each voxel reads its own velocity");
    }
}
