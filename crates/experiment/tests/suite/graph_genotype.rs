//! A genotype that is not a flat vector goes through the whole path (optimizer → genotype →
//! robot → episode → fitness) and the runner, with checkpoints and resume. The genotype is a
//! small graph of "phase neurons" placed in the cells of a biped; the mapper turns it into the
//! biped's per-cell phases. Everything specific to the graph lives in this file.

use crate::common;

use common::Killer;
use serde::{Deserialize, Serialize};
use vsrlab_evolution::rng::SeededRng;
use vsrlab_evolution::{GaConfig, GaSettings, GeneticAlgorithm, Representation, Sense};
use vsrlab_experiment::config::{self, Experiment};
use vsrlab_experiment::genotype::fnv1a;
use vsrlab_experiment::optimizers::Searcher;
use vsrlab_experiment::runner::{run_dir, run_search, Plan, RunError, Silent};
use vsrlab_experiment::{Genotype, RobotEvaluator};
use vsrlab_tasks::{EvaluationError, Mapper, Robot};

/// Cells of the biped-4x3 grid.
const CELLS: usize = 12;

/// A neuron in a grid cell with a phase; edges pull a neuron's phase towards its source's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Graph {
    nodes: Vec<(usize, f64)>,
    edges: Vec<(usize, usize)>,
}

impl Genotype for Graph {
    fn key(&self) -> u64 {
        fnv1a(serde_json::to_vec(self).unwrap())
    }
}

/// Variation of graphs: add or remove a node, add an edge, or perturb a phase.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct GraphOps;

impl Representation for GraphOps {
    type Genotype = Graph;

    fn random(&self, rng: &mut SeededRng) -> Graph {
        let n = 1 + rng.below(4);
        let nodes = (0..n).map(|_| (rng.below(CELLS), rng.uniform_in(-1.0, 1.0))).collect();
        Graph {
            nodes,
            edges: Vec::new(),
        }
    }

    fn mutate(&self, parent: &Graph, rng: &mut SeededRng) -> Graph {
        let mut g = parent.clone();
        match rng.below(4) {
            0 => g.nodes.push((rng.below(CELLS), rng.uniform_in(-1.0, 1.0))),
            1 if g.nodes.len() > 1 => {
                let k = rng.below(g.nodes.len());
                g.nodes.remove(k);
                g.edges.retain(|&(a, b)| a != k && b != k);
                for e in &mut g.edges {
                    e.0 -= usize::from(e.0 > k);
                    e.1 -= usize::from(e.1 > k);
                }
            }
            2 => g.edges.push((rng.below(g.nodes.len()), rng.below(g.nodes.len()))),
            _ => {
                let k = rng.below(g.nodes.len());
                g.nodes[k].1 += 0.3 * rng.normal();
            }
        }
        g
    }

    fn crossover(&self, first: &Graph, second: &Graph, rng: &mut SeededRng) -> Graph {
        let mut g = first.clone();
        let n = g.nodes.len();
        g.edges.extend(second.edges.iter().filter(|&&(a, b)| a < n && b < n));
        self.mutate(&g, rng)
    }
}

/// Graph → biped with one phase per grid cell (the sum of the phases of the cell's neurons, each
/// pulled halfway towards its edges' sources).
struct GraphMapper;

impl Mapper<Graph> for GraphMapper {
    fn robot(&self, g: &Graph) -> Result<Box<dyn Robot>, EvaluationError> {
        let mut phases = vec![0.0; CELLS];
        for (k, &(cell, phase)) in g.nodes.iter().enumerate() {
            let pull: f64 = g
                .edges
                .iter()
                .filter(|e| e.1 == k)
                .map(|e| g.nodes[e.0].1 - phase)
                .sum();
            phases[cell] += phase + 0.5 * pull;
        }
        common::phase_biped(&phases)
    }
}

/// The task, stop and output settings come from an experiment file as usual.
fn experiment() -> Experiment {
    let text = r#"
runs = 2
seed = 5

[representation]
body = "biped-4x3"
sensors = "empty"
brain = { kind = "phase-grid" }

[task]
terrain = "flat"
duration = 1.0

[optimizer]
kind = "ga"

[stop]
evaluations = 24

[output]
snapshot_every = 12
"#;
    config::parse(text, "graph.toml").unwrap()
}

fn new_optimizer(seed: u64) -> Result<Searcher<GeneticAlgorithm<GraphOps>>, RunError> {
    let config = GaConfig {
        settings: GaSettings {
            population_size: 6,
            offspring_size: 6,
            ..GaSettings::default()
        },
        sense: Sense::Maximize,
        ties: Vec::new(),
    };
    Ok(Searcher(GeneticAlgorithm::new(config, GraphOps, seed)?))
}

#[test]
fn a_graph_genotype_runs_checkpoints_and_resumes_like_an_uninterrupted_run() {
    let experiment = experiment();
    let evaluator = RobotEvaluator::with_mapper(GraphMapper, &experiment);
    let plan = Plan::of(&experiment);
    let dir = tempfile::tempdir().unwrap();
    let (straight, resumed) = (dir.path().join("straight"), dir.path().join("resumed"));
    let options = common::two_threads;

    let summaries = run_search(
        &plan,
        &new_optimizer,
        &evaluator,
        &straight,
        &options(false),
        &mut Silent,
    )
    .unwrap();
    assert_eq!(summaries.len(), 2);
    assert!(summaries.iter().all(|s| s.failures == 0 && s.best_fitness.is_some()));

    let done = run_search(
        &plan,
        &new_optimizer,
        &evaluator,
        &resumed,
        &options(false),
        &mut Killer { run: 1, after: 2 },
    )
    .unwrap();
    assert_eq!(done.len(), 1);
    assert!(run_dir(&resumed, 1, 2).join("checkpoint.json").exists());
    let summaries = run_search(&plan, &new_optimizer, &evaluator, &resumed, &options(true), &mut Silent).unwrap();
    assert_eq!(summaries.len(), 2);
    assert_eq!(files_of(&straight), files_of(&resumed));

    // snapshots carry the graphs; the best is a robot file that replays
    let snapshot =
        std::fs::read_to_string(run_dir(&straight, 0, 2).join("snapshots/evaluations-0000012.jsonl")).unwrap();
    let line: serde_json::Value = serde_json::from_str(snapshot.lines().next().unwrap()).unwrap();
    let graph: Graph = serde_json::from_value(line["genotype"].clone()).unwrap();
    assert!(!graph.nodes.is_empty());
    assert_eq!(line["body"], "####/####/#..#");
    vsrlab_tasks::files::load_robot(&run_dir(&straight, 0, 2).join("best.robot.json")).unwrap();
}

/// The deterministic files of an output folder.
fn files_of(out: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    vsrlab_experiment::runner::deterministic_files(out).unwrap()
}
