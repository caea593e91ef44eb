//! Calibration against the original simulator's reference outputs (vsr-model.md §9).

use crate::common;

use common::*;
use vsrlab_body::Preset;
use vsrlab_brain::{BrainSpec, ConstantSpec};
use vsrlab_physics::Solver;
use vsrlab_tasks::{episode, Locomotion, TraceLevel};

/// Flat ground for `duration` s, stepped by `solver` (the sequential-impulse solver follows the
/// preset's dyn4j version).
fn solver_task(solver: Solver, duration: f64) -> Locomotion {
    let mut t = task("flat", duration);
    t.physics.solver = solver;
    t
}

/// Mean area ratio at the last step and (min, max) over the last 2 s, plus centre y at the end and
/// the lowest voxel corner at the first step.
fn calibrate(body: &str, preset: Preset, brain: BrainSpec) -> (f64, f64, f64, f64, f64, u64) {
    calibrate_with(body, preset, brain, Solver::SoftSubsteps)
}

fn calibrate_with(body: &str, preset: Preset, brain: BrainSpec, solver: Solver) -> (f64, f64, f64, f64, f64, u64) {
    let t = solver_task(solver, 5.0);
    let o = episode::run(&robot(body, preset, brain), &t, 0, TraceLevel::Full).unwrap();
    let tr = o.trace.unwrap();
    let n = tr.units();
    let mean = |k: usize| tr.values("area_ratio")[k * n..(k + 1) * n].iter().sum::<f64>() / n as f64;
    let last = tr.len() - 1;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..tr.len() {
        if tr.times[k] >= 3.0 {
            lo = lo.min(mean(k));
            hi = hi.max(mean(k));
        }
    }
    let first_min_y = tr
        .polygons_at(0)
        .iter()
        .flatten()
        .map(|p| p.y)
        .fold(f64::INFINITY, f64::min);
    (mean(last), lo, hi, tr.centers[last].y, first_min_y, o.steps)
}

fn within(actual: f64, expected: f64, tol: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tol,
        "{what}: got {actual:.4}, reference {expected:.4} (tolerance {tol})"
    );
}

