//! Genotype → robot: parameter counts of the thesis's ch. 3 combinations, evaluation of random
//! genotypes, and the robot-file round trip.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use vsrlab_tasks::episode;
use vsrlab_tasks::files::{robot_from_json, robot_to_json};
use vsrlab_tasks::{evaluate, EvaluationError, Locomotion, Representation, TraceLevel};

/// A ch. 3 representation: `body` and `brain` as JSON, velocity + area + touch on every voxel.
fn representation(body: &str, brain: &str) -> Representation {
    let json = format!(r#"{{"body": {body}, "sensors": "uniform-vxy+a+t-0", "brain": {brain}}}"#);
    serde_json::from_str(&json).unwrap_or_else(|e| panic!("{json}: {e}"))
}

const DIRECT_10: &str = r#"{"kind": "direct", "width": 10, "height": 10}"#;
const GMM_10: &str = r#"{"kind": "gmm", "width": 10, "height": 10, "components": 5}"#;
const HOMOGENEOUS: &str = r#"{"kind": "distributed-mlp", "signals": 1, "hidden": [], "layout": "homogeneous"}"#;
const HETEROGENEOUS: &str = r#"{"kind": "distributed-mlp", "signals": 1, "hidden": [], "layout": "heterogeneous"}"#;

fn random_genotype(n: usize, seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
}

#[test]
fn parameter_counts_match_the_thesis() {
    let cases = [
        (DIRECT_10, HOMOGENEOUS, 100, 45),
        (DIRECT_10, HETEROGENEOUS, 100, 4500),
        (GMM_10, HOMOGENEOUS, 25, 45),
        (GMM_10, HETEROGENEOUS, 25, 4500),
    ];
    for (body, brain, body_genes, brain_genes) in cases {
        let r = representation(body, brain);
        assert_eq!(r.body_genes(), body_genes, "{body}");
        assert_eq!(r.brain_genes().unwrap(), brain_genes, "{brain}");
        assert_eq!(r.genotype_length().unwrap(), body_genes + brain_genes);
    }
    // a fixed biped-4x3 with a centralised MLP: 40 inputs, 26 hidden, 10 outputs (vsr-model.md §4.3)
    let fixed = representation(r#""biped-4x3""#, r#"{"kind": "mlp"}"#);
    assert_eq!(fixed.body_genes(), 0);
    assert_eq!(fixed.brain_genes().unwrap(), 1336);
}

#[test]
fn a_brain_whose_size_follows_the_body_is_rejected_with_an_evolved_body() {
    let r = representation(DIRECT_10, r#"{"kind": "mlp"}"#);
    let err = r.genotype_length().unwrap_err().to_string();
    assert!(
        err.contains("representation.brain") && err.contains("fixed body"),
        "{err}"
    );
}

#[test]
fn a_genotype_of_the_wrong_length_is_an_error_naming_both_counts() {
    let r = representation(DIRECT_10, HOMOGENEOUS);
    let err = evaluate(&r, &vec![0.5; 144], &Locomotion::default(), 0).unwrap_err();
    assert!(matches!(err, EvaluationError::Genotype(_)), "{err}");
    let msg = err.to_string();
    assert!(msg.contains("145") && msg.contains("144"), "{msg}");
}

#[test]
fn body_parts_accept_names_grids_rows_and_encodings() {
    let named = representation(r#""worm-3x2""#, r#"{"kind": "phase"}"#);
    let grid = representation(r####""###/###""####, r#"{"kind": "phase"}"#);
    let rows = representation(r####"["###", "###"]"####, r#"{"kind": "phase"}"#);
    assert_eq!(named, grid);
    assert_eq!(named, rows);
    let bad = serde_json::from_str::<Representation>(
        r#"{"body": {"kind": "direct", "width": 3}, "sensors": "empty", "brain": {"kind": "phase"}}"#,
    )
    .unwrap_err()
    .to_string();
    assert!(bad.contains("height"), "{bad}");
}

#[test]
fn random_genotypes_of_every_combination_walk_for_thirty_seconds() {
    let task = Locomotion::default();
    for (k, (body, brain)) in [
        (DIRECT_10, HOMOGENEOUS),
        (DIRECT_10, HETEROGENEOUS),
        (GMM_10, HOMOGENEOUS),
        (GMM_10, HETEROGENEOUS),
    ]
    .into_iter()
    .enumerate()
    {
        let r = representation(body, brain);
        let mut genotype = random_genotype(r.genotype_length().unwrap(), k as u64);
        if body == GMM_10 {
            // GMM genes as the thesis initialises them (U[0, 1]): weights, means and spreads
            // that give a non-empty body
            for g in &mut genotype[..25] {
                *g = g.abs();
            }
        }
        let outcome = evaluate(&r, &genotype, &task, 1).unwrap_or_else(|e| panic!("{body} {brain}: {e}"));
        assert!(outcome.steps >= 1800, "{}", outcome.steps);
        assert!(outcome.metric("velocity").is_finite() && outcome.metric("distance").is_finite());
        assert!(outcome.units >= 1 && outcome.units <= 100);
    }
}

#[test]
fn evaluate_then_save_load_and_replay_gives_the_identical_outcome() {
    let task = Locomotion {
        duration: 10.0,
        ..Locomotion::default()
    };
    for brain in [HOMOGENEOUS, HETEROGENEOUS] {
        let r = representation(r#"{"kind": "direct", "width": 5, "height": 5}"#, brain);
        let genotype = random_genotype(r.genotype_length().unwrap(), 7);
        let direct = evaluate(&r, &genotype, &task, 3).unwrap();
        let json = robot_to_json(&r.robot(&genotype).unwrap(), Some("round trip"));
        let loaded = robot_from_json(&json, "memory").unwrap();
        assert_eq!(loaded, r.robot(&genotype).unwrap());
        let replayed = episode::run(&loaded, &task, 3, TraceLevel::None).unwrap();
        assert_eq!(
            direct.metric("distance").to_bits(),
            replayed.metric("distance").to_bits()
        );
        assert_eq!(direct, replayed);
    }
}
