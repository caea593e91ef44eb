//! End to end, the graph chapter's tools (docs/ch4.1.md): a tiny graph-genotype experiment with
//! two modularity biases → `vsrlab modules` → `vsrlab reassemble` → the re-optimisation it writes
//! → `vsrlab transferability`, plus a video frame with the graph drawn and the errors that name
//! their option.

use crate::common;

use common::{ok, vsrlab};

const CONFIG: &str = r#"
name = "donors"
runs = 3
seed = 2

[representation]
body = "biped-4x3"
sensors = "uniform-a+t-0"
brain = { kind = "graph" }

[genotype]
kind = "graph"
modules = "legs-torso"
operators = { add_node = 0.4, add_edge = 0.4, mutate_edge = 0.2 }

[task]
terrain = "flat"
duration = 1.0

[optimizer]
kind = "ga"
population_size = 4
offspring_size = 4
mutation_probability = 1.0

[stop]
generations = 4

[output]
save_best = true

[sweep]
"genotype.modularity" = ["plain", "modular"]
"#;

#[test]
fn modules_reassembly_reoptimisation_and_transferability_end_to_end() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let config = d.join("donors.toml");
    std::fs::write(&config, CONFIG).unwrap();
    let out = d.join("out");
    let out_s = out.to_str().unwrap();
    ok(&["run", config.to_str().unwrap(), "--out", out_s]);

    // every evolved robot gets a module, with a finite compactness
    let text = ok(&[
        "modules",
        &format!("{out_s}/donors-plain"),
        &format!("{out_s}/donors-modular"),
        "--out",
        &format!("{out_s}/modules"),
    ]);
    assert_eq!(text.matches("module of").count(), 6, "{text}");
    let csv = std::fs::read_to_string(out.join("modules/modules.csv")).unwrap();
    for line in csv.lines().skip(1) {
        let c: f64 = line.split(',').nth(3).unwrap().parse().unwrap();
        assert!((0.0..=1.0).contains(&c), "{line}");
    }

    for bias in ["plain", "modular"] {
        let re = format!("{out_s}/re-{bias}");
        let text = ok(&[
            "reassemble",
            &format!("{out_s}/donors-{bias}"),
            "--cut",
            "legs",
            "--generations",
            "2",
            "--out",
            &re,
        ]);
        assert_eq!(text.matches("η_num").count(), 3, "{text}");
        assert!(text.contains("#..#/#..#/#..#"), "{text}");
        ok(&[
            "run",
            &format!("{re}/reoptimise.toml"),
            "--out",
            &format!("{re}/reoptimised"),
        ]);
        // the hybrid is the first member of its re-optimisation: its size is in generation 1
        let hybrid: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(format!("{re}/hybrid-00.robot.json")).unwrap()).unwrap();
        assert_eq!(hybrid["robot"]["brain"]["kind"], "graph");
    }
    let text = ok(&[
        "transferability",
        &format!("{out_s}/re-plain"),
        &format!("{out_s}/re-modular"),
        "--out",
        &format!("{out_s}/tr"),
    ]);
    assert!(
        text.contains("| donors-plain | 3 |") && text.contains("| donors-modular | 3 |"),
        "{text}"
    );
    assert!(text.contains("Mann–Whitney final ρ"), "{text}");
    let csv = std::fs::read_to_string(out.join("tr/transferability.csv")).unwrap();
    assert_eq!(csv.lines().count(), 7);
    for line in csv.lines().skip(1) {
        let rho: f64 = line.split(',').nth(2).unwrap().parse().unwrap();
        assert!(rho.is_finite(), "{line}");
    }
    assert!(out.join("tr/rho.png").exists() && out.join("tr/eta-num-boxplot.png").exists());

    // analyze draws |G| for graph runs
    ok(&[
        "analyze",
        &format!("{out_s}/donors-plain"),
        "--out",
        &format!("{out_s}/analysis"),
    ]);
    assert!(out.join("analysis/graph-size.png").exists());

    // a frame of an evolved robot with its graph drawn, and without
    let best = out.join("donors-plain/run-00/best.robot.json");
    let frame = |draw: &str, name: &str| {
        let path = d.join(name);
        ok(&[
            "simulate",
            "--robot",
            best.to_str().unwrap(),
            "--duration",
            "0.5",
            "--draw",
            draw,
            "--video",
            path.to_str().unwrap(),
        ]);
        std::fs::read(path).unwrap()
    };
    assert_ne!(
        frame("graph", "with.png"),
        frame("none", "without.png"),
        "the graph layer draws something"
    );
}

#[test]
fn graph_commands_name_the_option_at_fault() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().to_str().unwrap();
    let (good, err) = vsrlab(&["transferability", d, "--out", &format!("{d}/x")]);
    assert!(
        !good && err.contains("transfer.csv") && err.contains("reassemble"),
        "{err}"
    );
    let (good, err) = vsrlab(&["modules", d, "--sizes", "5..2"]);
    assert!(!good && err.contains("sizes") && err.contains("5..2"), "{err}");
    let (good, err) = vsrlab(&["reassemble", d, "--cut", "legs", "--out", &format!("{d}/y")]);
    assert!(!good && err.contains(d), "{err}");
}
