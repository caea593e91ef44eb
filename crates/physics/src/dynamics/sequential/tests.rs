//! Behaviour of the sequential-impulse solver on small scenes with known answers.

use crate::dynamics::settings::{Solver, WorldSettings};
use crate::{PartDesc, Polygon, SpringDesc, Vec2, World, WorldBuilder};

fn settings() -> WorldSettings {
    WorldSettings {
        solver: Solver::SequentialImpulses,
        ..WorldSettings::default()
    }
}

/// Ground: a static box whose top is at y = 5.
fn with_ground(b: &mut WorldBuilder) {
    let ground = Polygon::rect(Vec2::new(0.0, -20.0), 50.0, 25.0);
    b.add_static_polygon(ground, 0.2, 0.0);
}

fn square(centre: Vec2, side: f64) -> PartDesc {
    PartDesc::new(centre, Polygon::square(Vec2::ZERO, side))
        .density(0.25)
        .friction(10.0)
        .restitution(0.1)
        .damping(0.1, 0.1)
}

/// A spring of rest length `rest` between the centres of parts `a` and `c` (8 Hz, ζ = 0.3).
fn centre_spring(a: crate::PartHandle, c: crate::PartHandle, rest: f64) -> SpringDesc {
    SpringDesc {
        part_a: a,
        part_b: c,
        anchor_a: Vec2::ZERO,
        anchor_b: Vec2::ZERO,
        rest_length: rest,
        frequency: 8.0,
        damping_ratio: 0.3,
        mass_model: crate::SpringMassModel::EffectiveMass,
        collide_connected: false,
    }
}

fn run(world: &mut World, steps: usize) {
    for _ in 0..steps {
        world.step().expect("finite");
    }
}

#[test]
fn a_free_square_falls_one_step_of_gravity() {
    let mut b = WorldBuilder::new(settings());
    let h = b.add_part(square(Vec2::new(0.0, 10.0), 1.2));
    let mut w = b.build().unwrap();
    w.step().unwrap();
    let dt = 1.0 / 60.0;
    // v = g·dt (damped once), then x += v·dt
    let expected = 10.0 - 9.8 * dt * (1.0 - 0.1 * dt) * dt;
    assert!((w.part_position(h).y - expected).abs() < 1e-12);
}

#[test]
fn a_square_comes_to_rest_on_the_ground_overlapping_by_about_the_slop() {
    let mut b = WorldBuilder::new(settings());
    with_ground(&mut b);
    let h = b.add_part(square(Vec2::new(0.0, 6.0), 1.2));
    let mut w = b.build().unwrap();
    run(&mut w, 180);
    let bottom = w.part_position(h).y - 0.6;
    let overlap = 5.0 - bottom;
    assert!(overlap > 0.0 && overlap < 3.0 * 0.005, "overlap {overlap}");
    assert!(w.part_velocity(h).length() < 0.05, "{:?}", w.part_velocity(h));
    assert!(w.part_touching(h));
}

#[test]
fn welded_squares_stay_together_through_a_landing() {
    let mut b = WorldBuilder::new(settings());
    with_ground(&mut b);
    let l = b.add_part(square(Vec2::new(0.0, 8.0), 1.2));
    let r = b.add_part(square(Vec2::new(1.2, 8.5), 1.2));
    b.weld(l, r);
    let mut w = b.build().unwrap();
    assert!(!w.same_body(l, r), "welded parts stay bodies of their own");
    let start = w.part_position(r) - w.part_position(l);
    let gap = |w: &World| (w.part_position(r) - w.part_position(l)) - rotated(start, w.part_angle(l));
    let mut largest: f64 = 0.0;
    for _ in 0..240 {
        w.step().unwrap();
        // continuous collision stops one part at its time of impact and not its partner, as
        // dyn4j does; the weld pulls them together again in the next steps
        largest = largest.max(gap(&w).length());
        assert!((w.part_angle(r) - w.part_angle(l)).abs() < 0.05);
    }
    assert!(largest < 0.2, "largest weld gap {largest}");
    assert!(gap(&w).length() < 0.01, "weld gap at rest {:?}", gap(&w));
    assert!(w.part_touching(l) || w.part_touching(r));
}

