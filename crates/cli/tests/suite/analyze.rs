//! End to end: two tiny experiments → `vsrlab label --auto` → `vsrlab analyze` with and without
//! labels; every figure and table must appear.

use std::path::Path;
use std::process::Command;

const VSRLAB: &str = env!("CARGO_BIN_EXE_vsrlab");

fn vsrlab(args: &[&str]) -> String {
    let out = Command::new(VSRLAB).args(args).output().expect("vsrlab runs");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "vsrlab {args:?} failed:\n{text}");
    text
}

fn experiment(dir: &Path, name: &str, optimizer: &str) -> String {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "name = \"{name}\"\nruns = 2\nseed = 3\n\n[representation]\n\
             body = {{ kind = \"direct\", width = 3, height = 3, on_empty = \"single-voxel\" }}\n\
             sensors = \"uniform-vxy+a+t-0\"\n\
             brain = {{ kind = \"distributed-mlp\", layout = \"homogeneous\", signals = 1, hidden = [] }}\n\n\
             [task]\nduration = 2.0\n\n[optimizer]\n{optimizer}\n\n[stop]\nevaluations = 48\n\n[output]\nsnapshot_every = 16\n"
        ),
    )
    .unwrap();
    path.display().to_string()
}

#[test]
fn label_then_analyze_two_settings() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let ga = experiment(d, "tiny-ga", "kind = \"ga\"\npopulation_size = 8\noffspring_size = 8");
    let es = experiment(d, "tiny-es", "kind = \"es\"\npopulation_size = 8");
    let (out_ga, out_es) = (d.join("out/ga"), d.join("out/es"));
    vsrlab(&["run", &ga, "--out", out_ga.to_str().unwrap()]);
    vsrlab(&["run", &es, "--out", out_es.to_str().unwrap()]);
    let results = d.join("out");
    let results = results.to_str().unwrap();

    // without --out, the analysis goes inside the results folder, not the current one
    let out = Command::new(VSRLAB)
        .args(["analyze", results])
        .current_dir(d)
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(d.join("out/analysis/summary.md").is_file());
    assert!(!d.join("analysis").exists());

    let plain = d.join("plain");
    vsrlab(&["analyze", results, "--out", plain.to_str().unwrap()]);
    for f in ["fitness", "best-boxplot", "descriptors", "pca-best"] {
        for ext in ["png", "svg"] {
            assert!(plain.join(format!("{f}.{ext}")).is_file(), "{f}.{ext}");
        }
    }
    let md = std::fs::read_to_string(plain.join("summary.md")).unwrap();
    assert!(
        md.contains("tiny-es") && md.contains("tiny-ga") && md.contains("No labels given"),
        "{md}"
    );

    // --group-by pools by settings of the resolved files: a key both share pools all 4 runs
    let grouped = d.join("grouped");
    let g = grouped.to_str().unwrap();
    vsrlab(&["analyze", results, "--out", g, "--group-by", "optimizer.kind"]);
    let csv = std::fs::read_to_string(grouped.join("summary.csv")).unwrap();
    assert!(
        csv.contains("optimizer.kind=es") && csv.contains("optimizer.kind=ga"),
        "{csv}"
    );
    vsrlab(&[
        "analyze",
        results,
        "--out",
        g,
        "--group-by",
        "stop.evaluations,task.duration",
    ]);
    let csv = std::fs::read_to_string(grouped.join("summary.csv")).unwrap();
    assert_eq!(csv.lines().count(), 2, "{csv}");
    assert!(csv.contains("\"stop.evaluations=48, task.duration=2.0\",4"), "{csv}");

    let lab = d.join("lab");
    vsrlab(&[
        "label",
        results,
        "--out",
        lab.to_str().unwrap(),
        "--count",
        "12",
        "--auto",
        "--width",
        "160",
    ]);
    assert!(lab.join("index.html").is_file() && lab.join("videos/r-0001.gif").is_file());
    let replay = std::fs::read_to_string(lab.join("replays/r-0001.replay.json")).unwrap();
    assert!(
        replay.starts_with("{\"format\":\"vsrlab-replay\""),
        "the viewer's replay of each video"
    );
    let labels = lab.join("labels.csv");
    assert_eq!(std::fs::read_to_string(&labels).unwrap().lines().count(), 13);

    let full = d.join("full");
    vsrlab(&[
        "analyze",
        results,
        "--labels",
        labels.to_str().unwrap(),
        "--out",
        full.to_str().unwrap(),
        "--folds",
        "3",
    ]);
    for f in [
        "fitness",
        "best-boxplot",
        "descriptors",
        "pca-best",
        "isi",
        "isi-boxplot",
        "species",
    ] {
        assert!(full.join(format!("{f}.png")).is_file(), "{f}.png");
    }
    let csv = std::fs::read_to_string(full.join("summary.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
    assert!(std::fs::read_to_string(full.join("pvalues.csv"))
        .unwrap()
        .contains("isi,tiny-es,tiny-ga"));

    // Missing inputs are named, not skipped silently.
    let text = vsrlab(&["analyze", results, "--out", d.join("again").to_str().unwrap()]);
    assert!(text.contains("setting tiny-ga: only 2 run(s)"), "{text}");
    std::fs::remove_file(out_ga.join("run-01/generations.csv")).unwrap();
    std::fs::remove_file(out_ga.join("run-01/best.robot.json")).unwrap();
    let text = vsrlab(&["analyze", results, "--out", d.join("missing").to_str().unwrap()]);
    assert!(
        text.contains("run-01: no generations.csv; the run is left out of the fitness figure"),
        "{text}"
    );
    assert!(text.contains("run-01: no best.robot.json"), "{text}");
}

#[test]
fn label_refuses_zero_bins_naming_the_option() {
    let tmp = tempfile::tempdir().unwrap();
    let out = Command::new(VSRLAB)
        .args(["label", tmp.path().to_str().unwrap(), "--bins", "0"])
        .args(["--out", tmp.path().join("lab").to_str().unwrap()])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("bins") && err.contains("got 0"), "{err}");
    assert!(!tmp.path().join("lab").exists());
}

