//! `vsrlab bench`: the JSON rows carry the speed and, where vsr-model.md §7 measured the original on
//! the same robot, the ratio to the version of the original that the preset reproduces.

use std::process::Command;

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

/// Runs a tiny bench (1 s episodes, one episode per row) and returns its JSON.
fn bench(preset: &str, robots: &str) -> serde_json::Value {
    let args = [
        "bench",
        "--duration",
        "1",
        "--min-seconds",
        "0",
        "--threads",
        "2",
        "--preset",
        preset,
        "--robots",
        robots,
        "--json",
    ];
    let out = Command::new(VSRLAB).args(args).output().expect("vsrlab runs");
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout).expect("bench prints JSON")
}

#[test]
fn single_rows_compare_with_the_matching_original_version() {
    for (preset, version, biped, worm) in [("2022", "HEAD", 2300.0, 910.0), ("2021", "v1.10.0", 1900.0, 1150.0)] {
        let json = bench(preset, "biped-4x3,worm-10x4,box-10x10");
        assert_eq!(json["preset"], preset);
        let rows = json["rows"].as_array().unwrap();
        // a single and a parallel row per robot, in the requested order
        assert_eq!(rows.len(), 6, "{json}");
        for row in rows {
            let robot = row["robot"].as_str().unwrap();
            let steps = row["steps"].as_f64().unwrap();
            let voxels = row["voxels"].as_f64().unwrap();
            assert_eq!(steps, 60.0 * row["episodes"].as_f64().unwrap(), "{row}");
            let per_s = row["steps_per_s"].as_f64().unwrap();
            assert!(per_s > 0.0 && (row["voxel_steps_per_s"].as_f64().unwrap() - per_s * voxels).abs() < 1e-6 * per_s);
            let expected = match robot {
                "biped-4x3" => Some(biped),
                "worm-10x4" => Some(worm),
                _ => None,
            };
            assert_eq!(row["original_steps_per_s"].as_f64(), expected, "{row}");
            match (expected, row["mode"].as_str().unwrap()) {
                (Some(original), "single") => {
                    assert_eq!(row["original_version"], version);
                    let ratio = row["ratio_to_original"].as_f64().unwrap();
                    assert!((ratio - per_s / original).abs() < 1e-9 * ratio, "{row}");
                }
                _ => assert!(row["ratio_to_original"].is_null(), "{row}"),
            }
        }
    }
}

#[test]
fn unknown_preset_is_an_error_naming_it() {
    let out = Command::new(VSRLAB)
        .args(["bench", "--duration", "1", "--min-seconds", "0", "--preset", "2019"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("2019"));
}
