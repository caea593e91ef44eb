//! Whole-world tests: each sets up a small scene and checks a physical expectation derived by
//! hand (the derivation is in the test's comment).

use super::*;
use proptest::prelude::*;

/// EvoGym's rigid side-spring stiffness (diagonals half).
const RIGID: f64 = 300_000_000.0 / 3.5;
/// EvoGym's soft side-spring stiffness (diagonals a quarter).
const SOFT: f64 = 300_000_000.0 / 6.0;
const CELL: f64 = 0.1;

/// The springs and quads of a `w × h` grid of square cells of side [`CELL`], lower-left corner at
/// `(x0, y0)`, EvoGym-style: shared corners, side springs, two diagonals per cell, outline sides
/// as boundary. `rigid` cells also get tight limits of 3 % on their sides.
pub(super) struct Grid {
    pub body: BodyId,
    pub points: Vec<PointId>,
    pub sides: Vec<SpringId>,
}

pub(super) fn grid(
    b: &mut MassSpringBuilder,
    (x0, y0): (f64, f64),
    (w, h): (usize, usize),
    rigid: bool,
    fixed: bool,
    watch: bool,
) -> Grid {
    let body = b.add_body(if watch {
        BodyDesc::new().watch_self_overlap()
    } else {
        BodyDesc::new()
    });
    let mut points = Vec::new();
    for j in 0..=h {
        for i in 0..=w {
            let p = PointDesc::at(x0 + i as f64 * CELL, y0 + j as f64 * CELL);
            points.push(b.add_point(if fixed { p.fixed() } else { p }));
        }
    }
    let at = |i: usize, j: usize| points[j * (w + 1) + i];
    let (side_k, diag_k) = if rigid {
        (RIGID, RIGID / 2.0)
    } else {
        (SOFT, SOFT / 4.0)
    };
    let mut horizontal = vec![];
    for j in 0..=h {
        for i in 0..w {
            horizontal.push(b.add_spring(SpringDesc::between(at(i, j), at(i + 1, j), side_k)));
        }
    }
    let mut vertical = vec![];
    for j in 0..h {
        for i in 0..=w {
            vertical.push(b.add_spring(SpringDesc::between(at(i, j), at(i, j + 1), side_k)));
        }
    }
    let mut sides = vec![];
    for j in 0..h {
        for i in 0..w {
            b.add_spring(SpringDesc::between(at(i, j), at(i + 1, j + 1), diag_k));
            b.add_spring(SpringDesc::between(at(i + 1, j), at(i, j + 1), diag_k));
            let cell_sides = [
                horizontal[j * w + i],
                vertical[j * (w + 1) + i + 1],
                horizontal[(j + 1) * w + i],
                vertical[j * (w + 1) + i],
            ];
            if rigid {
                cell_sides.iter().for_each(|&s| b.limit_length(s, 0.03));
            }
            sides.extend(cell_sides);
            let corners = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            let outline = [j == 0, i == w - 1, j == h - 1, i == 0];
            b.add_quad(QuadDesc::new(body, corners).boundary(outline));
        }
    }
    Grid { body, points, sides }
}

fn min_y(w: &MassSpringWorld, pts: &[PointId]) -> f64 {
    pts.iter()
        .map(|p| w.positions_y()[p.index()])
        .fold(f64::INFINITY, f64::min)
}

fn mean(values: &[f64], pts: &[PointId]) -> f64 {
    pts.iter().map(|p| values[p.index()]).sum::<f64>() / pts.len() as f64
}

fn one_substep(settings: MassSpringSettings) -> MassSpringSettings {
    MassSpringSettings {
        substeps: 1,
        ..settings
    }
}

/// Upward zero crossings (interpolated times) of a sampled signal.
fn upward_crossings(signal: &[f64], dt: f64) -> Vec<f64> {
    (1..signal.len())
        .filter(|&i| signal[i - 1] < 0.0 && signal[i] >= 0.0)
        .map(|i| (i as f64 - 1.0 + signal[i - 1] / (signal[i - 1] - signal[i])) * dt)
        .collect()
}

/// Stretch (length − 1) of spring 0 sampled after every substep for `n` substeps.
fn record_stretch(w: &mut MassSpringWorld, n: usize) -> Vec<f64> {
    (0..n)
        .map(|_| {
            w.step(&[]).unwrap();
            w.spring_length(SpringId(0)) - 1.0
        })
        .collect()
}