#[test]
fn continuous_collision_stops_a_fast_square_at_the_ground() {
    for continuous_collision in [true, false] {
        let mut b = WorldBuilder::new(WorldSettings {
            continuous_collision,
            ..settings()
        });
        b.add_static_polygon(Polygon::rect(Vec2::new(0.0, 4.9), 50.0, 0.1), 0.2, 0.0);
        let h = b.add_part(square(Vec2::new(0.0, 7.0), 0.3));
        let mut w = b.build().unwrap();
        // 110 units/s: 1.8 per step, far more than the ground is thick (0.2)
        w.apply_force(h, Vec2::new(0.0, -110.0 * 0.0225 * 60.0));
        run(&mut w, 6);
        let y = w.part_position(h).y;
        if continuous_collision {
            assert!(y > 4.9, "stopped on the ground: y = {y}");
        } else {
            assert!(y < 4.8, "without it the square passes through: y = {y}");
        }
    }
}

fn rotated(v: Vec2, angle: f64) -> Vec2 {
    crate::Rot::new(angle).apply(v)
}

#[test]
fn a_stretched_spring_pulls_its_parts_back_to_rest_length() {
    let mut b = WorldBuilder::new(WorldSettings {
        gravity: Vec2::ZERO,
        ..settings()
    });
    let a = b.add_part(square(Vec2::new(0.0, 0.0), 1.0));
    let c = b.add_part(square(Vec2::new(3.0, 0.0), 1.0));
    b.add_spring(centre_spring(a, c, 2.0));
    let mut w = b.build().unwrap();
    run(&mut w, 300);
    let d = (w.part_position(c) - w.part_position(a)).length();
    assert!((d - 2.0).abs() < 1e-3, "distance {d}");
}

#[test]
fn the_same_world_stepped_twice_gives_the_same_bits() {
    let make = || {
        let mut b = WorldBuilder::new(settings());
        with_ground(&mut b);
        let parts: Vec<_> = (0..4)
            .map(|i| b.add_part(square(Vec2::new(1.25 * i as f64, 6.0 + 0.3 * i as f64), 1.2)))
            .collect();
        b.weld(parts[0], parts[1]);
        b.weld(parts[2], parts[3]);
        (b.build().unwrap(), parts)
    };
    let (mut w1, p1) = make();
    let (mut w2, p2) = make();
    run(&mut w1, 200);
    run(&mut w2, 200);
    for (a, b) in p1.iter().zip(&p2) {
        assert_eq!(w1.part_position(*a), w2.part_position(*b));
        assert_eq!(w1.part_angle(*a), w2.part_angle(*b));
    }
}

/// Two squares joined by a spring, resting on the ground, in a world of dyn4j `version`.
fn resting_pair(version: crate::Dyn4jVersion) -> (World, [crate::PartHandle; 2], crate::SpringHandle) {
    let mut b = WorldBuilder::new(WorldSettings {
        dyn4j: Some(version),
        ..settings()
    });
    with_ground(&mut b);
    let a = b.add_part(square(Vec2::new(0.0, 5.6), 1.2));
    let c = b.add_part(square(Vec2::new(2.0, 5.6), 1.2));
    let spring = b.add_spring(centre_spring(a, c, 2.0));
    (b.build().unwrap(), [a, c], spring)
}

#[test]
fn dyn4j_4_puts_an_island_at_rest_and_a_new_rest_length_wakes_it() {
    use crate::Dyn4jVersion::{V3_3_0, V4_2_1};
    let (mut w, parts, spring) = resting_pair(V4_2_1);
    run(&mut w, 120);
    // asleep: velocities exactly 0, and the island stays where it is, gravity or not
    let still: Vec<Vec2> = parts.iter().map(|&p| w.part_position(p)).collect();
    for &p in &parts {
        assert_eq!((w.part_velocity(p), w.part_angular_velocity(p)), (Vec2::ZERO, 0.0));
    }
    // the same rest length again does not wake it (dyn4j's setRestDistance)
    w.set_spring_rest_length(spring, 2.0);
    run(&mut w, 60);
    assert_eq!(parts.map(|p| w.part_position(p)).to_vec(), still);
    // a new rest length does: the spring pulls the parts together again
    w.set_spring_rest_length(spring, 1.5);
    run(&mut w, 1);
    assert!(w.part_velocity(parts[0]).x > 0.0 && w.part_velocity(parts[1]).x < 0.0);
    run(&mut w, 300);
    let d = (w.part_position(parts[1]) - w.part_position(parts[0])).length();
    assert!((d - 1.5).abs() < 0.05, "distance {d}");
    // dyn4j 3.3.0 worlds never sleep: their resting parts keep their tiny speeds
    let (mut old, parts, _) = resting_pair(V3_3_0);
    run(&mut old, 120);
    let moving = parts
        .iter()
        .any(|&p| old.part_velocity(p) != Vec2::ZERO || old.part_angular_velocity(p) != 0.0);
    assert!(moving, "a 3.3.0 world has no at-rest detection");
}

