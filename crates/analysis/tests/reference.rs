//! Checks against stored scikit-learn and SciPy figures (regenerate them with
//! `crates/analysis/scripts/make_reference.py`).

use serde_json::Value;
use std::path::PathBuf;
use vsrlab_analysis::forest::{cross_validate, Folds, ForestParams};
use vsrlab_analysis::stats::mann_whitney_u;

fn data(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(name)
}

fn load_csv(name: &str) -> (Vec<Vec<f64>>, Vec<usize>) {
    let mut r = csv::Reader::from_path(data(name)).unwrap();
    let mut x = Vec::new();
    let mut y = Vec::new();
    for rec in r.records() {
        let rec = rec.unwrap();
        let vals: Vec<f64> = rec.iter().map(|v| v.parse().unwrap()).collect();
        y.push(*vals.last().unwrap() as usize);
        x.push(vals[..vals.len() - 1].to_vec());
    }
    (x, y)
}

fn reference(name: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(data(name)).unwrap()).unwrap()
}

/// Our 5-fold accuracy (mean over `seeds` forest seeds, same unshuffled folds as the reference)
/// must be within 3 points of scikit-learn's mean over its seeds.
fn check_forest(name: &str, seeds: u64) {
    let (x, y) = load_csv(&format!("{name}.csv"));
    let classes = y.iter().max().unwrap() + 1;
    let r = reference("forest_reference.json");
    let sk = r["datasets"][name]["mean_accuracy"].as_f64().unwrap();
    let ours: f64 = (0..seeds)
        .map(|s| {
            cross_validate(
                &x,
                &y,
                classes,
                5,
                Folds::Contiguous,
                &ForestParams {
                    seed: s,
                    ..Default::default()
                },
            )
            .accuracy
        })
        .sum::<f64>()
        / seeds as f64;
    eprintln!(
        "{name}: ours {ours:.4}, scikit-learn {sk:.4}, difference {:+.4}",
        ours - sk
    );
    assert!(
        (ours - sk).abs() <= 0.03,
        "{name}: ours {ours:.4} vs scikit-learn {sk:.4}"
    );
}

#[test]
fn forest_matches_scikit_learn_on_iris() {
    check_forest("iris", 10);
}

#[test]
fn forest_matches_scikit_learn_on_wine() {
    check_forest("wine", 10);
}

#[test]
fn forest_matches_scikit_learn_on_digits() {
    check_forest("digits", 3);
}

#[test]
fn mann_whitney_matches_scipy() {
    let r = reference("mannwhitney_reference.json");
    let cases = r["cases"].as_array().unwrap();
    assert!(cases.len() >= 10);
    let mut worst = 0.0f64;
    for c in cases {
        let v = |k: &str| {
            c[k].as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect::<Vec<f64>>()
        };
        let got = mann_whitney_u(&v("x"), &v("y")).unwrap();
        let (u, p) = (c["u"].as_f64().unwrap(), c["p"].as_f64().unwrap());
        eprintln!(
            "{}: U {} / {u}, p {:.12} / {p:.12} ({:?})",
            c["name"], got.u, got.p, got.method
        );
        assert!((got.u - u).abs() < 1e-9, "{}: U {} vs {u}", c["name"], got.u);
        assert!((got.p - p).abs() < 1e-6, "{}: p {} vs {p}", c["name"], got.p);
        worst = worst.max((got.p - p).abs());
    }
    eprintln!("largest |p − p_scipy| = {worst:e}");
}
