//! Stability: random connected bodies under random actuation on every terrain never produce
//! non-finite values or absurd voxel areas; a blown-up state is an error, never a panic.

mod common;

use common::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use vsrlab_body::{Morphology, Preset};
use vsrlab_brain::BrainSpec;
use vsrlab_physics::{Vec2, WorldSettings};
use vsrlab_tasks::{locomotion, EpisodeError, TraceLevel};

/// Sane area-ratio bounds (see docs/physics.md): the actuation range is [0.775, 1.225]; impacts and
/// loads may squash or stretch a voxel further, but below 0.3 or above 2.0 it has collapsed or
/// torn, which the original's ropes and springs also prevent.
const AREA_BOUNDS: (f64, f64) = (0.3, 2.0);
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
        0 => BrainSpec::Random { period: 0.0, seed: rng.random() },
        1 => BrainSpec::Random { period: rng.random_range(0.05..1.0), seed: rng.random() },
        _ => BrainSpec::Phase {
            frequency: rng.random_range(0.1..5.0),
            amplitude: 1.0,
            phase_x: rng.random_range(-2.0..2.0),
            phase_y: rng.random_range(-2.0..2.0),
        },
    }
}

#[test]
fn a_thousand_random_bodies_stay_finite_and_sane_on_every_terrain() {
    let cases = 1000;
    let worst: Vec<(f64, f64)> = (0..cases)
        .into_par_iter()
        .map(|i| {
            let mut rng = ChaCha8Rng::seed_from_u64(i as u64);
            let body = random_body(&mut rng);
            let brain = random_brain(&mut rng);
            let preset = if i % 2 == 0 { Preset::Y2021 } else { Preset::Y2022 };
            let terrain = TERRAINS[i % TERRAINS.len()];
            let mut r = robot("box-1x1", preset, brain);
            r.body = body.clone();
            let o = locomotion::run(&r, &task(terrain, 30.0), i as u64, TraceLevel::Full)
                .unwrap_or_else(|e| panic!("case {i} ({terrain}, preset {preset}, body {}): {e}", body.to_rows().join("/")));
            let tr = o.trace.unwrap();
            assert!(o.velocity.is_finite());
            assert!(tr.polygons.iter().flatten().all(|p| p.is_finite()), "case {i}: non-finite polygon");
            let lo = tr.area_ratios.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = tr.area_ratios.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            assert!(
                lo >= AREA_BOUNDS.0 && hi <= AREA_BOUNDS.1,
                "case {i} ({terrain}, preset {preset}, body {}): area ratio range [{lo:.3}, {hi:.3}]",
                body.to_rows().join("/")
            );
            (lo, hi)
        })
        .collect();
    let lo = worst.iter().map(|w| w.0).fold(f64::INFINITY, f64::min);
    let hi = worst.iter().map(|w| w.1).fold(f64::NEG_INFINITY, f64::max);
    println!("{cases} random bodies: area ratio range over all steps [{lo:.3}, {hi:.3}]");
}

#[test]
fn a_state_that_blows_up_is_reported_as_an_error() {
    let r = robot("biped-4x3", Preset::Y2021, phase());
    let mut t = task("flat", 2.0);
    t.physics = WorldSettings {
        gravity: Vec2::new(0.0, -1e308),
        ..Default::default()
    };
    match locomotion::run(&r, &t, 0, TraceLevel::None) {
        Err(EpisodeError::Physics { time, .. }) => assert!(time > 0.0),
        other => panic!("expected a physics error, got {other:?}"),
    }
}

#[test]
fn invalid_tasks_are_rejected_with_the_field_named() {
    let r = robot("biped-4x3", Preset::Y2021, phase());
    let mut t = task("flat", 2.0);
    t.duration = -1.0;
    let e = locomotion::run(&r, &t, 0, TraceLevel::None).unwrap_err();
    assert!(e.to_string().contains("task.duration"), "{e}");
    let mut t = task("flat", 2.0);
    t.physics.substeps = 0;
    let e = locomotion::run(&r, &t, 0, TraceLevel::None).unwrap_err();
    assert!(e.to_string().contains("substeps"), "{e}");
}