/// With tracking rate 1 springs are Hooke springs: two free unit masses on a spring of stiffness
/// k oscillate in their separation at ω = √(2k/m) = √200, period 2π/√200 = 0.44429 s.
#[test]
fn a_hooke_spring_oscillates_at_the_analytic_frequency() {
    let settings = MassSpringSettings {
        tracking_rate: 1.0,
        ..one_substep(MassSpringSettings::weightless())
    };
    let mut b = MassSpringBuilder::new(settings);
    let p = b.add_point(PointDesc::at(0.0, 0.0));
    let q = b.add_point(PointDesc::at(1.1, 0.0));
    b.add_spring(SpringDesc::between(p, q, 100.0).rest_length(1.0));
    let mut w = b.build().unwrap();
    let crossings = upward_crossings(&record_stretch(&mut w, 20_000), 1e-4);
    assert!(crossings.len() >= 4, "{crossings:?}");
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let expected = 2.0 * std::f64::consts::PI / 200f64.sqrt();
    assert!(
        (period / expected - 1.0).abs() < 1e-4,
        "period {period}, expected {expected}"
    );
}

/// EvoGym's tracking (rest = length + c (goal − length) before each substep) turns a spring of
/// stiffness k into a damped oscillator. One free unit mass on a spring to a fixed point, u its
/// stretch; solving the substep exactly (harmonic motion of ω = √k about the substep's rest
/// length, which sits at (1 − c)u) gives the linear map
///   u' = (1 − c + c cos θ) u + (sin θ / ω) v,   v' = −c ω sin θ u + cos θ v,   θ = ω dt,
/// whose eigenvalues r e^{±iφ} have r² = det = c + (1 − c) cos θ and cos φ = trace / (2r).
/// So the period is 2π dt / φ and the amplitude shrinks by r^(2π/φ) per period (for small θ:
/// stiffness c k, damping k dt / 2).
#[test]
fn a_tracked_spring_oscillates_and_decays_as_the_substep_map_predicts() {
    let (k, c, dt) = (1e5, 0.006, 1e-4);
    let mut b = MassSpringBuilder::new(one_substep(MassSpringSettings::weightless()));
    let p = b.add_point(PointDesc::at(0.0, 0.0).fixed());
    let q = b.add_point(PointDesc::at(1.1, 0.0));
    b.add_spring(SpringDesc::between(p, q, k).rest_length(1.0));
    let mut w = b.build().unwrap();
    let stretch = record_stretch(&mut w, 10_000);

    let theta = k.sqrt() * dt;
    let det = c + (1.0 - c) * theta.cos();
    let trace = 1.0 - c + c * theta.cos() + theta.cos();
    let phi = (trace / (2.0 * det.sqrt())).acos();
    let period = 2.0 * std::f64::consts::PI * dt / phi;
    let shrink = det.sqrt().powf(2.0 * std::f64::consts::PI / phi);
    assert!(
        (period - 0.2579).abs() < 1e-3 && (shrink - 0.525).abs() < 5e-3,
        "derivation: {period} {shrink}"
    );

    let crossings = upward_crossings(&stretch, dt);
    let measured = (crossings[3] - crossings[0]) / 3.0;
    assert!(
        (measured / period - 1.0).abs() < 1e-3,
        "period {measured}, expected {period}"
    );
    let per = (period / dt) as usize;
    let peak = |n: usize| {
        stretch[n * per..(n + 1) * per]
            .iter()
            .fold(0.0f64, |m, s| m.max(s.abs()))
    };
    let ratio = peak(2) / peak(1);
    assert!((ratio / shrink - 1.0).abs() < 5e-3, "decay {ratio}, expected {shrink}");
}

