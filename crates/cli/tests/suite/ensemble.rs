//! `vsrlab simulate --ensemble` and `--initial-x` (docs/fidelity.md): shifted starts, their
//! summary, the same numbers on every run, and errors that name the option.

use crate::common;
use common::{ok, vsrlab};

fn json(text: &str) -> serde_json::Value {
    serde_json::from_str(text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

#[test]
fn an_ensemble_summarises_shifted_starts_and_repeats_exactly() {
    let args = [
        "simulate",
        "--ensemble",
        "6",
        "--shift",
        "1e-3",
        "--duration",
        "3",
        "--json",
    ];
    let first = json(&ok(&args));
    let shifts: Vec<f64> = first["shifts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(shifts, vec![-3e-3, -2e-3, -1e-3, 1e-3, 2e-3, 3e-3]);
    let values: Vec<f64> = first["values"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(values.len(), 6);
    assert!(values.iter().all(|v| v.is_finite()));
    let s = &first["summary"];
    let (min, max) = (s["min"].as_f64().unwrap(), s["max"].as_f64().unwrap());
    assert_eq!(min, values.iter().copied().fold(f64::INFINITY, f64::min));
    assert_eq!(max, values.iter().copied().fold(f64::NEG_INFINITY, f64::max));
    assert!(s["median"].as_f64().unwrap() >= min && s["median"].as_f64().unwrap() <= max);
    let again = json(&ok(&args));
    assert_eq!(again["values"], first["values"], "bit-identical on every run");
    let text = ok(&["simulate", "--ensemble", "4", "--duration", "2"]);
    assert!(text.contains("median") && text.contains("parting"), "{text}");
}

#[test]
fn initial_x_moves_the_start() {
    let dir = tempfile::tempdir().unwrap();
    let first_center = |extra: &[&str]| {
        let path = dir.path().join("r.replay.json");
        let mut args = vec!["simulate", "--duration", "0.5", "--replay", path.to_str().unwrap()];
        args.extend_from_slice(extra);
        ok(&args);
        let replay = json(&std::fs::read_to_string(&path).unwrap());
        replay["channels"]["center"]["data"][0].as_f64().unwrap() * replay["quantum"].as_f64().unwrap()
    };
    let moved = first_center(&["--initial-x", "20"]) - first_center(&[]);
    assert!((moved - 9.0).abs() < 0.05, "moved by {moved}");
}

#[test]
fn ensemble_errors_name_the_option() {
    for (args, expect) in [
        (vec!["simulate", "--ensemble", "1"], "--ensemble: at least 2"),
        (vec!["simulate", "--ensemble", "4", "--shift", "0"], "--shift"),
        (
            vec!["simulate", "--ensemble", "4", "--duration", "1", "--metric", "nope"],
            "--metric",
        ),
        (
            vec!["simulate", "--task", "jump", "--initial-x", "3"],
            "--initial-x: a jump task has no start position",
        ),
        (
            vec!["simulate", "--task", "jump", "--ensemble", "4", "--duration", "1"],
            "no start position",
        ),
    ] {
        let (success, text) = vsrlab(&args);
        assert!(!success, "{args:?}");
        assert!(text.contains(expect), "{args:?}: {text}");
    }
}

#[test]
fn numeric_options_take_negative_numbers_and_refuse_non_finite_ones_by_name() {
    // a negative start is a value, not an unknown option (the task then says what it allows)
    let (_, text) = vsrlab(&["simulate", "--duration", "0.1", "--initial-x", "-50"]);
    assert!(!text.contains("unexpected argument"), "{text}");
    for (option, value) in [("--duration", "nan"), ("--transient", "inf"), ("--initial-x", "NaN")] {
        let (success, text) = vsrlab(&["simulate", option, value]);
        assert!(!success, "{option} {value}");
        assert!(
            text.contains(option) && text.contains("must be a finite number"),
            "{option} {value}: {text}"
        );
    }
}
