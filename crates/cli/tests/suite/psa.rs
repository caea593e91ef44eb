//! End to end, the PSA tools (docs/psa.md): `vsrlab simulate --body psa…` on each PSA task with a
//! video frame, its robot file replayed, `vsrlab inflate`, and errors that name their option.

use crate::common;

use common::{ok, vsrlab};

#[test]
fn simulate_runs_a_psa_on_each_task_and_saves_a_robot_that_replays() {
    let dir = tempfile::tempdir().unwrap();
    for task in ["escape", "carrier", "locomotion:psa-hilly-3-10"] {
        let frame = dir.path().join("frame.png");
        let robot = dir.path().join("psa.json");
        let first = ok(&[
            "simulate",
            "--body",
            "psa:small",
            "--task",
            task,
            "--duration",
            "2",
            "--json",
            "--video",
            frame.to_str().unwrap(),
            "--save-robot",
            robot.to_str().unwrap(),
        ]);
        assert!(first.contains("\"brain\": \"heads\""), "{first}");
        assert!(frame.exists());
        let again = ok(&[
            "simulate",
            "--robot",
            robot.to_str().unwrap(),
            "--task",
            task,
            "--duration",
            "2",
            "--json",
        ]);
        let metric = |text: &str| {
            let v: serde_json::Value = serde_json::from_str(text).unwrap();
            let key = if task == "escape" { "distance" } else { "velocity" };
            v[key].as_f64().unwrap()
        };
        assert_eq!(
            metric(&first),
            metric(&again),
            "{task}: the robot file replays the same episode"
        );
    }
}

#[test]
fn inflate_writes_its_table_and_figure() {
    let dir = tempfile::tempdir().unwrap();
    let text = ok(&[
        "inflate",
        "--sizes",
        "small,medium",
        "--duration",
        "3",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert!(text.contains("| small |") && text.contains("| medium |"), "{text}");
    let csv = std::fs::read_to_string(dir.path().join("inflation.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 2 * 180);
    assert!(dir.path().join("inflation.png").exists());
}

#[test]
fn bad_psa_options_name_the_option() {
    for (args, expected) in [
        (
            vec!["simulate", "--body", "psa:huge"],
            "--body: unknown PSA size 'huge'",
        ),
        (vec!["simulate", "--body", "psa", "--brain", "nope"], "--brain:"),
        (vec!["simulate", "--body", "psa", "--task", "escape:-3"], "--task:"),
        (vec!["inflate", "--sizes", "tiny"], "--sizes: unknown size 'tiny'"),
        (vec!["inflate", "--duration", "0.5"], "--duration: must be in [2, 600]"),
    ] {
        let (success, text) = vsrlab(&args);
        assert!(!success && text.contains(expected), "{args:?}: {text}");
    }
}

#[test]
fn task_of_replays_an_evolved_psa_on_its_experiment_s_task() {
    let dir = tempfile::tempdir().unwrap();
    let config = dir.path().join("psa.toml");
    std::fs::write(
        &config,
        r#"
name = "psa"
runs = 1
seed = 2
[representation]
body = { kind = "psa", size = "small" }
brain = { kind = "heads" }
[task]
kind = "carrier"
duration = 3.0
ball = { radius = 1.25, x = 5.0, y = 13.5, density = 500.0, friction = 10.0 }
[optimizer]
kind = "cma-es"
population_size = 6
[stop]
evaluations = 12
"#,
    )
    .unwrap();
    let out = dir.path().join("out");
    ok(&["run", config.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let robot = out.join("run-00/best.robot.json");
    let replay = ok(&[
        "simulate",
        "--robot",
        robot.to_str().unwrap(),
        "--task-of",
        out.to_str().unwrap(),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&replay).unwrap();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let best = summary.to_string();
    let velocity = v["velocity"].as_f64().unwrap();
    assert_eq!(v["duration"].as_f64(), Some(3.0), "the experiment's duration");
    assert!(
        best.contains(&format!("{velocity}")),
        "replayed {velocity}, summary {best}"
    );
    // the default task (a medium PSA's ball) is another episode
    let other = ok(&[
        "simulate",
        "--robot",
        robot.to_str().unwrap(),
        "--task",
        "carrier",
        "--duration",
        "3",
        "--json",
    ]);
    let w: serde_json::Value = serde_json::from_str(&other).unwrap();
    assert_ne!(w["velocity"].as_f64(), Some(velocity));
}