#[test]
fn two_sequential_substeps_fall_three_quarters_of_one_step() {
    // semi-implicit Euler over two halves h: x drops g·h² then 2·g·h², 3/4 of g·dt² in one step
    let no_damping = |p: PartDesc| p.damping(0.0, 0.0);
    let mut fall = [0.0; 2];
    for (n, f) in [1, 2].into_iter().zip(&mut fall) {
        let mut b = WorldBuilder::new(WorldSettings {
            sequential_substeps: n,
            ..settings()
        });
        let h = b.add_part(no_damping(square(Vec2::new(0.0, 10.0), 1.2)));
        let mut w = b.build().unwrap();
        w.step().unwrap();
        *f = 10.0 - w.part_position(h).y;
        assert_eq!(w.step_count(), 1);
        assert!((w.time() - 1.0 / 60.0).abs() < 1e-15);
    }
    let dt = 1.0 / 60.0;
    assert!((fall[0] - 9.8 * dt * dt).abs() < 1e-12, "{fall:?}");
    assert!((fall[1] - 0.75 * 9.8 * dt * dt).abs() < 1e-12, "{fall:?}");
}

#[test]
fn sub_stepped_and_coloured_sweeps_land_welded_squares_and_change_the_motion() {
    let land = |s: WorldSettings| {
        let mut b = WorldBuilder::new(s);
        with_ground(&mut b);
        // a row of four squares welded in turn, the two ends joined by a spring
        let row: Vec<_> = (0..4)
            .map(|i| b.add_part(square(Vec2::new(1.2 * f64::from(i), 8.0), 1.2)))
            .collect();
        for pair in row.windows(2) {
            b.weld(pair[0], pair[1]);
        }
        b.add_spring(centre_spring(row[0], row[3], 3.4));
        let mut w = b.build().unwrap();
        run(&mut w, 240);
        for &p in &row {
            let bottom = w.part_position(p).y - 0.6;
            assert!((5.0 - bottom).abs() < 0.05, "bottom {bottom}");
            assert!(w.part_velocity(p).length() < 0.05);
        }
        w.part_position(row[3])
    };
    let plain = land(settings());
    let sub = land(WorldSettings {
        sequential_substeps: 3,
        ..settings()
    });
    let coloured = land(WorldSettings {
        coloured_joints: true,
        ..settings()
    });
    // the variants are other models: their trajectories part from dyn4j's order
    assert_ne!(plain, sub);
    assert_ne!(plain, coloured);
}

#[test]
fn merged_welds_make_one_body_that_lands_and_rests() {
    let mut b = WorldBuilder::new(WorldSettings {
        merge_welds: true,
        ..settings()
    });
    with_ground(&mut b);
    let l = b.add_part(square(Vec2::new(0.0, 8.0), 1.2));
    let r = b.add_part(square(Vec2::new(1.2, 8.0), 1.2));
    let free = b.add_part(square(Vec2::new(4.0, 8.0), 1.2));
    b.weld(l, r);
    b.add_spring(centre_spring(r, free, 2.8));
    let mut w = b.build().unwrap();
    assert!(w.same_body(l, r) && !w.same_body(r, free));
    assert_eq!(w.body_count(), 2);
    let start = w.part_position(r) - w.part_position(l);
    run(&mut w, 240);
    // one rigid body: the parts keep their offset exactly (up to the rotation)
    let gap = (w.part_position(r) - w.part_position(l)) - rotated(start, w.part_angle(l));
    assert!(gap.length() < 1e-9, "{gap:?}");
    for p in [l, r, free] {
        assert!((5.0 - (w.part_position(p).y - 0.6)).abs() < 0.05);
        assert!(w.part_velocity(p).length() < 0.05);
    }
}
