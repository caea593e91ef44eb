//! Same inputs, same outcome: across repeated runs and across thread counts.

use crate::common;

use common::*;
use rayon::prelude::*;
use vsrlab_body::Preset;
use vsrlab_brain::{BrainSpec, RandomSpec};
use vsrlab_tasks::{episode, Outcome, TraceLevel};

fn batch(threads: usize) -> Vec<Outcome> {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let cases: Vec<(&str, &str, BrainSpec)> = vec![
        ("biped-4x3", "flat", phase()),
        (
            "worm-6x2",
            "hilly-1-10",
            BrainSpec::Random(RandomSpec { period: 0.2, seed: 3 }),
        ),
        ("comb-5x2", "steppy-1-5", phase()),
        (
            "box-3x3",
            "uphill-10",
            BrainSpec::Random(RandomSpec { period: 0.0, seed: 9 }),
        ),
        ("tripod-5x3", "downhill-10", phase()),
    ];
    pool.install(|| {
        cases
            .par_iter()
            .enumerate()
            .map(|(i, (body, terrain, brain))| {
                let r = robot(body, Preset::Y2021, brain.clone());
                episode::run(&r, &task(terrain, 4.0), i as u64, TraceLevel::Full).unwrap()
            })
            .collect()
    })
}

#[test]
fn outcomes_are_bit_identical_across_runs_and_thread_counts() {
    let one = batch(1);
    let two = batch(2);
    let four = batch(4);
    assert_eq!(one, two);
    assert_eq!(one, four);
    assert_eq!(one, batch(1));
    // bit-identical, not merely equal within tolerance
    for (a, b) in one.iter().zip(&four) {
        assert_eq!(a.metric("distance").to_bits(), b.metric("distance").to_bits());
    }
}

#[test]
fn different_seeds_change_random_terrain_outcomes() {
    let r = robot("biped-4x3", Preset::Y2021, phase());
    let a = episode::run(&r, &task("hilly-2-5", 5.0), 1, TraceLevel::None).unwrap();
    let b = episode::run(&r, &task("hilly-2-5", 5.0), 2, TraceLevel::None).unwrap();
    assert_ne!(a.metric("distance"), b.metric("distance"));
}
