//! The self-organizing graph controller evolved from an experiment file (`[genotype] kind =
//! "graph"`, thesis §4.1): runs with its graph statistics logged, resumes bit for bit, keeps the
//! topology fixed in the weights-only ablation, starts from a seed graph, and names the field of
//! every mistake in the file.

use crate::common;

use common::Killer;
use vsrlab_body::Morphology;
use vsrlab_brain::graph_ops::{apply, Operator, Topology};
use vsrlab_brain::BrainShape;
use vsrlab_brain::{BrainSpec, GraphSpec};
use vsrlab_experiment::config;
use vsrlab_experiment::genotypes::graph::GraphGenotypeConfig;
use vsrlab_experiment::run_configured;
use vsrlab_experiment::runner::{deterministic_files, run_dir, RunOptions, Silent};

/// A tiny graph experiment; `extra` lines go into `[genotype]`.
fn text(extra: &str) -> String {
    format!(
        r#"
name = "g"
runs = 2
seed = 3

[representation]
body = "biped-4x3"
sensors = "uniform-a-0"
brain = {{ kind = "graph" }}

[genotype]
kind = "graph"
modules = "legs-torso"
{extra}

[task]
terrain = "flat"
duration = 1.0

[optimizer]
kind = "ga"
population_size = 6
offspring_size = 6
mutation_probability = 1.0

[stop]
generations = 6

[output]
snapshot_every = 6
save_best = true
"#
    )
}

/// The `best_<name>` column of every row of a generations.csv.
fn column(csv: &str, name: &str) -> Vec<f64> {
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let k = header
        .iter()
        .position(|h| *h == name)
        .unwrap_or_else(|| panic!("no {name} in {header:?}"));
    lines.map(|l| l.split(',').nth(k).unwrap().parse().unwrap()).collect()
}

#[test]
fn a_graph_experiment_logs_its_graphs_and_resumes_bit_for_bit() {
    let experiment = config::parse(&text(""), "g.toml").unwrap();
    let dir = tempfile::tempdir().unwrap();
    let (straight, resumed) = (dir.path().join("straight"), dir.path().join("resumed"));
    let options = common::two_threads;
    let summaries = run_configured(&experiment, &straight, &options(false), &mut Silent).unwrap();
    assert!(summaries.iter().all(|s| s.failures == 0 && s.best_fitness.is_some()));
    let csv = std::fs::read_to_string(run_dir(&straight, 0, 2).join("generations.csv")).unwrap();
    // 10 voxels × 1 reading: 20 neurons, 10 edges at the start; the size is their sum
    let (neurons, edges, size) = (
        column(&csv, "best_neurons"),
        column(&csv, "best_edges"),
        column(&csv, "best_size"),
    );
    assert_eq!((neurons[0], edges[0], size[0]), (20.0, 10.0, 30.0));
    for k in 0..size.len() {
        assert_eq!(size[k], neurons[k] + edges[k]);
    }
    let within = column(&csv, "best_within_module");
    assert_eq!(within[0], 1.0, "the initial edges stay inside their voxels");
    assert_eq!(column(&csv, "best_connection_cost")[0], 0.0);
    // the best robot is a robot file with a graph brain that lists its neurons
    let best = vsrlab_tasks::files::load_robot(&run_dir(&straight, 0, 2).join("best.robot.json")).unwrap();
    assert!(matches!(&best.brain, BrainSpec::Graph(g) if !g.neurons.is_empty()));

    run_configured(&experiment, &resumed, &options(false), &mut Killer { run: 1, after: 3 }).unwrap();
    assert!(run_dir(&resumed, 1, 2).join("checkpoint.json").exists());
    run_configured(&experiment, &resumed, &options(true), &mut Silent).unwrap();
    assert_eq!(
        deterministic_files(&straight).unwrap(),
        deterministic_files(&resumed).unwrap()
    );
}

#[test]
fn topology_evolves_only_when_the_operators_allow_it() {
    let run = |extra: &str| {
        let experiment = config::parse(&text(extra), "g.toml").unwrap();
        let dir = tempfile::tempdir().unwrap();
        run_configured(&experiment, dir.path(), &RunOptions::default(), &mut Silent).unwrap();
        // every graph of the final population, from the last snapshot of run 0
        let snapshots = run_dir(dir.path(), 0, 2).join("snapshots");
        let mut files: Vec<_> = std::fs::read_dir(&snapshots)
            .unwrap()
            .map(|e| e.unwrap().path())
            .collect();
        files.sort();
        let text = std::fs::read_to_string(files.last().unwrap()).unwrap();
        text.lines()
            .map(|l| {
                let v: serde_json::Value = serde_json::from_str(l).unwrap();
                serde_json::from_value::<GraphSpec>(v["genotype"].clone()).unwrap()
            })
            .collect::<Vec<_>>()
    };
    let weights_only = run("operators = \"weights-only\"");
    assert!(weights_only
        .iter()
        .all(|g| g.neurons.len() == 20 && g.edges.len() == 10));
    let grown = run("operators = { add_node = 1.0 }");
    assert!(
        grown.iter().all(|g| g.neurons.len() > 20 && g.edges.len() > 10),
        "only node additions: every survivor has grown"
    );
}

