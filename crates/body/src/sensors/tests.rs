use super::node::{Context, Node};
use super::*;
use crate::params::VoxelParams;
use vsrlab_physics::{Polygon, Vec2, WorldBuilder, WorldSettings};

fn state(area_ratio: f64, velocity: Vec2, angle: f64, touching: bool, center: Vec2) -> VoxelState {
    VoxelState {
        polygon: [Vec2::ZERO; 4],
        area_ratio,
        center,
        velocity,
        angle,
        touching,
    }
}

fn empty_world() -> World {
    WorldBuilder::new(WorldSettings::default()).build().unwrap()
}

fn read(spec: &SensorSpec, s: &VoxelState, world: &World, t: f64, node: &mut Node) -> Vec<f64> {
    let mut out = vec![0.0; spec.dimension()];
    node.sense(&Context { world, state: s, t }, &mut out);
    out
}

#[test]
fn soft_normalized_area_matches_published_examples() {
    let spec = SensorSpec::named("a").unwrap();
    let w = empty_world();
    let mut node = Node::build(&spec, (0.0, 0.0), 0);
    for (area, expected) in [(0.8, 0.168), (1.0, 0.5), (1.2, 0.832)] {
        let v = read(&spec, &state(area, Vec2::ZERO, 0.0, false, Vec2::ZERO), &w, 0.0, &mut node)[0];
        assert!((v - expected).abs() < 5e-4, "{area}: {v}");
    }
}

#[test]
fn average_uses_an_inclusive_time_window() {
    let spec = SensorSpec::named("t").unwrap(); // Average(Touch, 0.25)
    let w = empty_world();
    let mut node = Node::build(&spec, (0.0, 0.0), 0);
    let dt = 1.0 / 60.0;
    let mut t = 0.0;
    let mut last = 0.0;
    for k in 0..60 {
        t += dt;
        // touching for the last 8 steps only
        let touching = k >= 52;
        last = read(&spec, &state(1.0, Vec2::ZERO, 0.0, touching, Vec2::ZERO), &w, t, &mut node)[0];
    }
    // the 0.25 s window holds 16 samples at 60 Hz, 8 of which touch
    assert!((last - 0.5).abs() < 1e-9, "{last}");
}

#[test]
fn trend_of_a_ramp_is_its_slope() {
    let spec = SensorSpec::Trend {
        window: 0.5,
        of: Box::new(SensorSpec::Velocity { rotated: false, vmax: 4.0, axes: Axes::X }),
    };
    let w = empty_world();
    let mut node = Node::build(&spec, (0.0, 0.0), 0);
    let mut t = 0.0;
    let mut out = 0.0;
    for _ in 0..90 {
        t += 1.0 / 60.0;
        out = read(&spec, &state(1.0, Vec2::new(3.0 * t, 0.0), 0.0, false, Vec2::ZERO), &w, t, &mut node)[0];
    }
    assert!((out - 3.0).abs() < 1e-9, "{out}");
}

#[test]
fn rotated_velocity_is_in_the_voxel_frame() {
    let spec = SensorSpec::Velocity { rotated: true, vmax: 8.0, axes: Axes::Xy };
    let w = empty_world();
    let mut node = Node::build(&spec, (0.0, 0.0), 0);
    // voxel turned by +90°: world +y is the voxel's +x
    let v = read(&spec, &state(1.0, Vec2::new(0.0, 2.0), std::f64::consts::FRAC_PI_2, false, Vec2::ZERO), &w, 0.0, &mut node);
    assert!((v[0] - 2.0).abs() < 1e-12 && v[1].abs() < 1e-12, "{v:?}");
}

