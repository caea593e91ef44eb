//! Tests of the whole suite on assembled robots.

use super::*;
use crate::params::VoxelParams;
use crate::Vsr;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
use vsrlab_physics::{Polygon, Vec2, WorldBuilder, WorldSettings};

/// Counts allocations per thread, to check that sensing does not allocate.
mod counting {
    use std::alloc::{GlobalAlloc, Layout, System};
    use std::cell::Cell;

    thread_local! {
        static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
    }

    pub struct Counting;

    // SAFETY: forwards every call to the system allocator unchanged; only counts.
    unsafe impl GlobalAlloc for Counting {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
            System.alloc(layout)
        }
        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            System.dealloc(ptr, layout)
        }
        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
            System.realloc(ptr, layout, new_size)
        }
    }

    #[global_allocator]
    static GLOBAL: Counting = Counting;

    /// Allocations made by this thread so far.
    pub fn allocations() -> usize {
        ALLOCATIONS.with(Cell::get)
    }
}

/// A robot standing on flat ground (top surface y = 0), and its world.
struct Scene {
    body: Morphology,
    vsr: Vsr,
    world: World,
}

impl Scene {
    fn new(body: &str, lift: f64) -> Scene {
        let body = Morphology::parse(body).unwrap();
        let mut b = WorldBuilder::new(WorldSettings::default());
        b.add_static_polygon(Polygon::rect(Vec2::new(0.0, -5.0), 200.0, 5.0), 1.0, 0.0);
        let vsr = Vsr::assemble(&mut b, &body, &VoxelParams::default(), Vec2::new(0.0, lift), 1);
        let world = b.build().unwrap();
        Scene { body, vsr, world }
    }

    fn states(&self) -> Vec<VoxelState> {
        (0..self.vsr.voxel_count())
            .map(|i| self.vsr.voxel_state(&self.world, i))
            .collect()
    }

    fn suite(&self, config: &str, seed: u64) -> SensorSuite {
        SensorSuite::new(&SensorConfig::parse(config).unwrap(), &self.body, seed).unwrap()
    }

    /// Readings at times dt, 2 dt, … for `steps` steps, stepping the world in between.
    fn run(&mut self, suite: &mut SensorSuite, steps: usize) -> Vec<Vec<f64>> {
        let mut out = vec![0.0; suite.total_readings()];
        let mut all = Vec::new();
        for k in 1..=steps {
            self.world.step().unwrap();
            let states = self.states();
            suite.sense(&self.world, &states, k as f64 * DEFAULT_TIME_STEP, &mut out);
            all.push(out.clone());
        }
        all
    }
}

#[test]
fn readings_are_laid_out_voxel_by_voxel() {
    let scene = Scene::new("biped-4x3", 0.0);
    let suite = scene.suite("spinedTouchSighted-t-f-0", 0);
    // bottom voxels: a, t (2); middle: a (1), rightmost middle: a + l5 (6); top: a, vxy (3),
    // top-right: a, vxy, cpg, l5 (9)
    let per_voxel: Vec<usize> = (0..10).map(|v| suite.readings_per_voxel(v)).collect();
    assert_eq!(per_voxel, vec![2, 7, 1, 1, 1, 6, 3, 3, 3, 9]);
    assert_eq!(suite.total_readings(), per_voxel.iter().sum::<usize>());
    assert_eq!(suite.readings_range(1), 2..9);
    assert_eq!(suite.domains(9), vec![(0.0, 1.0); 9]);
    let uniform = scene.suite("uniform-a+vxy+t-0.01", 0);
    assert_eq!(uniform.readings_per_voxel(3), 4);
    assert_eq!(uniform.total_readings(), 40);
    assert_eq!(uniform.specs(0).len(), 3);
}

