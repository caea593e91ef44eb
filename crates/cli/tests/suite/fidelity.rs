//! `vsrlab fidelity` (docs/fidelity.md, "The protocol"): the CI subset of the protocol's cases,
//! and errors that name the option or the reference's line.

use crate::common;
use common::{ok, vsrlab};

#[test]
fn the_ci_subset_of_the_protocol_passes_under_the_faithful_solver() {
    // the 2021 biped actuated at +1, 20 starts (k = ±1 … ±10): the original's ensemble against
    // the sequential-impulse solver's, with every test computed
    let args = [
        "fidelity",
        "--solver",
        "sequential-impulses",
        "--cases",
        "2021/biped-4x3/flat/constant:1",
        "--starts",
        "20",
        "--json",
    ];
    let text = ok(&args);
    let answer: serde_json::Value = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert_eq!(answer["passed"], 1, "{text}");
    let case = &answer["cases"][0];
    assert_eq!(case["case"], "2021/biped-4x3/flat/constant:1");
    assert_eq!(case["n"], 20);
    let values = case["values"].as_array().unwrap();
    assert_eq!(values.len(), 20);
    assert!(values.iter().all(|v| v.as_f64().unwrap().is_finite()));
    let e = &case["equivalence"];
    let (low, high, margin) = (
        e["low"].as_f64().unwrap(),
        e["high"].as_f64().unwrap(),
        e["margin"].as_f64().unwrap(),
    );
    assert!(margin > 0.0 && -margin <= low && low <= high && high <= margin, "{e}");
    assert!(case["ks"]["p"].as_f64().unwrap() >= 0.001);
    // the same table on every run (but the CPU seconds)
    let untimed = |text: &str| {
        let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
        v["cpu_seconds"] = serde_json::Value::Null;
        v["cases"][0]["seconds"] = serde_json::Value::Null;
        v
    };
    assert_eq!(untimed(&ok(&args)), untimed(&text));
}

#[test]
fn bad_options_and_references_are_named() {
    let (success, text) = vsrlab(&["fidelity", "--cases", "no-such-case"]);
    assert!(
        !success && text.contains("--cases: no reference case matches"),
        "{text}"
    );
    let (success, text) = vsrlab(&["fidelity", "--set", "physics.contact_hertz"]);
    assert!(
        !success && text.contains("--set \"physics.contact_hertz\": KEY=VALUE expected"),
        "{text}"
    );
    let (success, text) = vsrlab(&[
        "fidelity",
        "--cases",
        "2021/biped-4x3/flat/phase",
        "--set",
        "physics.no_such=1",
    ]);
    assert!(
        !success && text.contains("case 2021/biped-4x3/flat/phase") && text.contains("no_such"),
        "{text}"
    );
    let (success, text) = vsrlab(&["fidelity", "--starts", "2"]);
    assert!(!success && text.contains("--starts: at least 4"), "{text}");
    let (success, text) = vsrlab(&["fidelity", "--reference", "/no/such/file.csv"]);
    assert!(!success && text.contains("--reference /no/such/file.csv"), "{text}");
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.csv");
    std::fs::write(
        &bad,
        "preset,body,terrain,brain,k,velocity\n2021,biped-4x3,flat,phase,1,fast\n",
    )
    .unwrap();
    let (success, text) = vsrlab(&["fidelity", "--reference", bad.to_str().unwrap()]);
    assert!(
        !success && text.contains("reference, line 2: velocity: not a number"),
        "{text}"
    );
}
