//! Co-design end to end (thesis ch. 5.2): both encodings run with PPO inside evolution, resume
//! from their checkpoints, and `vsrlab codesign` draws their learning curves; bad tables are
//! refused naming the field.

use crate::common::{ok, vsrlab};

/// A tiny co-design experiment: Walker cut to 40 steps, 2 PPO iterations of small rollouts.
fn experiment(name: &str, genotype: &str, optimizer: &str) -> String {
    format!(
        r#"name = "{name}"
runs = 2
seed = 3

[genotype]
{genotype}
width = 3
height = 3

[genotype.ppo]
iterations = 2
environments = 2
steps_per_environment = 16
hidden = [8]

[task]
kind = "evogym"
env = "Walker-v0"
duration = 0.12

[optimizer]
{optimizer}

[stop]
evaluations = 8

[output]
snapshot_every = 4
"#
    )
}

const DIRECT: &str = "kind = \"material-grid\"";
const GA: &str = "kind = \"ga\"\npopulation_size = 2\noffspring_size = 4\ntournament_size = 1\nmutation_probability = 1.0\ninitial_population_size = 4";
const CPPN: &str = "kind = \"cppn\"";
const NEAT: &str = "kind = \"neat\"\npopulation_size = 4\nmutation = { activations = [\"sigmoid\"] }";

#[test]
fn both_encodings_run_resume_and_are_analysed() {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path();
    for (name, genotype, optimizer) in [("direct", DIRECT, GA), ("cppn", CPPN, NEAT)] {
        let file = root.join(format!("{name}.toml"));
        std::fs::write(&file, experiment(name, genotype, optimizer)).unwrap();
        let out = root.join("out").join(name);
        let text = ok(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--threads",
            "2",
        ]);
        assert!(text.contains("each trained by 2 PPO iterations"), "{text}");
        let generations = std::fs::read_to_string(out.join("run-00/generations.csv")).unwrap();
        assert!(generations
            .lines()
            .next()
            .unwrap()
            .ends_with("best_size,best_rigid,best_soft,best_horizontal,best_vertical"));
        let snapshot = std::fs::read_to_string(out.join("run-00/snapshots/evaluations-0000008.jsonl")).unwrap();
        // a snapshot holds every body the generation trained (the population the learning
        // curves are medians over): the GA's 2 parents and 4 children before the best 2 are
        // kept, NEAT's 4 genomes; each trained one with its learning curve
        let rows: Vec<serde_json::Value> = snapshot.lines().map(|l| serde_json::from_str(l).unwrap()).collect();
        assert_eq!(rows.len(), if name == "direct" { 6 } else { 4 }, "{snapshot}");
        // (a body without an actuator fails before any training, and says so)
        for row in rows.iter().filter(|r| r["error"].is_null()) {
            let curve = row["series"]["learning_curve"].as_array().expect(&snapshot);
            assert_eq!(curve.len(), 3, "{row}");
            assert_eq!(row["fitness"], curve[2]);
        }
        // the best robot carries the policy its fitness came from: replayed on the experiment's
        // task, it earns the fitness (reward per step) times the 40 steps
        let best = out.join("run-00/best.robot.json");
        let robot = std::fs::read_to_string(&best).unwrap();
        assert!(robot.contains("\"kind\": \"policy\""), "{robot}");
        let replay = ok(&[
            "simulate",
            "--robot",
            best.to_str().unwrap(),
            "--task-of",
            out.to_str().unwrap(),
            "--json",
        ]);
        let replay: serde_json::Value = serde_json::from_str(&replay).unwrap();
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("run-00/summary.json")).unwrap()).unwrap();
        let (reward, fitness) = (
            replay["reward"].as_f64().unwrap(),
            summary["best_fitness"].as_f64().unwrap(),
        );
        assert!(
            (reward - 40.0 * fitness).abs() <= 1e-9 * reward.abs().max(1e-6),
            "{reward} vs 40 × {fitness}"
        );
        // resuming a finished experiment changes nothing
        let before = std::fs::read(out.join("run-01/generations.csv")).unwrap();
        ok(&[
            "run",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--resume",
        ]);
        assert_eq!(std::fs::read(out.join("run-01/generations.csv")).unwrap(), before);
    }
    // vsrlab analyze draws the co-design kinds' own size figure, not the graph's (issue 56,
    // item 4: best_size, a share of the grid, was drawn as "|G| = neurons + edges")
    let analysis = root.join("analysis");
    let direct = root.join("out").join("direct");
    ok(&["analyze", direct.to_str().unwrap(), "--out", analysis.to_str().unwrap()]);
    assert!(analysis.join("body-size.png").is_file());
    assert!(!analysis.join("graph-size.png").exists());
    // the best robots (EvoGym bodies) have the thesis's morphology descriptors from their kind
    // (issue 56, item 4: they were left out of best.csv and the descriptor figure)
    let best = std::fs::read_to_string(analysis.join("best.csv")).unwrap();
    let rows: Vec<&str> = best.lines().collect();
    assert!(rows[0].contains(",voxels,elongation,compactness,"), "{best}");
    assert_eq!(rows.len(), 3, "a row per run: {best}");
    for row in &rows[1..] {
        let voxels: usize = row.split(',').nth(3).unwrap().parse().unwrap();
        assert!((1..=25).contains(&voxels), "{row}");
    }
    assert!(analysis.join("descriptors.png").is_file());
    let summary = std::fs::read_to_string(analysis.join("summary.md")).unwrap();
    assert!(summary.contains("share of the grid's cells present"), "{summary}");
    // the fitness is named as the genotype kind defines it (a body's learned mean reward per
    // step), not as the task's summed reward nor as a velocity
    assert!(summary.contains("median best reward per step"), "{summary}");
    assert!(
        !summary.contains("velocity") && !summary.contains("final ISI"),
        "{summary}"
    );
    let figures = root.join("figures");
    let text = ok(&[
        "codesign",
        root.join("out").to_str().unwrap(),
        "--out",
        figures.to_str().unwrap(),
        "--window",
        "2",
    ]);
    assert!(
        text.contains("| direct | 2 |") && text.contains("| cppn | 2 |"),
        "{text}"
    );
    for stem in [
        "learning-curves",
        "learning-radius",
        "learning-over-evolution",
        "materials",
        "fitness",
    ] {
        assert!(figures.join(format!("{stem}.png")).is_file(), "{stem}");
    }
    let curves = std::fs::read_to_string(figures.join("learning-curves.csv")).unwrap();
    assert!(
        curves.starts_with("setting,stage,run,evaluations,iteration,median_reward\n")
            && curves.contains("direct,end,1,8,1,"),
        "{curves}"
    );
}