#[test]
fn a_resting_robot_reads_rest_values() {
    let mut scene = Scene::new("box-2x1", 0.0);
    let mut suite = scene.suite("uniform-a+t+vxy+px+py+m+cpg-0", 0);
    let readings = scene.run(&mut suite, 30);
    let last = readings.last().unwrap();
    for v in 0..2 {
        let r = &last[suite.readings_range(v)];
        assert_eq!(r.len(), 8);
        assert!((r[0] - 0.5).abs() < 0.05, "a ≈ 0.5 at rest: {r:?}");
        assert_eq!(r[1], 1.0, "touching the ground for the whole window: {r:?}");
        assert!(
            (r[2] - 0.5).abs() < 0.05 && (r[3] - 0.5).abs() < 0.05,
            "vxy ≈ 0.5 at rest: {r:?}"
        );
        assert_eq!((r[4], r[5], r[6]), (v as f64, 0.5, 0.0), "px, py (H = 1), m");
        let cpg = ((-std::f64::consts::TAU * 30.0 * DEFAULT_TIME_STEP).sin() + 1.0) / 2.0;
        assert!((r[7] - cpg).abs() < 1e-12);
    }
}

#[test]
fn lidar_rays_report_directions_and_last_distances() {
    // a 3×1 worm resting on the ground: the rightmost voxel looks east, the others west (H = 1
    // puts every voxel at relative y = 0.5)
    let mut scene = Scene::new("worm-3x1", 0.0);
    let body = scene.body.clone();
    let specs = vec![
        vec![SensorSpec::Lidar(LidarSpec {
            range: 10.0,
            rays: 3,
            layout: RayLayout::Ends,
        })],
        vec![SensorSpec::Lidar(LidarSpec {
            range: 10.0,
            rays: 1,
            layout: RayLayout::Ends,
        })],
        vec![SensorSpec::Lidar(LidarSpec {
            range: 10.0,
            rays: 5,
            layout: RayLayout::Ends,
        })
        .normalized()],
    ];
    let mut suite = SensorSuite::from_specs(specs, &body, 0, DEFAULT_TIME_STEP).unwrap();
    let before = suite.lidar_rays(0);
    assert_eq!(before.iter().map(|r| r.distance).collect::<Vec<_>>(), vec![10.0; 3]);
    let angles: Vec<f64> = before.iter().map(|r| r.relative_angle).collect();
    assert!((angles[0] - 3.0 * FRAC_PI_4).abs() < 1e-12 && (angles[2] - 5.0 * FRAC_PI_4).abs() < 1e-12);
    assert_eq!(suite.lidar_rays(1)[0].relative_angle, FRAC_PI_4, "one-ray quirk");
    assert_eq!(suite.lidar_rays(2).len(), 5);
    let out = scene.run(&mut suite, 5).pop().unwrap();
    // the leftmost voxel's lowest ray (5π/4) meets the ground at √2 × the centre height
    let state = scene.vsr.voxel_state(&scene.world, 0);
    let height = state.center.y;
    let rays = suite.lidar_rays(0);
    assert!(
        (rays[2].distance - height * 2f64.sqrt()).abs() < 0.05 * height,
        "{rays:?}, centre at {height}"
    );
    assert_eq!(rays[0].distance, 10.0, "up-left sees nothing");
    assert_eq!(&out[0..3], &rays.iter().map(|r| r.distance).collect::<Vec<_>>()[..]);
    // normalised readings: distance / range
    let east = suite.lidar_rays(2);
    for (k, ray) in east.iter().enumerate() {
        assert!((out[4 + k] - ray.distance / 10.0).abs() < 1e-12);
    }
    suite.reset();
    assert_eq!(suite.lidar_rays(0)[2].distance, 10.0);
}

#[test]
fn rotated_velocity_is_read_in_the_voxel_frame() {
    // a voxel turned by −90° has its x axis along world −y and its y axis along world +x
    let scene = Scene::new("box-1x1", 20.0);
    let specs = vec![vec![SensorSpec::Velocity(VelocitySpec {
        rotated: true,
        vmax: 8.0,
        axes: Axes::Xy,
    })]];
    let mut suite = SensorSuite::from_specs(specs, &scene.body, 0, DEFAULT_TIME_STEP).unwrap();
    let mut state = scene.states()[0];
    state.velocity = Vec2::new(1.0, -3.0);
    state.angle = -FRAC_PI_2;
    let mut out = [0.0; 2];
    suite.sense(&scene.world, &[state], 0.1, &mut out);
    assert!((out[0] - 3.0).abs() < 1e-12 && (out[1] - 1.0).abs() < 1e-12, "{out:?}");
}