/// (body, preset, area f=0, f=+1, f=−1, sine range or None, centre y at rest).
type Reference = (&'static str, Preset, f64, f64, f64, Option<(f64, f64)>, f64);
const REFERENCES: [Reference; 4] = [
    (
        "box-1x1",
        Preset::Y2022,
        0.9993,
        0.7992,
        1.1993,
        Some((0.8004, 1.1993)),
        6.4939,
    ),
    ("box-3x3", Preset::Y2022, 0.9979, 0.7979, 1.1978, None, 9.4850),
    (
        "box-1x1",
        Preset::Y2021,
        0.9987,
        0.7737,
        1.2241,
        Some((0.7750, 1.2251)),
        6.4933,
    ),
    ("box-3x3", Preset::Y2021, 0.9955, 0.7708, 1.2198, None, 9.4631),
];

#[test]
fn constant_and_sine_actuation_match_reference_area_ratios() {
    calibration_matches(Solver::SoftSubsteps);
}

#[test]
fn the_sequential_impulse_solver_matches_the_reference_area_ratios_too() {
    calibration_matches(Solver::SequentialImpulses);
}

fn calibration_matches(solver: Solver) {
    for (body, preset, a0, a_pos, a_neg, sine_range, rest_y) in REFERENCES {
        let what = |s: &str| format!("{body} preset {preset} ({solver:?}) {s}");
        let (a, _, _, y, first_min_y, steps) =
            calibrate_with(body, preset, BrainSpec::Constant(ConstantSpec { value: 0.0 }), solver);
        assert_eq!(
            steps, 301,
            "5 s at 1/60 s is 301 steps, as in the original (its time is a float sum of steps)"
        );
        within(a, a0, 0.01, &what("f = 0 area"));
        // rest height and first-step fall within 2 %
        within(y, rest_y, 0.02 * rest_y, &what("centre y at rest"));
        let fall = 6.0 - first_min_y;
        within(fall, 6.0 - 5.9973, 0.02 * (6.0 - 5.9973), &what("first-step fall"));
        let a_plus = calibrate_with(body, preset, BrainSpec::Constant(ConstantSpec { value: 1.0 }), solver).0;
        let a_minus = calibrate_with(body, preset, BrainSpec::Constant(ConstantSpec { value: -1.0 }), solver).0;
        within(a_plus, a_pos, 0.01, &what("f = +1 area"));
        within(a_minus, a_neg, 0.01, &what("f = -1 area"));
        println!(
            "{body} {preset} {solver:?}: f=0 {a:.4} (ref {a0}), f=+1 {a_plus:.4} (ref {a_pos}), f=-1 {a_minus:.4} (ref {a_neg}), \
             rest y {y:.4} (ref {rest_y}), first-step min y {first_min_y:.4} (ref 5.9973)"
        );
        if let Some((lo_ref, hi_ref)) = sine_range {
            let (_, lo, hi, ..) = calibrate_with(body, preset, sine(), solver);
            println!("{body} {preset} {solver:?}: 1 Hz sine [{lo:.4}, {hi:.4}] (ref [{lo_ref}, {hi_ref}])");
            within(lo, lo_ref, 0.01, &what("1 Hz sine min area"));
            within(hi, hi_ref, 0.01, &what("1 Hz sine max area"));
        }
    }
}

#[test]
fn rest_height_is_close_to_nominal() {
    // a resting 1×1 voxel sits on the ground at y = 5: its centre is near 5 + L/2 = 6.5
    let (_, _, _, y, _, _) = calibrate(
        "box-1x1",
        Preset::Y2021,
        BrainSpec::Constant(ConstantSpec { value: 0.0 }),
    );
    assert!(y < 6.5 && y > 6.45, "{y}");
}

#[test]
fn phase_gaits_walk_and_are_reported_beside_the_original() {
    // The original's velocities (vsr-model.md §9) are single chaotic samples; we only require
    // sane, finite, forward-moving gaits here and print ours beside theirs.
    let cases = [
        ("biped-4x3", Preset::Y2021, 0.1339),
        ("worm-10x4", Preset::Y2021, 0.0493),
        ("biped-4x3", Preset::Y2022, 0.6709),
        ("worm-10x4", Preset::Y2022, 0.7035),
    ];
    for (body, preset, original) in cases {
        let o = episode::run(&robot(body, preset, phase()), &task("flat", 30.0), 0, TraceLevel::None).unwrap();
        println!(
            "{body} preset {preset}: velocity {:.4} (original {original})",
            o.metric("velocity")
        );
        assert_eq!(o.steps, 1801);
        assert!(
            o.metric("velocity").is_finite() && o.metric("velocity").abs() < 3.0,
            "{body}: {}",
            o.metric("velocity")
        );
    }
}

/// vsr-model.md §9.1: the lidar on voxel (3, 1) of a biped (east side, 5 rays) looks along the
/// centres of 5 bins in v1.10.0 (preset 2021) and along the side's ends in HEAD (2022); a robot's
/// episode records the directions its preset's sensors use.
#[test]
fn lidar_directions_follow_the_preset() {
    use std::f64::consts::PI;
    use vsrlab_body::sensors::SensorConfig;
    for (preset, expected) in [
        (Preset::Y2021, [-PI / 5.0, -PI / 10.0, 0.0, PI / 10.0, PI / 5.0]),
        (Preset::Y2022, [-PI / 4.0, -PI / 8.0, 0.0, PI / 8.0, PI / 4.0]),
    ] {
        let mut r = robot("biped-4x3", preset, phase());
        r.sensors = SensorConfig::parse("spinedTouchSighted-f-f-0").unwrap();
        let o = episode::run(&r, &task("flat", 0.1), 0, TraceLevel::Full).unwrap();
        let trace = o.trace.unwrap();
        let cells = trace.channel("cells").unwrap();
        let v31 = cells.rows().position(|c| c == [3.0, 1.0]).unwrap() as f64;
        let angles: Vec<f64> = trace
            .channel("rays")
            .unwrap()
            .rows()
            .filter(|ray| ray[0] == v31)
            .map(|ray| ray[1])
            .collect();
        assert_eq!(angles.len(), 5, "{preset}");
        for (a, e) in angles.iter().zip(expected) {
            assert!((a - e).abs() < 1e-12, "{preset}: {angles:?}");
        }
    }
}

/// The centres (x, y) and angles of the four corner squares (NW, NE, SE, SW) of a single voxel,
/// preset 2022, constant actuation +1 on flat ground, left edge at x = 11, after step 301: the
/// original (2D-VSR-Sim HEAD on dyn4j 4.2.1) run here as a measuring instrument (docs/fidelity.md).
const ORIGINAL_VOXEL_2022_STEP_301: [(f64, f64, f64); 4] = [
    (11.690415693487841, 7.155040229207399, -0.0014563501254180856),
    (13.324653750544515, 7.15267762528792, -0.0016118114321839168),
    (13.320768781819632, 5.5223092407914125, -0.0044083666075956885),
    (11.688254136251722, 5.52410310906965, -6.803474299432713e-4),
];

/// Step by step, the sequential-impulse solver follows the original: a voxel that falls, lands
/// (continuous collision, contacts, friction) and contracts ends within 10⁻⁵ of the original's
/// corner squares (measured: 7·10⁻⁷ at most over the 301 steps); the soft solver does not.
#[test]
fn the_sequential_impulse_solver_follows_the_original_voxel_step_by_step() {
    let brain = BrainSpec::Constant(ConstantSpec { value: 1.0 });
    let robot = robot("box-1x1", Preset::Y2022, brain);
    let largest_gap = |solver: Solver| {
        let t = solver_task(solver, 10.0);
        let mut e = vsrlab_tasks::Episode::new(&robot, &t, 0, TraceLevel::None).unwrap();
        for _ in 0..301 {
            e.step(None).unwrap();
        }
        let mut gap: f64 = 0.0;
        for (k, &(x, y, angle)) in ORIGINAL_VOXEL_2022_STEP_301.iter().enumerate() {
            let h = vsrlab_physics::PartHandle(k as u32);
            let p = e.world().part_position(h);
            gap = gap.max((p.x - x).abs()).max((p.y - y).abs());
            gap = gap.max((e.world().part_angle(h) - angle).abs());
        }
        gap
    };
    let sequential = largest_gap(Solver::SequentialImpulses);
    println!("largest gap to the original after 301 steps: sequential impulses {sequential:.2e}");
    assert!(sequential < 1e-5, "{sequential}");
    let soft = largest_gap(Solver::SoftSubsteps);
    println!("soft sub-steps {soft:.2e}");
    assert!(soft > 1e-4, "{soft}");
}

/// vsr-model.md §9.1, preset 2022, worm-6x2: the original's 30 shifted starts have median
/// velocity 0.4749, IQR [0.4638, 0.4845]. Ten shifted starts under the sequential-impulse solver
/// land there (measured with 30: median 0.4756, IQR [0.4604, 0.4894]); the soft solver's do not
/// (0.126 from every start).
#[test]
fn sequential_impulses_reproduce_the_original_2022_worm_ensemble() {
    use vsrlab_tasks::ensemble::{self, Summary};
    let robot = robot("worm-6x2", Preset::Y2022, phase());
    let median = |solver: Solver| {
        let task = vsrlab_tasks::TaskSpec::Locomotion(solver_task(solver, 30.0));
        let v = ensemble::run_shifted(&robot, &task, &ensemble::shifts(10, 1e-6), 0, "velocity").unwrap();
        Summary::of(&v).unwrap().median
    };
    let sequential = median(Solver::SequentialImpulses);
    let soft = median(Solver::SoftSubsteps);
    println!("worm-6x2 2022, median over 10 starts: sequential impulses {sequential:.4}, soft {soft:.4}");
    assert!((0.44..=0.50).contains(&sequential), "{sequential}");
    assert!(!(0.44..=0.50).contains(&soft), "{soft}");
}

/// 2D-VSR-Sim (v1.10 on) measures distance with the mean of the voxels' outer-polygon centres,
/// which moves when corners turn although the mass centre does not. The 2022 biped's phase gait
/// falls for its first 0.1 s (no contact yet): the original measures −0.011575535210397449 per
/// second (the instrument, e569066, docs/fidelity.md); the mass centre does not move at all.
#[test]
fn locomotion_measures_the_original_s_polygon_centre() {
    let robot = robot("biped-4x3", Preset::Y2022, BrainSpec::parse("phase").unwrap());
    let t = solver_task(Solver::SequentialImpulses, 0.1);
    let o = episode::run(&robot, &t, 0, TraceLevel::Center).unwrap();
    let v = o.metric("velocity");
    assert!((v - -0.011575535210397449).abs() < 1e-9, "velocity {v}");
    let centers = &o.trace.unwrap().centers;
    let moved = centers[centers.len() - 1].x - centers[0].x;
    assert!(moved.abs() < 1e-9, "the mass centre moved by {moved}");
}
