//! End to end, the Hebbian chapter's tools: a tiny sweep (Hebbian vs its fixed-weight baseline,
//! with damage) → `vsrlab reassess` with and without damage → `vsrlab plasticity`; every table and
//! figure must appear, and the numbers must be sane.

use crate::common;

use common::{ok, vsrlab};
use std::path::Path;

const EXPERIMENT: &str = r#"
name = "tiny-hebb"
runs = 2
seed = 1

[representation]
body = "worm-4x1"
sensors = "uniform-a+t-0"

[task]
terrain = "hilly-1-10"
duration = 4.0
random_terrain_per_evaluation = true
damage = { at = 2.0, probability = 0.5 }

[optimizer]
kind = "es"
population_size = 6

[stop]
evaluations = 12

[sweep."representation.brain"]
hebbian = { kind = "hebbian" }
mlp = { kind = "hebbian", model = "dew" }
"#;

fn csv_rows(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

#[test]
fn reassess_and_plasticity_run_end_to_end() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let config = d.join("tiny.toml");
    std::fs::write(&config, EXPERIMENT).unwrap();
    let out = d.join("out");
    ok(&["run", config.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let hebb = out.join("tiny-hebb-hebbian");
    let mlp = out.join("tiny-hebb-mlp");
    let (hebb, mlp) = (hebb.to_str().unwrap(), mlp.to_str().unwrap());

    let re = d.join("re");
    let text = ok(&[
        "reassess",
        hebb,
        mlp,
        "--episodes",
        "3",
        "--window",
        "1",
        "--out",
        re.to_str().unwrap(),
    ]);
    assert!(
        text.contains("tiny-hebb-hebbian") && text.contains("Mann–Whitney"),
        "{text}"
    );
    let rows = csv_rows(&re.join("reassess.csv"));
    assert_eq!(rows.len(), 2 * 2 * 3, "2 settings × 2 runs × 3 episodes");
    for f in ["reassess-boxplot", "reassess-velocity-over-time"] {
        assert!(
            re.join(format!("{f}.png")).is_file() && re.join(format!("{f}.svg")).is_file(),
            "{f}"
        );
    }
    // without the experiment's damage the episodes differ
    let healed = d.join("healed");
    ok(&[
        "reassess",
        hebb,
        mlp,
        "--episodes",
        "3",
        "--damage",
        "none",
        "--out",
        healed.to_str().unwrap(),
    ]);
    assert_ne!(rows, csv_rows(&healed.join("reassess.csv")));

    let pl = d.join("pl");
    let text = ok(&[
        "plasticity",
        hebb,
        "--freeze-at",
        "0,2,4",
        "--weights-at",
        "1,4",
        "--episodes",
        "2",
        "--bins",
        "8",
        "--out",
        pl.to_str().unwrap(),
    ]);
    assert!(
        text.contains("restart") && text.contains("continue") && text.contains("unfrozen"),
        "{text}"
    );
    let frozen = csv_rows(&pl.join("frozen.csv"));
    // 2 runs × (3 times × 2 protocols + 1 unfrozen) × 2 episodes
    assert_eq!(frozen.len(), 2 * 7 * 2);
    assert!(frozen.iter().all(|r| r[5].parse::<f64>().unwrap().is_finite()));
    // learning until the end of the episode is the unfrozen run itself
    let velocity = |protocol: &str, time: &str| -> Vec<String> {
        frozen
            .iter()
            .filter(|r| r[2] == protocol && r[3] == time)
            .map(|r| r[5].clone())
            .collect()
    };
    assert_eq!(velocity("continue", "4"), velocity("unfrozen", "4"));
    let weights = csv_rows(&pl.join("weights.csv"));
    assert_eq!(weights.len(), 2 * 8, "2 times × 8 bins");
    for f in ["frozen", "weights"] {
        assert!(pl.join(format!("{f}.png")).is_file(), "{f}");
    }

    // a fixed-weight brain has nothing to freeze
    let (success, text) = vsrlab(&["plasticity", mlp, "--out", d.join("bad").to_str().unwrap()]);
    assert!(!success && text.contains("no plastic weights"), "{text}");
    // bad options are named
    let (success, text) = vsrlab(&[
        "reassess",
        hebb,
        "--damage",
        "2:7",
        "--out",
        d.join("bad").to_str().unwrap(),
    ]);
    assert!(!success && text.contains("probability"), "{text}");
    let (success, text) = vsrlab(&[
        "reassess",
        hebb,
        "--terrain",
        "hilly-x",
        "--out",
        d.join("bad").to_str().unwrap(),
    ]);
    assert!(!success && text.contains("terrain"), "{text}");
}
