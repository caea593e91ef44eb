//! Stability: random connected bodies under random actuation on every terrain never produce
//! non-finite values or absurd voxel areas; a blown-up state is an error, never a panic.

use crate::common;

use common::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use vsrlab_body::{Morphology, Preset};
use vsrlab_brain::{BrainSpec, PhaseSpec, RandomSpec};
use vsrlab_physics::{ContactModel, Solver, WorldSettings};
use vsrlab_tasks::{episode, EpisodeError, TraceLevel};

/// Sane area-ratio bounds (see docs/physics.md): the actuation range is [0.775, 1.225]; impacts and
/// loads may squash or stretch a voxel further, but below 0.3 or above 2.0 it has collapsed or
/// torn, which the original's ropes and springs also prevent.
const AREA_BOUNDS: (f64, f64) = (0.1, 2.0);
const TERRAINS: [&str; 5] = ["flat", "hilly-1-10", "steppy-1-10", "uphill-20", "downhill-30"];

/// A random connected body up to 10×10: grow from one cell by random neighbour additions.
fn random_body(rng: &mut ChaCha8Rng) -> Morphology {
    let (w, h) = (rng.random_range(1..=10usize), rng.random_range(1..=10usize));
    let target = rng.random_range(1..=w * h);
    let mut cells = vec![false; w * h];
    let start = rng.random_range(0..w * h);
    cells[start] = true;
    let mut count = 1;
    let mut frontier = vec![start];
    while count < target && !frontier.is_empty() {
        let i = frontier[rng.random_range(0..frontier.len())];
        let (x, y) = (i % w, i / w);
        let options = [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)];
        let (nx, ny) = options[rng.random_range(0..4)];
        if nx < w && ny < h && !cells[ny * w + nx] {
            cells[ny * w + nx] = true;
            frontier.push(ny * w + nx);
            count += 1;
        }
    }
    Morphology::from_cells(w, h, cells).expect("grown bodies are connected")
}

fn random_brain(rng: &mut ChaCha8Rng) -> BrainSpec {
    match rng.random_range(0..3) {
        0 => BrainSpec::Random(RandomSpec {
            period: 0.0,
            seed: rng.random(),
        }),
        1 => BrainSpec::Random(RandomSpec {
            period: rng.random_range(0.05..1.0),
            seed: rng.random(),
        }),
        _ => BrainSpec::Phase(PhaseSpec {
            frequency: rng.random_range(0.1..5.0),
            amplitude: 1.0,
            phase_x: rng.random_range(-2.0..2.0),
            phase_y: rng.random_range(-2.0..2.0),
        }),
    }
}

/// Runs one random case: the area-ratio range over the episode, or a description of what failed.
fn run_case(i: usize, only: Option<usize>, physics: &Physics) -> Result<(f64, f64), String> {
    let mut rng = ChaCha8Rng::seed_from_u64(i as u64);
    let body = random_body(&mut rng);
    let brain = random_brain(&mut rng);
    let preset = if i.is_multiple_of(2) {
        Preset::Y2021
    } else {
        Preset::Y2022
    };
    let terrain = TERRAINS[i % TERRAINS.len()];
    let mut r = robot("box-1x1", preset, brain);
    r.body = body.clone();
    let mut tk = task(terrain, 30.0);
    if let Some(n) = std::env::var("ROBUSTNESS_SUBSTEPS").ok().and_then(|v| v.parse().ok()) {
        tk.physics.substeps = n;
    }
    tk.physics.solver = physics.solver;
    (physics.set)(&mut tk.physics);
    let describe = || {
        format!(
            "case {i} ({terrain}, preset {preset}, {}, body {}, brain {})",
            physics.name,
            body.to_rows().join("/"),
            serde_json::to_string(&r.brain).unwrap()
        )
    };
    let o = episode::run(&r, &tk, i as u64, TraceLevel::Full).map_err(|e| format!("{}: {e}", describe()))?;
    let velocity = o.metric("velocity");
    let tr = o.trace.unwrap();
    if !velocity.is_finite() || !tr.outlines.iter().all(|p| p.is_finite()) {
        return Err(format!("{}: non-finite state", describe()));
    }
    if only.is_some() {
        let n = tr.units();
        for (k, chunk) in tr.values("area_ratio").chunks(n * 60).enumerate() {
            print!("{k}s:{:.2} ", chunk.iter().copied().fold(f64::INFINITY, f64::min));
        }
        println!();
    }
    let lo = tr.values("area_ratio").iter().copied().fold(f64::INFINITY, f64::min);
    let hi = tr
        .values("area_ratio")
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    if lo < AREA_BOUNDS.0 || hi > AREA_BOUNDS.1 {
        return Err(format!("{}: area ratio range [{lo:.3}, {hi:.3}]", describe()));
    }
    Ok((lo, hi))
}

/// 240 random connected bodies up to 10×10, random actuation, 30 s, cycling through every
/// terrain and both presets (ROBUSTNESS_CASES=n runs more: 400 until CI time ran short; 1,000
/// and 10,000 were run before releases). Every case must stay finite; at most 0.5 % of cases may leave the sane area bounds
/// (a known, rare tangle of very large bodies tumbling down steep slopes in the rope-less 2022
/// preset: docs/physics.md, "Known limitations"). Failures are printed.
#[test]
fn random_bodies_stay_finite_and_sane_on_every_terrain() {
    random_bodies_stay_finite_and_sane(cases("ROBUSTNESS_CASES", 240), &Physics::solver(Solver::SoftSubsteps));
}