#[test]
fn a_seeded_population_starts_from_the_robot_file_graph() {
    // a seed: the initial graph with one added hidden neuron and known weights
    let m = Morphology::named("biped-4x3").unwrap();
    let (neurons, edges) = GraphSpec::initial(&BrainShape::grid(&m, &[1; 10]));
    let mut seed = GraphSpec {
        parameters: vec![0.25; 2 * edges.len()],
        neurons,
        edges,
        grow: 0,
    };
    let topology = Topology {
        max_dist: f64::INFINITY,
        omega: [1.0, 1.0],
        modules: None,
        sigma: 0.7,
    };
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(1);
    seed = apply(&seed, Operator::AddNode, &topology, &mut rng);
    let dir = tempfile::tempdir().unwrap();
    let robot = vsrlab_tasks::RobotSpec {
        body: m,
        preset: Default::default(),
        voxel: None,
        sensors: vsrlab_body::sensors::SensorConfig::parse("uniform-a-0").unwrap(),
        brain: BrainSpec::Graph(seed.clone()),
    };
    let path = dir.path().join("seed.robot.json");
    std::fs::write(&path, vsrlab_tasks::files::robot_to_json(&robot, None)).unwrap();
    let extra = format!(
        "initial = {:?}\noperators = \"weights-only\"\ninitial_operators = \"weights-only\"",
        path.display().to_string()
    );
    let file = text(&extra).replace("modules = \"legs-torso\"", "modules = \"discovered\"");
    let experiment = config::parse(&file, "g.toml").unwrap();
    let graph: &GraphGenotypeConfig = experiment.genotype.as_ref().unwrap().downcast_ref().unwrap();
    assert!(graph.seeded && graph.initial.is_none());
    assert_ne!(graph.modules, "discovered", "the discovered module is written out");
    assert_eq!(experiment.representation.brain, BrainSpec::Graph(seed.clone()));
    let resolved = config::parse(&experiment.to_toml(), "resolved.toml").unwrap();
    assert_eq!(resolved, experiment, "the resolved file stands on its own");
    let out = dir.path().join("out");
    run_configured(&experiment, &out, &RunOptions::default(), &mut Silent).unwrap();
    let first = std::fs::read_to_string(run_dir(&out, 0, 2).join("snapshots/evaluations-0000006.jsonl")).unwrap();
    let graphs: Vec<GraphSpec> = first
        .lines()
        .map(|l| {
            serde_json::from_value(serde_json::from_str::<serde_json::Value>(l).unwrap()["genotype"].clone()).unwrap()
        })
        .collect();
    assert!(graphs.contains(&seed), "the seed itself is in the first population");
    // weights-only mutants of the seed, then weights-only evolution: the seed's topology everywhere
    assert!(graphs
        .iter()
        .all(|g| g.neurons == seed.neurons && g.edges == seed.edges));
}

#[test]
fn mistakes_name_their_field() {
    let error = |text: String| config::parse(&text, "g.toml").unwrap_err().to_string();
    let cases = [
        (
            text("").replace("brain = { kind = \"graph\" }", "brain = { kind = \"mlp\" }"),
            "representation.brain",
            "kind = \"graph\"",
        ),
        (
            text("").replace("mutation_probability = 1.0", "mutation_probability = 0.2"),
            "optimizer.mutation_probability",
            "no crossover",
        ),
        (
            text("").replace("kind = \"ga\"", "kind = \"cma-es\"").replace(
                "population_size = 6\noffspring_size = 6\nmutation_probability = 1.0\n",
                "",
            ),
            "optimizer.kind",
            "(ga, map-elites, nsga2), not cma-es",
        ),
        (
            text("").replace("modules = \"legs-torso\"", "modules = \"thirds\""),
            "genotype.modules",
            "halves, legs-torso, voxels",
        ),
        (
            text("operators = { fly = 1.0 }"),
            "genotype.operators",
            "unknown operator 'fly'",
        ),
        (
            text("operators = { add_node = -1.0 }"),
            "genotype.operators.add_node",
            "≥ 0",
        ),
        (
            text("initial_operators = \"many\""),
            "genotype.initial_operators",
            "unknown operator mix",
        ),
        (text("connectivity = \"far\""), "genotype.connectivity", "far"),
        (text("omega = 0.0"), "genotype.omega", "positive"),
        (text("wings = 2"), "genotype.wings", "unknown field"),
        (
            text("").replace("modules = \"legs-torso\"", "modules = \"discovered\""),
            "genotype.modules",
            "genotype.initial",
        ),
        (
            text("initial = \"/nonexistent/robot.json\""),
            "genotype.initial",
            "/nonexistent/robot.json",
        ),
        (
            text("").replace(
                "body = \"biped-4x3\"",
                "body = { kind = \"direct\", width = 3, height = 3 }",
            ),
            "representation.brain",
            "fixed body",
        ),
    ];
    for (text, field, words) in cases {
        let message = error(text);
        assert!(message.contains(&format!("field '{field}'")), "{field}: {message}");
        assert!(message.contains(words), "{field}: {message}");
    }
}