#[test]
fn lidar_measures_the_distance_to_the_ground() {
    let mut b = WorldBuilder::new(WorldSettings::default());
    b.add_static_polygon(Polygon::rect(Vec2::new(0.0, -5.0), 100.0, 5.0), 0.2, 0.0);
    let w = b.build().unwrap();
    // bottom voxel: south side, rays from 5π/4 to 7π/4; the middle one points straight down
    let spec = SensorSpec::Lidar { range: 10.0, rays: 3 };
    let mut node = Node::build(&spec, (0.5, 0.0), 0);
    let d = read(&spec, &state(1.0, Vec2::ZERO, 0.0, false, Vec2::new(0.0, 4.0)), &w, 0.0, &mut node);
    assert!((d[1] - 4.0).abs() < 1e-9, "{d:?}");
    assert!((d[0] - 4.0 * std::f64::consts::SQRT_2).abs() < 1e-9, "{d:?}");
    // out of range: the range itself
    let far = read(&spec, &state(1.0, Vec2::ZERO, 0.0, false, Vec2::new(0.0, 40.0)), &w, 0.0, &mut node);
    assert_eq!(far, vec![10.0; 3]);
}

#[test]
fn noise_streams_are_independent_per_voxel_and_reproducible() {
    let m = Morphology::named("box-2x1").unwrap();
    let cfg = SensorConfig::parse("uniform-a-0.1").unwrap();
    let mut b = WorldBuilder::new(WorldSettings::default());
    let vsr = Vsr::assemble(&mut b, &m, &VoxelParams::default(), Vec2::ZERO, 1);
    let w = b.build().unwrap();
    let states: Vec<VoxelState> = (0..2).map(|i| vsr.voxel_state(&w, i)).collect();
    let run = |seed| {
        let mut suite = SensorSuite::new(&cfg, &m, seed).unwrap();
        let mut out = vec![0.0; 2];
        suite.sense(&w, &vsr, &states, 0.1, &mut out);
        out
    };
    let a = run(7);
    assert_ne!(a[0], a[1], "two voxels in the same state must get different noise");
    assert_eq!(a, run(7));
    assert_ne!(a, run(8));
}

#[test]
fn placements_put_the_right_sensors_on_the_right_voxels() {
    let m = Morphology::named("box-3x2").unwrap();
    let uniform = SensorConfig::parse("uniform-a+vxy+t-0").unwrap().specs(&m).unwrap();
    assert!(uniform.iter().all(|v| v.len() == 3));
    let spined = SensorConfig::parse("spinedTouchSighted-t-f-0").unwrap().specs(&m).unwrap();
    // grid order: bottom row (y = 0) first; voxel 0 = (0,0) bottom-left
    assert_eq!(spined[0].len(), 2); // a, t
    assert_eq!(spined[2].len(), 3); // a, t, l5 (rightmost column)
    assert_eq!(spined[5].len(), 4); // top-right: a, vxy, cpg, l5
    assert_eq!(spined[5][2], SensorSpec::named("cpg").unwrap());
    let empty = SensorConfig::parse("empty").unwrap().specs(&m).unwrap();
    assert!(empty.iter().all(Vec::is_empty));
    let per_voxel = SensorConfig::PerVoxel(vec![vec!["a".into()]; 6]);
    assert_eq!(SensorSuite::new(&per_voxel, &m, 0).unwrap().total_readings(), 6);
}

#[test]
fn bad_configs_name_the_token() {
    let e = SensorConfig::parse("uniform-a+zz-0").unwrap_err();
    assert!(e.to_string().contains("'zz'"), "{e}");
    let e = SensorConfig::parse("uniform-a-x").unwrap_err();
    assert!(e.to_string().contains("'x'"), "{e}");
    assert!(SensorConfig::parse("everywhere").is_err());
    assert!(SensorConfig::parse("spinedTouch-q-f-0").unwrap_err().to_string().contains("'q'"));
    let m = Morphology::named("box-2x1").unwrap();
    let short = SensorConfig::PerVoxel(vec![vec!["a".into()]]);
    assert_eq!(
        SensorSuite::new(&short, &m, 0).unwrap_err(),
        SensorError::WrongVoxelCount { expected: 2, got: 1 }
    );
}

#[test]
fn config_serde_accepts_strings_and_lists() {
    let a: SensorConfig = serde_json::from_str("\"uniform-a-0\"").unwrap();
    assert_eq!(a, SensorConfig::Named("uniform-a-0".into()));
    let b: SensorConfig = serde_json::from_str("[[\"a\",\"t\"],[]]").unwrap();
    assert_eq!(b, SensorConfig::PerVoxel(vec![vec!["a".into(), "t".into()], vec![]]));
}