/// One substep from rest at length 0.1 with target 2.0, clipped to 1.6: goal 0.16 and rest
/// 0.1 + 0.006 × (0.16 − 0.1) = 0.10036. The next substep starts from the current length ℓ, not
/// from the old rest length: rest = ℓ + 0.006 (0.16 − ℓ). Target 0.3 clips to 0.6: goal 0.06.
#[test]
fn rest_length_moves_0_6_percent_from_the_current_length_toward_the_clipped_target() {
    let mut b = MassSpringBuilder::new(one_substep(MassSpringSettings::weightless()));
    let p = b.add_point(PointDesc::at(0.0, 0.0));
    let q = b.add_point(PointDesc::at(0.1, 0.0));
    let s = b.add_spring(SpringDesc::between(p, q, SOFT));
    b.add_actuator(&[s]);
    let mut w = b.build().unwrap();
    w.step(&[2.0]).unwrap();
    assert!((w.goal_lengths()[0] - 0.16).abs() < 1e-15);
    assert!((w.rest_lengths()[0] - 0.10036).abs() < 1e-15, "{}", w.rest_lengths()[0]);
    let len = w.spring_length(s);
    assert!(len > 0.1, "the spring extends toward its goal");
    w.step(&[2.0]).unwrap();
    assert!((w.rest_lengths()[0] - (len + 0.006 * (0.16 - len))).abs() < 1e-15);
    let len = w.spring_length(s);
    w.step(&[0.3]).unwrap();
    assert!((w.rest_lengths()[0] - (len + 0.006 * (0.06 - len))).abs() < 1e-15);
}

/// A spring of rest 1, band 0.25, stiffness 0, stretched to 1.5 and left still: the loose pass
/// removes 80 % of the excess 0.25, leaving 1.3; a tight limit of 3 % then removes half of the
/// excess 0.27, leaving 1.165. With one end fixed only the free end moves its half (0.1), leaving
/// 1.4.
#[test]
fn projection_pulls_lengths_back_into_their_bands() {
    let run = |tight: bool, fix_first: bool| {
        let mut b = MassSpringBuilder::new(one_substep(MassSpringSettings::weightless()));
        let first = PointDesc::at(0.0, 0.0);
        let p = b.add_point(if fix_first { first.fixed() } else { first });
        let q = b.add_point(PointDesc::at(0.9, 1.2));
        let s = b.add_spring(SpringDesc::between(p, q, 0.0).rest_length(1.0));
        if tight {
            b.limit_length(s, 0.03);
        }
        let mut w = b.build().unwrap();
        w.step(&[]).unwrap();
        w.spring_length(s)
    };
    assert!((run(false, false) - 1.3).abs() < 1e-12);
    assert!((run(true, false) - 1.165).abs() < 1e-12);
    assert!((run(false, true) - 1.4).abs() < 1e-12);
}

/// A 3 × 3 rigid block (16 unit masses, weight 1760) resting on the ground plane: its 4 bottom
/// points carry 440 each, so the static depth is 440 / 1.4e7 ≈ 3.1e-5. The ground has no damping,
/// so the block may bounce about that depth; it must never go deeper than 4× it and must stay
/// stable. Tracking makes a spring's static stiffness c k = 0.006 × 8.57e7 ≈ 5.1e5 (see the
/// tracked-spring test), so the block sags: its three layers of vertical springs carry 1320, 880
/// and 440 over 4 springs each, at most (2640 / 4) / 5.1e5 ≈ 1.28e-3 with the diagonals ignored;
/// with Hooke springs of stiffness k it would sag 80 times less.
#[test]
fn a_block_settles_on_the_ground_without_sinking() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
    let g = grid(&mut b, (0.0, 0.0), (3, 3), true, false, true);
    let mut w = b.build().unwrap();
    let depth = 440.0 / 1.4e7;
    let mut deepest = 0.0f64;
    for _ in 0..333 {
        w.step(&[]).unwrap();
        deepest = deepest.min(min_y(&w, &g.points));
    }
    assert!(deepest > -4.0 * depth, "sank to {deepest}");
    assert!(deepest < 0.0, "touches the ground");
    let sag = 0.3 - w.positions_y()[g.points.last().unwrap().index()] + deepest.min(0.0);
    let bound = 2640.0 / 4.0 / (0.006 * RIGID);
    assert!(sag > 0.5 * bound && sag < bound, "sagged {sag}, bound {bound}");
    let speed = mean(w.velocities_y(), &g.points).abs() + mean(w.velocities_x(), &g.points).abs();
    assert!(speed < 0.01, "still moving at {speed}");
}

