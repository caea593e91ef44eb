//! Gas pressure in a ring of parts, parts that never rotate, and circles.

use std::f64::consts::PI;
use vsrlab_physics::{
    EdgeLength, PartDesc, PartHandle, Polygon, PressureRingDesc, RingHandle, SpringDesc, SpringHandle, SpringMassModel,
    Vec2, World, WorldBuilder, WorldSettings,
};

/// A ring of `n` unit squares on a circle of radius `r`, neighbours joined by springs.
fn ring(n: usize, r: f64, gravity: Vec2, length: EdgeLength) -> (World, Vec<PartHandle>, RingHandle) {
    let settings = WorldSettings {
        gravity,
        ..WorldSettings::default()
    };
    ring_in(settings, n, r, length)
}

/// [`ring`] in a world of the given settings.
fn ring_in(settings: WorldSettings, n: usize, r: f64, length: EdgeLength) -> (World, Vec<PartHandle>, RingHandle) {
    let mut b = WorldBuilder::new(settings);
    let parts: Vec<PartHandle> = (0..n)
        .map(|i| {
            let a = 2.0 * PI * i as f64 / n as f64;
            let pos = Vec2::new(r * a.cos(), r * a.sin() + r + 1.0);
            b.add_part(
                PartDesc::new(pos, Polygon::square(Vec2::ZERO, 1.0))
                    .density(2500.0)
                    .friction(1.0)
                    .fixed_rotation(),
            )
        })
        .collect();
    let rest = 2.0 * r * (PI / n as f64).sin();
    let springs: Vec<SpringHandle> = (0..n)
        .map(|i| {
            b.add_spring(SpringDesc {
                part_a: parts[i],
                anchor_a: Vec2::ZERO,
                part_b: parts[(i + 1) % n],
                anchor_b: Vec2::ZERO,
                rest_length: rest,
                frequency: 8.0,
                damping_ratio: 0.3,
                mass_model: SpringMassModel::ReducedMass,
                collide_connected: false,
            })
        })
        .collect();
    b.add_static_polygon(Polygon::rect(Vec2::new(0.0, -1.0), 100.0, 1.0), 1.0, 0.0);
    let h = b.add_pressure_ring(PressureRingDesc {
        parts: parts.clone(),
        springs: if length == EdgeLength::SpringRest {
            springs
        } else {
            Vec::new()
        },
        length,
        pressure: 0.0,
    });
    (b.build().unwrap(), parts, h)
}

fn centre(w: &World, parts: &[PartHandle]) -> Vec2 {
    parts.iter().fold(Vec2::ZERO, |a, &p| a + w.part_position(p)) / parts.len() as f64
}

#[test]
fn ring_area_is_the_inscribed_polygon_and_grows_with_pressure() {
    let (n, r) = (15, 7.5);
    let (mut w, _, h) = ring(n, r, Vec2::ZERO, EdgeLength::Actual);
    let inscribed = 0.5 * n as f64 * r * r * (2.0 * PI / n as f64).sin();
    assert!((w.ring_area(h) - inscribed).abs() < 1e-9);
    let mut areas = Vec::new();
    for p in [0.0, 20_000.0, 40_000.0] {
        w.set_ring_pressure(h, p);
        assert_eq!(w.ring_pressure(h), p);
        for _ in 0..300 {
            w.step().unwrap();
        }
        areas.push(w.ring_area(h));
    }
    assert!((areas[0] - inscribed).abs() < 1e-6, "no pressure, no change: {areas:?}");
    assert!(areas[1] > areas[0] * 1.02 && areas[2] > areas[1] * 1.02, "{areas:?}");
}

#[test]
fn sequential_sub_steps_hold_the_pressure_of_the_step_once() {
    // the pressure force is computed once per step and held over the sub-steps, as external
    // forces are: two sub-steps inflate the ring as far as one (not as twice the pressure would)
    let area = |sequential_substeps: u32, pressure: f64| {
        let settings = WorldSettings {
            gravity: Vec2::ZERO,
            solver: vsrlab_physics::Solver::SequentialImpulses,
            sequential_substeps,
            ..WorldSettings::default()
        };
        let (mut w, _, h) = ring_in(settings, 15, 7.5, EdgeLength::Actual);
        w.set_ring_pressure(h, pressure);
        for _ in 0..300 {
            w.step().unwrap();
        }
        w.ring_area(h)
    };
    let (one, two, double) = (area(1, 20_000.0), area(2, 20_000.0), area(1, 40_000.0));
    assert!((two - one).abs() < 0.005 * one, "{one} {two}");
    assert!(double > one * 1.02, "{one} {double}");
}