/// A tiny affordance run (ch. 5.1, two objectives): `analyze` writes the Pareto table and
/// figures, the knee and specialist boxplots, and each run's knee and specialists as robot files
/// that replay to the objectives the table gives them.
#[test]
fn analyze_two_objective_runs_saves_knees_that_replay_to_their_scores() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let file = d.join("aff.toml");
    std::fs::write(
        &file,
        "name = \"aff\"\nruns = 1\nseed = 2\n\n[representation]\n\
         body = { kind = \"voxel3d\", body = \"flatworm\", sensors = \"cpg:5,touch,floor,vy,vx\" }\n\
         brain = { kind = \"elman\" }\n\n\
         [task]\nkind = \"affordance\"\nduration = 0.05\npenalties = false\n\n\
         [optimizer]\nkind = \"nsga2\"\npopulation_size = 4\noffspring_size = 4\n\n[stop]\nevaluations = 8\n",
    )
    .unwrap();
    let out = d.join("out");
    vsrlab(&["run", file.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let analysis = d.join("analysis");
    let text = vsrlab(&["analyze", out.to_str().unwrap(), "--out", analysis.to_str().unwrap()]);
    for figure in [
        "pareto",
        "knee-sensing",
        "knee-locomotion",
        "specialist-sensing",
        "specialist-locomotion",
    ] {
        assert!(analysis.join(format!("{figure}.png")).exists(), "{figure}: {text}");
    }
    let csv = std::fs::read_to_string(analysis.join("pareto.csv")).unwrap();
    let knee: Vec<&str> = csv
        .lines()
        .find(|l| l.split(',').nth(5).is_some_and(|r| r.split('+').any(|r| r == "knee")))
        .expect("a knee row")
        .split(',')
        .collect();
    let robots: Vec<_> = std::fs::read_dir(analysis.join("pareto-robots"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    let knee_file = robots
        .iter()
        .find(|p| p.to_string_lossy().contains("-run-00-knee"))
        .unwrap_or_else(|| panic!("{robots:?}"));
    let replayed = vsrlab(&[
        "simulate",
        "--robot",
        knee_file.to_str().unwrap(),
        "--task-of",
        file.to_str().unwrap(),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&replayed).unwrap();
    assert_eq!(
        v["locomotion"].as_f64().unwrap(),
        knee[3].parse::<f64>().unwrap(),
        "{replayed}"
    );
    assert_eq!(v["sensing"].as_f64().unwrap(), knee[4].parse::<f64>().unwrap());
}