/// A soft 2 × 2 block dropped onto a fixed 6 × 1 terrain strip whose top is at y = 0.1: the
/// contact pushes with at least 2.1e6 × 0.005 = 10 500 as soon as a point touches, far above a
/// point's share of the weight, so the block must never go below the surface by more than that
/// offset. Because that push jumps from 0 to 10 500 at the surface there is no resting
/// equilibrium: the block chatters on the surface (a tolerance of a tenth of a cell, not derived:
/// it neither sinks nor flies off).
#[test]
fn a_block_rests_on_fixed_terrain() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
    grid(&mut b, (0.0, 0.0), (6, 1), true, true, false);
    let g = grid(&mut b, (0.2, 0.12), (2, 2), false, false, true);
    let mut w = b.build().unwrap();
    let mut lowest = f64::INFINITY;
    for _ in 0..333 {
        w.step(&[]).unwrap();
        lowest = lowest.min(min_y(&w, &g.points));
    }
    assert!(lowest > 0.1 - 0.005, "went down to {lowest}");
    let mut highest = 0.0f64;
    for _ in 0..100 {
        w.step(&[]).unwrap();
        highest = highest.max(min_y(&w, &g.points));
    }
    assert!(highest < 0.1 + 0.01, "left the surface up to {highest}");
}

/// A flat 4 × 1 block sliding at 1 m/s on the ground: the friction saturates at μ N with
/// μ = 10 × 0.2 = 2, so it decelerates at μ g = 220 and stops after v² / (2 μ g) = 1/440 ≈ 2.27
/// mm. (Flat, because a square cell tips over its front edge once μ exceeds width / height = 1.)
/// Without friction it keeps sliding (drag 0.1 loses 1 % of the speed in 0.1 s).
#[test]
fn friction_stops_a_sliding_block() {
    let slide = |friction: f64| {
        let mut settings = MassSpringSettings::evogym();
        settings.ground.as_mut().unwrap().friction = friction;
        let mut b = MassSpringBuilder::new(settings);
        let g = grid(&mut b, (0.0, 0.0), (4, 1), true, false, true);
        let mut w = b.build().unwrap();
        g.points.iter().for_each(|&p| w.set_velocity(p, 1.0, 0.0));
        let x0 = mean(w.positions_x(), &g.points);
        for _ in 0..33 {
            w.step(&[]).unwrap();
        }
        (mean(w.positions_x(), &g.points) - x0, mean(w.velocities_x(), &g.points))
    };
    let (distance, speed) = slide(2.0);
    let expected = 1.0 / 440.0;
    assert!(
        distance > 0.8 * expected && distance < 1.25 * expected,
        "slid {distance}, expected {expected}"
    );
    assert!(speed.abs() < 1e-3, "still at {speed}");
    let (distance, speed) = slide(0.0);
    assert!(distance > 0.09 && speed > 0.98, "frictionless: {distance} {speed}");
}

/// Two soft 2 × 2 blocks flying at each other at 2 m/s each without gravity. Touching, their
/// centres are one block width (0.2) apart; passing through would bring the centres together.
/// The penalty must keep them at least 0.15 apart and send them apart again.
#[test]
fn two_bodies_collide_and_do_not_pass_through_each_other() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::weightless());
    let left = grid(&mut b, (0.0, 0.0), (2, 2), false, false, true);
    let right = grid(&mut b, (0.25, 0.03), (2, 2), false, false, true);
    let mut w = b.build().unwrap();
    left.points.iter().for_each(|&p| w.set_velocity(p, 2.0, 0.0));
    right.points.iter().for_each(|&p| w.set_velocity(p, -2.0, 0.0));
    let mut closest = f64::INFINITY;
    let mut touched = false;
    for _ in 0..666 {
        let report = w.step(&[]).unwrap();
        touched |= report.contacts > 0;
        closest = closest.min(mean(w.positions_x(), &right.points) - mean(w.positions_x(), &left.points));
    }
    assert!(touched);
    assert!(closest > 0.15, "centres came within {closest}");
    let parting = mean(w.velocities_x(), &right.points) - mean(w.velocities_x(), &left.points);
    assert!(parting > 0.0, "still approaching at {parting}");
    assert_ne!(left.body, right.body);
}

/// An 8-cell strip folded back over itself, the folded half shifted by half a cell: cells 4..7
/// lie on [0.25, 0.4], [0.15, 0.25], [0.05, 0.15], [−0.05, 0.05]. Non-neighbouring cells with
/// overlapping boxes: (0,6) (0,7) (1,5) (1,6) (2,4) (2,5), 12 ordered pairs > 8 boundary cells.
#[test]
fn a_body_folded_into_itself_is_reported_unstable() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::weightless());
    let g = grid(&mut b, (0.0, 0.0), (8, 1), false, false, true);
    let mut w = b.build().unwrap();
    w.step(&[]).unwrap();
    assert_eq!(w.self_overlap_pairs(g.body), 0);
    for &p in &g.points {
        let x = w.positions_x()[p.index()];
        if x > 0.41 {
            w.set_position(p, 0.75 - x, w.positions_y()[p.index()]);
        }
    }
    assert_eq!(w.self_overlap_pairs(g.body), 12);
    let err = w.step(&[]).unwrap_err();
    assert!(
        matches!(
            err,
            MassSpringError::SelfOverlap {
                body: 0,
                pairs: 12,
                limit: 8,
                ..
            }
        ),
        "{err:?}"
    );
    assert_eq!(g.sides.len(), 32);
}