#[test]
fn pressure_forces_sum_to_zero_so_the_ring_does_not_drift() {
    for length in [EdgeLength::Actual, EdgeLength::SpringRest] {
        let (mut w, parts, h) = ring(10, 5.0, Vec2::ZERO, length);
        let start = centre(&w, &parts);
        w.set_ring_pressure(h, 30_000.0);
        for _ in 0..600 {
            w.step().unwrap();
        }
        let moved = (centre(&w, &parts) - start).length();
        assert!(moved < 1e-6, "{length:?}: centre moved {moved}");
        for &p in &parts {
            assert_eq!(w.part_angle(p), 0.0, "fixed rotation");
        }
    }
}

#[test]
fn spring_rest_variant_pushes_with_the_target_length() {
    // every spring's target set to half its length: the springs pull the same in all three runs;
    // the target-length variant's pressure pushes half as hard as the actual-length one
    let outward_speed = |length: EdgeLength, pressure: f64| {
        let (mut w, parts, h) = ring(12, 6.0, Vec2::ZERO, length);
        let rest = 2.0 * 6.0 * (PI / 12.0).sin();
        for i in 0..12 {
            w.set_spring_rest_length(SpringHandle(i), rest / 2.0);
        }
        w.set_ring_pressure(h, pressure);
        w.step().unwrap();
        let c = centre(&w, &parts);
        w.part_velocity(parts[0])
            .dot((w.part_position(parts[0]) - c).normalize_or_zero())
    };
    let springs_only = outward_speed(EdgeLength::Actual, 0.0);
    let actual = outward_speed(EdgeLength::Actual, 20_000.0) - springs_only;
    let target = outward_speed(EdgeLength::SpringRest, 20_000.0) - springs_only;
    assert!(actual > 0.0, "pressure pushes outward: {actual}");
    assert!(
        (target / actual - 0.5).abs() < 0.01,
        "target {target} vs actual {actual}"
    );
}

#[test]
fn a_ball_rests_on_the_ground_and_rolls_down_a_slope() {
    let mut b = WorldBuilder::new(WorldSettings::default());
    let ball = b.add_part(PartDesc::new(Vec2::new(0.0, 1.0), Polygon::circle(Vec2::ZERO, 1.0).unwrap()).friction(1.0));
    b.add_static_polygon(Polygon::rect(Vec2::new(0.0, -1.0), 50.0, 1.0), 1.0, 0.0);
    let mut w = b.build().unwrap();
    for _ in 0..300 {
        w.step().unwrap();
    }
    let y = w.part_position(ball).y;
    assert!((y - 1.0).abs() < 0.02, "rests at its radius, y = {y}");
    assert!(w.part_velocity(ball).length() < 1e-3);

    // a slope of 20°: a rolling ball turns clockwise as it goes down to the left... set up as a
    // wedge rising to the right
    let mut b = WorldBuilder::new(WorldSettings::default());
    let slope = 20f64.to_radians();
    let start = Vec2::new(5.0 * slope.cos(), 5.0 * slope.sin()) + Vec2::new(-slope.sin(), slope.cos()) * 1.0;
    let ball = b.add_part(PartDesc::new(start, Polygon::circle(Vec2::ZERO, 1.0).unwrap()).friction(1.0));
    let wedge = Polygon::convex(&[
        Vec2::new(-20.0 * slope.cos(), -20.0 * slope.sin()),
        Vec2::new(20.0 * slope.cos(), -20.0 * slope.sin()),
        Vec2::new(20.0 * slope.cos(), 20.0 * slope.sin()),
    ])
    .unwrap();
    b.add_static_polygon(wedge, 1.0, 0.0);
    let mut w = b.build().unwrap();
    for _ in 0..60 {
        w.step().unwrap();
    }
    let v = w.part_velocity(ball);
    let spin = w.part_angular_velocity(ball);
    assert!(v.x < -0.5, "rolls down to the left: {v:?}");
    // rolling without slipping: v = −ω·r along the slope, so ω > 0 when moving left
    let along = v.length();
    assert!((spin - along).abs() < 0.1 * along, "ω {spin} vs |v| {along}");
}

#[test]
fn bad_rings_and_circular_statics_are_rejected() {
    let mut b = WorldBuilder::new(WorldSettings::default());
    let p: Vec<PartHandle> = (0..2)
        .map(|i| {
            b.add_part(PartDesc::new(
                Vec2::new(i as f64 * 2.0, 0.0),
                Polygon::square(Vec2::ZERO, 1.0),
            ))
        })
        .collect();
    b.add_pressure_ring(PressureRingDesc {
        parts: p,
        length: EdgeLength::Actual,
        springs: Vec::new(),
        pressure: 1.0,
    });
    let err = b.build().unwrap_err().to_string();
    assert!(err.contains("pressure ring 0") && err.contains("at least 3"), "{err}");

    let mut b = WorldBuilder::new(WorldSettings::default());
    b.add_static_polygon(Polygon::circle(Vec2::ZERO, 1.0).unwrap(), 1.0, 0.0);
    let err = b.build().unwrap_err().to_string();
    assert!(err.contains("static polygon 0"), "{err}");
}