#[test]
fn bad_codesign_tables_name_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (experiment("a", DIRECT, NEAT), "optimizer.kind"),
        (experiment("b", CPPN, GA), "optimizer.kind"),
        (
            experiment("c", DIRECT, GA).replace("iterations = 2", "iterations = 0"),
            "genotype.ppo.iterations",
        ),
        (
            experiment("d", DIRECT, GA).replace("width = 3", "width = 300"),
            "genotype.width",
        ),
        (
            experiment("e", DIRECT, GA).replace(
                "kind = \"evogym\"\nenv = \"Walker-v0\"\nduration = 0.12",
                "terrain = \"flat\"",
            ),
            "task.kind",
        ),
        (
            experiment("f", DIRECT, GA).replace("mutation_probability = 1.0", "mutation_probability = 0.5"),
            "optimizer.mutation_probability",
        ),
        (
            experiment("g", DIRECT, GA).replace("height = 3", "height = 3\nmutation_rate = 1.5"),
            "genotype.mutation_rate",
        ),
        (
            experiment("h", DIRECT, GA).replace("hidden = [8]", "hiden = [8]"),
            "genotype.ppo",
        ),
    ];
    for (i, (text, field)) in cases.iter().enumerate() {
        let file = dir.path().join(format!("bad-{i}.toml"));
        std::fs::write(&file, text).unwrap();
        let (success, out) = vsrlab(&["validate", file.to_str().unwrap()]);
        assert!(!success && out.contains(field), "case {i}: expected {field}:\n{out}");
    }
    // a flat-vector experiment cannot name NEAT
    let quickstart = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../experiments/quickstart.toml"
    ))
    .unwrap();
    let start = quickstart.find("[optimizer]").unwrap();
    let end = start + quickstart[start..].find("\n[").unwrap();
    let file = dir.path().join("vector-neat.toml");
    std::fs::write(
        &file,
        format!(
            "{}[optimizer]\nkind = \"neat\"\n{}",
            &quickstart[..start],
            &quickstart[end..]
        ),
    )
    .unwrap();
    let (success, out) = vsrlab(&["validate", file.to_str().unwrap()]);
    assert!(
        !success && out.contains("optimizer.kind") && out.contains("cppn"),
        "{out}"
    );
}

#[test]
fn the_chapter_files_hold_the_thesis_settings() {
    use vsrlab_experiment::config::load_all;
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/ch5.2");
    let mut checked = 0;
    for task in ["bridge-walker", "beam-toppler", "cave-crawler"] {
        for encoding in ["direct", "cppn"] {
            let path = std::path::PathBuf::from(format!("{dir}/{task}-{encoding}.toml"));
            let experiments = load_all(&path).unwrap_or_else(|e| panic!("{e}"));
            let e = &experiments[0];
            let toml = e.to_toml();
            assert!(
                toml.contains("iterations = 1000") && toml.contains("environments = 4"),
                "{toml}"
            );
            let budget = if task == "cave-crawler" { 1000 } else { 500 };
            assert_eq!((e.runs, e.stop.evaluations), (10, Some(budget)), "{task}-{encoding}");
            let kind = if encoding == "direct" { "material-grid" } else { "cppn" };
            assert_eq!(e.genotype_kind().name(), kind);
            checked += 1;
        }
    }
    for encoding in ["direct", "cppn"] {
        let path = std::path::PathBuf::from(format!("{dir}/reduced-{encoding}.toml"));
        assert_eq!(
            load_all(&path).unwrap_or_else(|e| panic!("{e}")).len(),
            3,
            "three tasks"
        );
        checked += 1;
        // the 100-iteration BeamToppler files of docs/ch5.2.md
        let path = std::path::PathBuf::from(format!("{dir}/beam-toppler-100-{encoding}.toml"));
        let experiments = load_all(&path).unwrap_or_else(|e| panic!("{e}"));
        let toml = experiments[0].to_toml();
        assert!(
            toml.contains("iterations = 100\n") && toml.contains("BeamToppler-v0"),
            "{toml}"
        );
        assert_eq!((experiments[0].runs, experiments[0].stop.evaluations), (3, Some(20)));
        checked += 1;
    }
    assert_eq!(checked, 10);
}
