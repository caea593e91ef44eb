//! End to end, 3D voxel robots (docs/voxels3d.md): `vsrlab simulate --body 3d:…` with a video
//! frame and a replay, its robot file replayed to the same outcome, an evolution run, and errors
//! that name the field or option.

use crate::common;

use common::{ok, vsrlab};

#[test]
fn a_3d_robot_simulates_draws_replays_and_saves_a_robot_file_that_replays() {
    let dir = tempfile::tempdir().unwrap();
    let (frame, replay, robot) = (
        dir.path().join("f.png"),
        dir.path().join("r.replay.json"),
        dir.path().join("q.json"),
    );
    let first = ok(&[
        "simulate",
        "--body",
        "3d:quadruped",
        "--task",
        "locomotion3d",
        "--duration",
        "0.3",
        "--json",
        "--video",
        frame.to_str().unwrap(),
        "--replay",
        replay.to_str().unwrap(),
        "--save-robot",
        robot.to_str().unwrap(),
    ]);
    assert!(std::fs::read(&frame).unwrap().starts_with(b"\x89PNG"));
    let replay: serde_json::Value = serde_json::from_slice(&std::fs::read(&replay).unwrap()).unwrap();
    assert_eq!(
        replay["channels"]["voxel_xyz"]["per_frame"],
        28 * 3,
        "{}",
        replay["channels"]["voxel_xyz"]
    );
    let again = ok(&[
        "simulate",
        "--robot",
        robot.to_str().unwrap(),
        "--task",
        "locomotion3d",
        "--duration",
        "0.3",
        "--json",
    ]);
    let distance = |text: &str| {
        serde_json::from_str::<serde_json::Value>(text).unwrap()["distance"]
            .as_f64()
            .unwrap()
    };
    assert_eq!(distance(&first), distance(&again));
    assert!(distance(&first) > 0.0);
}

#[test]
fn an_experiment_evolves_a_3d_brain_and_bad_files_name_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let experiment = dir.path().join("e.toml");
    std::fs::write(
        &experiment,
        r#"name = "tiny3d"
runs = 1
seed = 1
[representation]
body = { kind = "voxel3d", body = "cube-2" }
brain = { kind = "distributed-mlp", signals = 1 }
[task]
kind = "locomotion3d"
duration = 0.1
obstacles = [[3, 0, 0]]
[optimizer]
kind = "ga"
population_size = 4
[stop]
evaluations = 8
"#,
    )
    .unwrap();
    let out = dir.path().join("out");
    ok(&["run", experiment.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    assert!(out.join("run-00/best.robot.json").exists());
    let best = std::fs::read_to_string(out.join("run-00/best.robot.json")).unwrap();
    assert!(best.contains("\"voxel3d\""), "{best}");
    // the analysis of 3D runs draws no empty 2D-descriptor figure and says why once (issue 56,
    // item 4: an empty descriptors.png and a warning per run)
    let analysis = dir.path().join("analysis");
    let text = ok(&["analyze", out.to_str().unwrap(), "--out", analysis.to_str().unwrap()]);
    assert!(analysis.join("fitness.png").is_file());
    assert!(!analysis.join("descriptors.png").exists() && !analysis.join("graph-size.png").exists());
    assert!(!text.contains("reads voxel robots only"), "{text}");
    assert_eq!(text.matches("of kind voxel3d").count(), 1, "{text}");
    let summary = std::fs::read_to_string(analysis.join("summary.md")).unwrap();
    assert!(!summary.contains("descriptors.png"), "{summary}");
    // no best.csv is written for them, and none is listed; no ISI columns without species
    assert!(!analysis.join("best.csv").exists());
    assert!(
        !summary.contains("best.csv") && !summary.contains("final ISI"),
        "{summary}"
    );

    let bad = dir.path().join("bad.json");
    std::fs::write(&bad, best.replace("cube-2", "#.#")).unwrap();
    let (success, text) = vsrlab(&["simulate", "--robot", bad.to_str().unwrap(), "--task", "locomotion3d"]);
    assert!(
        !success && text.contains("voxel3d.body") && text.contains("in pieces"),
        "{text}"
    );
    let (success, text) = vsrlab(&[
        "simulate",
        "--body",
        "3d:cube-2",
        "--sensors",
        "cpg,sonar",
        "--task",
        "locomotion3d",
    ]);
    assert!(!success && text.contains("unknown 3D sensor 'sonar'"), "{text}");
    std::fs::write(
        &experiment,
        std::fs::read_to_string(&experiment)
            .unwrap()
            .replace("[[3, 0, 0]]", "[[1, 1, 1]]"),
    )
    .unwrap();
    let (success, text) = vsrlab(&["validate", experiment.to_str().unwrap()]);
    assert!(!success && text.contains("obstacles[0]"), "{text}");
}

#[test]
fn an_affordance_episode_draws_its_votes_over_time_and_a_brain_without_votes_is_told() {
    let dir = tempfile::tempdir().unwrap();
    let votes = dir.path().join("votes.png");
    let out = ok(&[
        "simulate",
        "--body",
        "3d:flatworm",
        "--brain",
        "elman",
        "--task",
        "affordance:impassable",
        "--duration",
        "0.1",
        "--votes",
        votes.to_str().unwrap(),
    ]);
    assert!(out.contains("votes.png"), "{out}");
    assert!(std::fs::read(&votes).unwrap().starts_with(b"\x89PNG"));
    assert!(dir.path().join("votes.svg").exists());
    let (success, text) = vsrlab(&[
        "simulate",
        "--body",
        "3d:quadruped",
        "--task",
        "locomotion3d",
        "--duration",
        "0.05",
        "--votes",
        dir.path().join("none.png").to_str().unwrap(),
    ]);
    assert!(
        !success && text.contains("--votes") && text.contains("no votes"),
        "{text}"
    );
    assert!(!dir.path().join("none.png").exists());
}

/// A task's own length (`locomotion3d:0.05`) is the episode's, unless --duration is given
/// (issue 56, item 2: the CLI's default of 30 s used to win).
#[test]
fn a_tasks_own_length_holds_unless_duration_is_given() {
    let steps = |extra: &[&str]| {
        let mut args = vec![
            "simulate",
            "--body",
            "3d:quadruped",
            "--task",
            "locomotion3d:0.05",
            "--json",
        ];
        args.extend_from_slice(extra);
        let text = ok(&args);
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        (value["duration"].as_f64().unwrap(), value["steps"].as_f64().unwrap())
    };
    let (own, own_steps) = steps(&[]);
    assert_eq!(own, 0.05);
    let (given, given_steps) = steps(&["--duration", "0.1"]);
    assert_eq!(given, 0.1);
    assert!(
        (given_steps / own_steps - 2.0).abs() < 0.01,
        "{own_steps} {given_steps}"
    );
}
