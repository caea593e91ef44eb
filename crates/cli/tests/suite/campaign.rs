//! `vsrlab campaign`: two files side by side into one folder each, a summary table, refusal
//! without `--resume`, resume of a finished campaign, and `--ray` without Python's package.

use crate::common::{ok, vsrlab};
use std::process::Command;

fn file(dir: &std::path::Path, name: &str, seed: u64) -> String {
    let path = dir.join(format!("{name}.toml"));
    let text = format!(
        r#"
name = "{name}"
runs = 2
seed = {seed}
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = {{ kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }}
[task]
terrain = "flat"
duration = 1.0
fitness = "velocity"
[optimizer]
kind = "ga"
population_size = 4
offspring_size = 4
[stop]
evaluations = 12
"#
    );
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn a_campaign_writes_a_folder_per_setting_and_a_table_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (file(dir.path(), "first", 1), file(dir.path(), "second", 2));
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let text = ok(&["campaign", &a, &b, "--out", out, "--threads", "2"]);
    assert!(text.contains("campaign: 2 settings, 4 runs side by side"), "{text}");
    let header = text.lines().find(|l| l.starts_with("setting")).expect("a table");
    assert!(header.contains("median best"), "{header}");
    for name in ["first", "second"] {
        let row = text
            .lines()
            .find(|l| l.starts_with(&format!("{name} ")))
            .expect("a row");
        assert!(row.contains(" 2/2 ") && row.contains(" 24 "), "{row}");
        for run in ["run-00", "run-01"] {
            assert!(dir
                .path()
                .join("out")
                .join(name)
                .join(run)
                .join("best.robot.json")
                .is_file());
        }
    }
    let (success, again) = vsrlab(&["campaign", &a, &b, "--out", out]);
    assert!(!success && again.contains("--resume"), "{again}");
    let resumed = ok(&["campaign", &a, &b, "--out", out, "--resume"]);
    assert!(resumed.contains("first ") && resumed.contains(" 2/2 "), "{resumed}");
}

#[test]
fn ray_without_pythons_package_says_how_to_install_it() {
    let dir = tempfile::tempdir().unwrap();
    let a = file(dir.path(), "first", 1);
    for command in [vec!["campaign", a.as_str()], vec!["run", a.as_str()]] {
        let out = Command::new(env!("CARGO_BIN_EXE_vsrlab"))
            .args(&command)
            .args(["--out", dir.path().join("o").to_str().unwrap(), "--ray", "127.0.0.1:1"])
            .env("VSRLAB_PYTHON", dir.path().join("no-python"))
            .output()
            .unwrap();
        let text = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{text}");
        assert!(
            text.contains("pip install './python[ray]'") && text.lines().count() == 1,
            "{text}"
        );
    }
    assert!(!dir.path().join("o").exists(), "nothing written");
}

#[test]
fn solver_replaces_every_file_s_and_a_bad_one_is_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (file(dir.path(), "first", 1), file(dir.path(), "second", 2));
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let (success, text) = vsrlab(&["campaign", &a, &b, "--out", out, "--solver", "dyn4j"]);
    assert!(!success && text.contains("--solver: expected soft-substeps"), "{text}");
    assert!(!dir.path().join("out").exists(), "nothing written");
    ok(&["campaign", &a, &b, "--out", out, "--solver", "sequential-impulses"]);
    for name in ["first", "second"] {
        let resolved = std::fs::read_to_string(dir.path().join("out").join(name).join("experiment.toml")).unwrap();
        assert!(resolved.contains("solver = \"sequential-impulses\""), "{resolved}");
    }
}
