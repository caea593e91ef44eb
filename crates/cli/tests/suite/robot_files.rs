//! Robot files through the CLI: save, replay bit-exactly, render, and clear errors for broken files.

use std::path::Path;
use std::process::Command;

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

fn vsrlab(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(VSRLAB).args(args).output().expect("vsrlab runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn distance(json: &str) -> String {
    let v: serde_json::Value = serde_json::from_str(json).unwrap_or_else(|e| panic!("{e}: {json}"));
    v["distance"].to_string()
}

#[test]
fn a_saved_robot_replays_to_the_identical_outcome_and_renders() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("biped.robot.json");
    let file = file.to_str().unwrap();
    let common = ["--duration", "5", "--seed", "3", "--json"];
    let mut args = vec![
        "simulate",
        "--body",
        "biped-4x3",
        "--brain",
        "distributed-mlp",
        "--save-robot",
        file,
    ];
    args.extend(common);
    let (ok, first, err) = vsrlab(&args);
    assert!(ok, "{err}");
    let mut args = vec!["simulate", "--robot", file];
    args.extend(common);
    let (ok, replay, err) = vsrlab(&args);
    assert!(ok, "{err}");
    assert_eq!(distance(&first), distance(&replay));
    // and on another task, with a video
    let gif = dir.path().join("replay.gif");
    let (ok, _, err) = vsrlab(&[
        "simulate",
        "--robot",
        file,
        "--task",
        "locomotion:hilly-1-10",
        "--duration",
        "1",
        "--video",
        gif.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(std::fs::metadata(&gif).unwrap().len() > 1000);
}

/// Saves a valid robot, applies `edit` to its JSON, and returns the error of replaying it.
fn error_after(edit: impl Fn(&mut serde_json::Value)) -> String {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("r.json");
    let (ok, _, err) = vsrlab(&[
        "simulate",
        "--body",
        "biped-4x3",
        "--brain",
        "distributed-mlp",
        "--duration",
        "0.1",
        "--save-robot",
        file.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let mut v: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    edit(&mut v);
    std::fs::write(&file, serde_json::to_string_pretty(&v).unwrap()).unwrap();
    let (ok, _, err) = vsrlab(&["simulate", "--robot", file.to_str().unwrap(), "--duration", "0.1"]);
    assert!(!ok, "a broken file must be rejected");
    assert!(!err.contains("panicked"), "{err}");
    err
}

#[test]
fn broken_robot_files_get_errors_naming_the_field() {
    let err = error_after(|v| {
        v["robot"]["brain"]["weights"].as_array_mut().unwrap().pop();
    });
    assert!(err.contains("weights") && err.contains("expected 45"), "{err}");
    let err = error_after(|v| v["robot"]["sensors"] = "uniform-a+zz-0".into());
    assert!(err.contains("sensors") && err.contains("zz"), "{err}");
    // a heterogeneous brain made for another grid: the body no longer matches the brain
    let err = error_after(|v| {
        v["robot"]["brain"]["layout"] = "heterogeneous".into();
    });
    assert!(err.contains("weights") && err.contains("expected 540"), "{err}");
    let err = error_after(|v| v["robot"]["body"] = serde_json::json!(["#.#", "..."]));
    assert!(err.contains("body"), "{err}");
    let err = error_after(|v| v["robot"]["brian"] = serde_json::json!({}));
    assert!(err.contains("brian"), "{err}");
}

#[test]
fn the_shipped_example_robot_replays() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/biped-distributed.robot.json");
    let (ok, out, err) = vsrlab(&[
        "simulate",
        "--robot",
        example.to_str().unwrap(),
        "--duration",
        "10",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(
        v["velocity"].as_f64().unwrap() > 0.5,
        "the example robot should walk: {out}"
    );
}

#[test]
fn huge_brains_on_the_command_line_are_refused_naming_the_field() {
    for (brain, field) in [("mlp:100000000", "hidden"), ("distributed-mlp:1000000000", "signals")] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_vsrlab"))
            .args(["simulate", "--brain", brain, "--duration", "1"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{brain}: {stderr}");
        assert!(
            stderr.contains("--brain") && stderr.contains(field),
            "{brain}: {stderr}"
        );
    }
}

/// EvoGym's own robot files through the command line: a `.npz` robot saved by EvoGym runs on an
/// EvoGym task named as EvoGym names it, and robots are written back in both of EvoGym's forms
/// (the body is kept; the reward of the same body with the same default brain is the same).
#[test]
fn evogym_robot_files_are_read_and_written() {
    let saved = concat!(env!("CARGO_MANIFEST_DIR"), "/../tasks/tests/data/evogym_robot.npz");
    let dir = tempfile::tempdir().unwrap();
    let reward = |json: &str| {
        let v: serde_json::Value = serde_json::from_str(json).unwrap_or_else(|e| panic!("{e}: {json}"));
        v["reward"].as_f64().unwrap_or_else(|| panic!("no reward in {json}"))
    };
    let npz = dir.path().join("again.npz");
    let evogym_json = dir.path().join("again.json");
    let run = |robot: &str, extra: &[&str]| {
        let mut args = vec!["simulate", "--robot", robot, "--task", "bridge-walker", "--json"];
        args.extend(extra);
        let (ok, out, err) = vsrlab(&args);
        assert!(ok, "{err}");
        reward(&out)
    };
    let first = run(saved, &["--save-robot", npz.to_str().unwrap()]);
    let json_args = [
        "--save-robot",
        evogym_json.to_str().unwrap(),
        "--robot-format",
        "evogym-json",
    ];
    assert_eq!(run(npz.to_str().unwrap(), &json_args), first);
    assert_eq!(run(evogym_json.to_str().unwrap(), &[]), first);
    let text = std::fs::read_to_string(&evogym_json).unwrap();
    assert!(
        text.contains("\"grid_width\": 5") && text.contains("\"neighbors\""),
        "{text}"
    );
    // a voxel robot has no .npz form, and nothing is written
    let wrong = dir.path().join("biped.npz");
    let (ok, _, err) = vsrlab(&[
        "simulate",
        "--body",
        "biped-4x3",
        "--save-robot",
        wrong.to_str().unwrap(),
    ]);
    assert!(!ok && err.contains("evogym-npz") && err.contains("voxel"), "{err}");
    assert!(!wrong.exists());
    // a broken .npz names the array
    let broken = dir.path().join("broken.npz");
    let mut bytes = std::fs::read(saved).unwrap();
    // the name in the local header and in the central directory
    while let Some(at) = bytes.windows(5).position(|w| w == b"arr_1") {
        bytes[at..at + 5].copy_from_slice(b"arr_9");
    }
    std::fs::write(&broken, bytes).unwrap();
    let (ok, _, err) = vsrlab(&["simulate", "--robot", broken.to_str().unwrap(), "--task", "walker"]);
    assert!(!ok && err.contains("arr_1: missing"), "{err}");
}

/// What an EvoGym brain sees follows the task it runs (issue 56, items 6 and 7): a short-form
/// body on BridgeWalker gets a brain for BridgeWalker's observation (it was refused as a Walker
/// brain), a body-only `.npz` robot on CaveCrawler prints the brain that runs (it printed
/// "0 parameters" and Walker's observation), and a brain with weights for another task is
/// refused with the way out.
#[test]
fn an_evogym_brain_follows_the_task_it_runs() {
    let body = "evogym:33333/33333/33333/33333/33333";
    let (ok, out, err) = vsrlab(&[
        "simulate",
        "--body",
        body,
        "--task",
        "bridge-walker",
        "--duration",
        "0.1",
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("BridgeWalker-v0's observation") && !out.contains(" Walker-v0"),
        "{out}"
    );
    let saved = concat!(env!("CARGO_MANIFEST_DIR"), "/../tasks/tests/data/evogym_robot.npz");
    let (ok, out, err) = vsrlab(&[
        "simulate",
        "--robot",
        saved,
        "--task",
        "cave-crawler",
        "--duration",
        "0.1",
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("CaveCrawler-v0's observation") && !out.contains("(0 parameters)"),
        "{out}"
    );
    let dir = tempfile::tempdir().unwrap();
    let walker = dir.path().join("walker.json");
    let (ok, _, err) = vsrlab(&[
        "simulate",
        "--body",
        body,
        "--task",
        "walker",
        "--duration",
        "0.1",
        "--save-robot",
        walker.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (ok, _, err) = vsrlab(&[
        "simulate",
        "--robot",
        walker.to_str().unwrap(),
        "--task",
        "cave-crawler",
    ]);
    assert!(
        !ok && err.contains("Walker-v0") && err.contains("--task walker"),
        "{err}"
    );
}

/// EvoGym's `.npz` robots with bytes changed at random (seeded): every run either succeeds (a
/// byte that changes nothing that matters) or exits with an error naming the archive or the
/// array; none crashes.
#[test]
fn corrupted_npz_robots_never_crash() {
    let saved = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tasks/tests/data/evogym_robot.npz"
    ))
    .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("r.npz");
    let mut state = 11u64;
    let (mut refused, mut accepted) = (0, 0);
    for case in 0..40 {
        let mut bytes = saved.clone();
        for _ in 0..1 + case % 3 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let at = (state >> 33) as usize % bytes.len();
            bytes[at] = (state >> 17) as u8;
        }
        std::fs::write(&file, &bytes).unwrap();
        let out = Command::new(VSRLAB)
            .args([
                "simulate",
                "--robot",
                file.to_str().unwrap(),
                "--task",
                "walker",
                "--duration",
                "0.1",
            ])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        match out.status.code() {
            Some(0) => accepted += 1,
            Some(1) => {
                refused += 1;
                let named = ["arr_0", "arr_1", "npz", "UTF-8"].iter().any(|w| err.contains(w));
                assert!(named, "case {case}: {err}");
            }
            other => panic!("case {case}: exit {other:?}: {err}"),
        }
    }
    assert!(refused > 10, "{refused} refused, {accepted} accepted");
}