#[test]
fn noise_is_independent_between_voxels_and_reproducible() {
    let run = |seed| {
        let mut scene = Scene::new("box-2x1", 0.0);
        let mut suite = scene.suite("uniform-a+t-0.1", seed);
        scene.run(&mut suite, 20)
    };
    let a = run(7);
    // the two voxels are in mirror states: their noise-free readings agree to far below σ
    let diffs: Vec<f64> = a.iter().map(|r| r[0] - r[2]).collect();
    assert!(
        diffs.iter().filter(|d| d.abs() > 1e-3).count() > 15,
        "voxels must not share a noise stream: {diffs:?}"
    );
    // within a voxel, the two sensors have different streams too
    let noise_a: Vec<f64> = a.iter().map(|r| r[0] - 0.5).collect();
    let noise_t: Vec<f64> = a.iter().map(|r| r[1] - 1.0).collect();
    assert!(noise_a.iter().zip(&noise_t).all(|(x, y)| (x - y).abs() > 1e-9));
    assert_eq!(a, run(7), "same seed, same readings");
    assert_ne!(a, run(8), "another seed, other noise");
}

#[test]
fn reset_restarts_windows_and_noise() {
    let mut scene = Scene::new("box-2x2", 0.0);
    let world0 = scene.world.clone();
    let mut suite = scene.suite("uniform-a+vxy+t+ax-0.05", 3);
    let first = scene.run(&mut suite, 40);
    suite.reset();
    scene.world = world0;
    let second = scene.run(&mut suite, 40);
    assert_eq!(first, second);
}

#[test]
fn sensing_does_not_allocate() {
    let mut scene = Scene::new("biped-4x3", 0.0);
    let mut suite = scene.suite("uniform-a+t+r+vxy+axy+px+m+cpg+l5+l1-0.01", 1);
    let mut out = vec![0.0; suite.total_readings()];
    let mut states = scene.states();
    for k in 1..=200 {
        scene.world.step().unwrap();
        for (i, s) in states.iter_mut().enumerate() {
            *s = scene.vsr.voxel_state(&scene.world, i);
        }
        let before = counting::allocations();
        suite.sense(&scene.world, &states, k as f64 * DEFAULT_TIME_STEP, &mut out);
        assert_eq!(counting::allocations(), before, "step {k} allocated");
    }
    assert!(out.iter().all(|v| v.is_finite()));
}

#[test]
fn bad_configurations_are_errors_not_panics() {
    let body = Morphology::named("box-2x1").unwrap();
    let e = SensorSuite::new(&SensorConfig::PerVoxel(vec![vec!["a".into()]]), &body, 0).unwrap_err();
    assert_eq!(e, SensorError::WrongVoxelCount { expected: 2, got: 1 });
    let e = SensorSuite::new(
        &SensorConfig::Uniform {
            sensors: vec!["zz".into()],
            sigma: 0.0,
        },
        &body,
        0,
    )
    .unwrap_err();
    assert!(e.to_string().contains("'zz'"), "{e}");
    let e = SensorSuite::new(&SensorConfig::UniformAll { sigma: -1.0 }, &body, 0).unwrap_err();
    assert!(e.to_string().contains("'-1'"), "{e}");
    let e = SensorSuite::with_time_step(&SensorConfig::Empty, &body, 0, 0.0).unwrap_err();
    assert_eq!(e, SensorError::InvalidTimeStep(0.0));
    let specs = vec![
        vec![],
        vec![SensorSpec::AreaRatio, SensorSpec::Touch.averaged(f64::INFINITY)],
    ];
    let e = SensorSuite::from_specs(specs, &body, 0, DEFAULT_TIME_STEP).unwrap_err();
    assert!(
        matches!(
            e,
            SensorError::InvalidSensor {
                voxel: 1,
                sensor: 1,
                ..
            }
        ),
        "{e:?}"
    );
    assert!(e.to_string().starts_with("voxel 1, sensor 1: window"), "{e}");
    let empty = SensorSuite::new(&SensorConfig::Empty, &body, 0).unwrap();
    assert_eq!((empty.total_readings(), empty.readings_per_voxel(1)), (0, 0));
}