/// The same fold in a body that is not watched is not reported.
#[test]
fn an_unwatched_body_is_not_checked_for_self_overlap() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::weightless());
    let g = grid(&mut b, (0.0, 0.0), (8, 1), false, false, false);
    let mut w = b.build().unwrap();
    for &p in &g.points {
        let x = w.positions_x()[p.index()];
        if x > 0.41 {
            w.set_position(p, 0.75 - x, w.positions_y()[p.index()]);
        }
    }
    assert_eq!(w.self_overlap_pairs(g.body), 12);
    assert!(w.step(&[]).is_ok());
}

#[test]
fn the_same_world_stepped_the_same_way_is_bit_identical() {
    let build = || {
        let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
        let g = grid(&mut b, (0.0, 0.05), (2, 2), false, false, true);
        b.add_actuator(&g.sides[0..4]);
        b.build().unwrap()
    };
    let (mut a, mut c) = (build(), build());
    for i in 0..20 {
        let t = [0.6 + (i % 5) as f64 * 0.25];
        a.step(&t).unwrap();
        c.step(&t).unwrap();
    }
    assert!(a
        .positions_x()
        .iter()
        .zip(c.positions_x())
        .all(|(p, q)| p.to_bits() == q.to_bits()));
    assert!(a
        .velocities_y()
        .iter()
        .zip(c.velocities_y())
        .all(|(p, q)| p.to_bits() == q.to_bits()));
}

#[test]
fn bad_descriptions_are_refused_with_the_element_named() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
    let p = b.add_point(PointDesc::at(0.0, 0.0));
    b.add_spring(SpringDesc::between(p, p, 1.0));
    let err = b.build().unwrap_err().to_string();
    assert!(err.contains("spring 0"), "{err}");
    let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
    b.add_point(PointDesc::at(0.0, 0.0).mass(0.0));
    assert!(b.build().unwrap_err().to_string().contains("point 0: mass"));
    let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
    let q: Vec<_> = (0..4).map(|i| b.add_point(PointDesc::at(i as f64, 0.0))).collect();
    let body = b.add_body(BodyDesc::new());
    b.add_quad(QuadDesc::new(body, [q[0], q[1], q[2], q[3]]));
    assert!(b.build().unwrap_err().to_string().contains("quad 0 has zero area"));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Random small grids, random cell kinds, initial velocities from gentle to absurd and random
    /// targets: every step either succeeds with a finite state, or reports the trouble; the state
    /// left behind is finite in every case.
    #[test]
    fn random_grids_never_hide_a_non_finite_state(
        w in 1usize..4,
        h in 1usize..4,
        rigid in any::<bool>(),
        scale_exp in prop::sample::select(vec![0i32, 2, 4, 200, 300]),
        velocities in prop::collection::vec((-1.0..1.0f64, -1.0..1.0f64), 16),
        targets in prop::collection::vec(-1.0..3.0f64, 3 * 9),
    ) {
        let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
        let g = grid(&mut b, (0.0, 0.0), (w, h), rigid, false, true);
        for c in 0..w * h {
            b.add_actuator(&g.sides[4 * c..4 * c + 2]);
        }
        let mut world = b.build().unwrap();
        let scale = 10f64.powi(scale_exp);
        for (p, v) in g.points.iter().zip(&velocities) {
            world.set_velocity(*p, v.0 * scale, v.1 * scale);
        }
        for step in 0..3 {
            let result = world.step(&targets[step * w * h..(step + 1) * w * h]);
            let finite = [world.positions_x(), world.positions_y(), world.velocities_x(), world.velocities_y()]
                .iter()
                .all(|s| s.iter().all(|v| v.is_finite()));
            prop_assert!(finite, "step {step}: non-finite state left behind ({result:?})");
            if result.is_err() {
                break;
            }
        }
    }
}