/// The same under the sequential-impulse solver (dyn4j's pipeline), on fewer cases (48; 80 until
/// CI time ran short): it is slower.
/// ROBUSTNESS_SEQUENTIAL_CASES=n runs more.
#[test]
fn random_bodies_stay_finite_and_sane_under_sequential_impulses() {
    random_bodies_stay_finite_and_sane(
        cases("ROBUSTNESS_SEQUENTIAL_CASES", 48),
        &Physics::solver(Solver::SequentialImpulses),
    );
}

/// The fidelity candidates of docs/fidelity.md (settings, not defaults) on a few cases each
/// (ROBUSTNESS_CANDIDATE_CASES=n runs more): every state stays finite. The area bounds are
/// reported, not required: case 4 (a 10×8 body tumbling down a 30° slope) squeezes a voxel to
/// 1 % of its area under coloured, sub-stepped sweeps (docs/fidelity.md).
#[test]
fn random_bodies_stay_finite_and_sane_under_the_fidelity_candidates() {
    let n = cases("ROBUSTNESS_CANDIDATE_CASES", 8);
    let candidates = [
        Physics {
            name: "soft solver with dyn4j's contacts",
            solver: Solver::SoftSubsteps,
            set: |p| p.contact_model = ContactModel::Dyn4j,
        },
        Physics {
            name: "sequential impulses, welds merged",
            solver: Solver::SequentialImpulses,
            set: |p| p.merge_welds = true,
        },
        Physics {
            name: "sequential impulses, coloured, 2 sub-steps",
            solver: Solver::SequentialImpulses,
            set: |p| {
                p.coloured_joints = true;
                p.sequential_substeps = 2;
            },
        },
    ];
    for physics in &candidates {
        random_bodies_stay_finite(n, physics);
    }
}

/// The physics a robustness case runs with: a solver and changes to its settings.
struct Physics {
    name: &'static str,
    solver: Solver,
    set: fn(&mut WorldSettings),
}

impl Physics {
    fn solver(solver: Solver) -> Physics {
        Physics {
            name: match solver {
                Solver::SoftSubsteps => "soft-substeps",
                Solver::SequentialImpulses => "sequential-impulses",
            },
            solver,
            set: |_| {},
        }
    }
}

/// The number of cases in environment variable `name`, or `default`.
fn cases(name: &str, default: usize) -> usize {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

fn random_bodies_stay_finite_and_sane(cases: usize, physics: &Physics) {
    let (inside, outside) = random_bodies_stay_finite(cases, physics);
    assert!(
        outside * 200 <= inside + outside,
        "{outside} of {} cases left the area bounds",
        inside + outside
    );
}

/// Runs `cases` random cases and fails on any non-finite state or error; returns how many cases
/// stayed within the area bounds and how many left them (printed).
fn random_bodies_stay_finite(cases: usize, physics: &Physics) -> (usize, usize) {
    // ROBUSTNESS_CASE=i replays a single case (for debugging a failure)
    let only: Option<usize> = std::env::var("ROBUSTNESS_CASE").ok().and_then(|v| v.parse().ok());
    let results: Vec<Result<(f64, f64), String>> = (0..cases)
        .into_par_iter()
        .filter(|i| only.is_none_or(|o| o == *i))
        .map(|i| run_case(i, only, physics))
        .collect();
    let failures: Vec<&String> = results.iter().filter_map(|r| r.as_ref().err()).collect();
    for f in &failures {
        println!("outside bounds or failed: {f}");
    }
    assert!(
        failures.iter().all(|f| f.contains("area ratio range")),
        "non-finite states or errors: {failures:?}"
    );
    let ok: Vec<&(f64, f64)> = results.iter().filter_map(|r| r.as_ref().ok()).collect();
    let lo = ok.iter().map(|w| w.0).fold(f64::INFINITY, f64::min);
    let hi = ok.iter().map(|w| w.1).fold(f64::NEG_INFINITY, f64::max);
    println!(
        "{}: {} random bodies: {} within [{}, {}] (observed [{lo:.3}, {hi:.3}]), {} outside",
        physics.name,
        results.len(),
        ok.len(),
        AREA_BOUNDS.0,
        AREA_BOUNDS.1,
        failures.len()
    );
    (ok.len(), failures.len())
}

#[test]
fn a_state_that_blows_up_is_reported_as_an_error() {
    let r = robot("biped-4x3", Preset::Y2021, phase());
    let t = task("flat", 2.0);
    // a user-reachable blow-up: a spring so stiff that its stiffness overflows to infinity
    let mut r = r;
    let mut params = vsrlab_body::VoxelParams::preset(Preset::Y2021);
    params.spring_frequency = 1e200;
    r.voxel = Some(params);
    match episode::run(&r, &t, 0, TraceLevel::None) {
        Err(EpisodeError::Physics { time, .. }) => assert!(time > 0.0),
        other => panic!("expected a physics error, got {other:?}"),
    }
}

#[test]
fn invalid_tasks_are_rejected_with_the_field_named() {
    let r = robot("biped-4x3", Preset::Y2021, phase());
    let mut t = task("flat", 2.0);
    t.duration = -1.0;
    let e = episode::run(&r, &t, 0, TraceLevel::None).unwrap_err();
    assert!(e.to_string().contains("task.duration"), "{e}");
    let mut t = task("flat", 2.0);
    t.physics.substeps = 0;
    let e = episode::run(&r, &t, 0, TraceLevel::None).unwrap_err();
    assert!(e.to_string().contains("substeps"), "{e}");
}
