//! The graph genotype of the self-organizing controller (thesis §4.1): `[genotype] kind =
//! "graph"` in an experiment file. The genotype is the brain's graph itself ([`GraphSpec`] with
//! its neurons listed), varied by the topology operators of [`vsrlab_brain::graph_ops`] inside the
//! GA of `[optimizer] kind = "ga"` (mutation only), and mapped to a robot with the file's body,
//! sensors and preset.
//!
//! - `connectivity`: `minimal` (edges inside a voxel), `hopping` (to the 4 neighbours' cells,
//!   distance ≤ 1) or `full` (any length, the default);
//! - `modularity`: `plain` (ω = [1, 1]), `modular` ([ω, 1]), `unmodular` ([1, ω]) with `omega`
//!   (10), over the module map `modules` (`halves`, `legs-torso`, `voxels`, rows of digits, or
//!   `discovered`: the most compact module of the seed graph);
//! - `operators`: `thesis` (the five with 0.15/0.15/0.1/0.1/0.5), `weights-only` (mutate edge
//!   only: the ablation) or a table of weights by operator name; `sigma`: mutate edge's σ (0.7);
//! - `initial = "robot.json"`: the population starts from that robot's graph (the hybrid of a
//!   reassembly, or an evolved robot): member 0 is the graph itself, every other a mutant made
//!   with `initial_operators`. When the file is read, the graph is copied into
//!   `representation.brain` and `seeded = true` is written instead, so the resolved
//!   `experiment.toml` holds everything a resume needs.
//!
//! Graphs have no crossover: they evolve with any optimizer over variation operators whose
//! children are all mutants (`ga` or `nsga2` with `mutation_probability = 1.0`, `map-elites`).
//!
//! The best graph of each generation is logged in `generations.csv` as `best_neurons`,
//! `best_edges`, `best_size` (|G|), `best_connection_cost` and `best_within_module`.

use super::{check_operators, run_with_operators, time_with_operators};
use super::{GenotypeConfig, GenotypeEntry, GenotypeKind, GenotypeSize};
use crate::config::Experiment;
use crate::genotype::{fnv1a, Genotype};
use crate::optimizers::FieldError;
use crate::runner::{Observer, RunError, RunOptions, RunSummary};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use vsrlab_body::sensors::SensorSuite;
use vsrlab_body::Morphology;
use vsrlab_brain::graph_modules::{self, ModuleMap};
use vsrlab_brain::graph_ops::{apply, draw, Operator, Topology, THESIS_OPERATORS};
use vsrlab_brain::BrainShape;
use vsrlab_brain::{BrainSpec, GraphSpec};
use vsrlab_evolution::rng::SeededRng;
use vsrlab_evolution::Representation as Variation;
use vsrlab_tasks::{EvaluationError, Mapper, Representation, Robot, RobotSpec, Stored, StoredGenotypes};

/// The `kind` tag of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GraphTag {
    /// A graph of neurons in voxels (the self-organizing controller).
    Graph,
}

/// How far edges may reach.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Connectivity {
    /// Inside a voxel (maxDist 0).
    Minimal,
    /// To the neighbouring cells (maxDist 1).
    Hopping,
    /// Anywhere (maxDist ∞).
    #[default]
    Full,
}

impl Connectivity {
    fn max_dist(self) -> f64 {
        match self {
            Connectivity::Minimal => 0.0,
            Connectivity::Hopping => 1.0,
            Connectivity::Full => f64::INFINITY,
        }
    }
}

/// Which new edges the topology operators favour.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Modularity {
    /// No bias: [1, 1].
    #[default]
    Plain,
    /// Within-module edges ω times likelier: [ω, 1].
    Modular,
    /// Crossing edges ω times likelier: [1, ω].
    Unmodular,
}

/// Operator weights: a name (`thesis`, `weights-only`) or a table by operator name.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum OperatorMix {
    /// `thesis` or `weights-only`.
    Named(String),
    /// Weights by operator name (`add_node`, `remove_node`, `add_edge`, `remove_edge`,
    /// `mutate_edge`, `remove_crossing_edge`).
    Weights(BTreeMap<String, f64>),
}

impl Default for OperatorMix {
    fn default() -> Self {
        OperatorMix::Named("thesis".into())
    }
}

impl OperatorMix {
    /// The operators with their weights.
    pub fn resolve(&self) -> Result<Vec<(Operator, f64)>, FieldError> {
        match self {
            OperatorMix::Named(name) => match name.as_str() {
                "thesis" => Ok(THESIS_OPERATORS.to_vec()),
                "weights-only" => Ok(vec![(Operator::MutateEdge, 1.0)]),
                other => Err(FieldError::message(format!(
                    "unknown operator mix '{other}': expected thesis, weights-only or a table of weights by operator"
                ))),
            },
            OperatorMix::Weights(table) => {
                let mut mix = Vec::new();
                for (name, &weight) in table {
                    let op = Operator::NAMED
                        .iter()
                        .find(|n| n.0 == name)
                        .map(|n| n.1)
                        .ok_or_else(|| {
                            let names: Vec<&str> = Operator::NAMED.iter().map(|n| n.0).collect();
                            FieldError::message(format!(
                                "unknown operator '{name}': expected one of {}",
                                names.join(", ")
                            ))
                        })?;
                    if !(weight.is_finite() && weight >= 0.0) {
                        return Err(FieldError::new(
                            name.as_str(),
                            format!("a weight must be a finite number ≥ 0, got {weight}"),
                        ));
                    }
                    mix.push((op, weight));
                }
                if mix.iter().map(|m| m.1).sum::<f64>() <= 0.0 {
                    return Err(FieldError::message("give at least one operator a positive weight"));
                }
                Ok(mix)
            }
        }
    }
}

/// The `[genotype]` table of a graph genotype (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GraphGenotypeConfig {
    /// `graph`.
    pub kind: GraphTag,
    /// How far edges may reach.
    #[serde(default)]
    pub connectivity: Connectivity,
    /// The modularity bias.
    #[serde(default)]
    pub modularity: Modularity,
    /// ω of the bias.
    #[serde(default = "default_omega")]
    pub omega: f64,
    /// The module map (bias, the within-module share logged, crossing-edge removal).
    #[serde(default = "default_modules")]
    pub modules: String,
    /// The operators of every child.
    #[serde(default)]
    pub operators: OperatorMix,
    /// The operators that make the initial mutants of a seeded population.
    #[serde(default)]
    pub initial_operators: OperatorMix,
    /// σ of "mutate edge".
    #[serde(default = "default_sigma")]
    pub sigma: f64,
    /// A robot file whose graph seeds the population (replaced by `seeded` when read).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<PathBuf>,
    /// Whether `representation.brain` holds the seed graph with its parameters.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub seeded: bool,
}

fn default_omega() -> f64 {
    10.0
}

fn default_modules() -> String {
    "halves".into()
}

fn default_sigma() -> f64 {
    vsrlab_brain::graph_ops::EDGE_SIGMA
}

/// The fixed body of a representation, or the field and message.
fn fixed_body(representation: &Representation) -> Result<&Morphology, FieldError> {
    representation.body.fixed_grid().ok_or_else(|| {
        FieldError::new(
            "representation.body",
            "a graph genotype places neurons in voxels: give a fixed voxel body (a shape name or rows)",
        )
    })
}

/// The graph brain of a representation, or the field and message.
fn graph_brain(representation: &Representation) -> Result<&GraphSpec, FieldError> {
    match &representation.brain {
        BrainSpec::Graph(g) => Ok(g),
        other => Err(FieldError::new(
            "representation.brain",
            format!(
                "a graph genotype needs brain = {{ kind = \"graph\" }}, not {}",
                other.as_kind().name()
            ),
        )),
    }
}

impl GenotypeKind for GraphGenotypeConfig {
    fn name(&self) -> &'static str {
        "graph"
    }

    /// Replaces `initial` by the robot file's graph in `representation.brain` and a
    /// `discovered` module map by its rows.
    fn load_files(&mut self, representation: &mut Representation) -> Result<(), FieldError> {
        if let Some(path) = self.initial.take() {
            let field = |m: String| FieldError::new("genotype.initial", format!("{}: {m}", path.display()));
            let robot = vsrlab_tasks::files::load_robot(&path).map_err(|e| field(e.to_string()))?;
            let BrainSpec::Graph(graph) = robot.brain else {
                return Err(field(format!(
                    "its brain is {}, not a graph",
                    robot.brain.as_kind().name()
                )));
            };
            let body = fixed_body(representation)?;
            if &robot.body != body {
                return Err(field(format!(
                    "its body {} is not representation.body {}",
                    robot.body.to_rows().join("/"),
                    body.to_rows().join("/")
                )));
            }
            if graph.neurons.is_empty() || graph.parameters.is_empty() {
                return Err(field("its graph lists no neurons or parameters".into()));
            }
            representation.brain = BrainSpec::Graph(graph);
            self.seeded = true;
        }
        if self.modules == "discovered" {
            let field = |m: String| FieldError::new("genotype.modules", m);
            if !self.seeded {
                return Err(field(
                    "\"discovered\" needs a seed graph to discover the module in: set genotype.initial".into(),
                ));
            }
            let body = fixed_body(representation)?.clone();
            let graph = graph_brain(representation)?;
            let partition = graph_modules::discover(graph, &body, 2..=5)
                .ok_or_else(|| field("the body is too small to hold a module of 2 to 5 voxels".into()))?;
            self.modules = ModuleMap::of_region(&body, &partition.module).to_rows();
        }
        Ok(())
    }

    fn validate(&self, experiment: &Experiment) -> Result<(), FieldError> {
        let body = fixed_body(&experiment.representation)?;
        let graph = graph_brain(&experiment.representation)?;
        check_operators(experiment, false)?;
        let err = |field: &str, m: String| Err(FieldError::new(format!("genotype.{field}"), m));
        if !(self.omega.is_finite() && self.omega > 0.0) {
            return err("omega", format!("must be a positive number, got {}", self.omega));
        }
        if !(self.sigma.is_finite() && self.sigma >= 0.0) {
            return err("sigma", format!("must be a finite number ≥ 0, got {}", self.sigma));
        }
        if let Err(m) = ModuleMap::parse(&self.modules, body) {
            return err("modules", m.to_string());
        }
        self.operators.resolve().map_err(|e| e.at("genotype.operators"))?;
        self.initial_operators
            .resolve()
            .map_err(|e| e.at("genotype.initial_operators"))?;
        if self.seeded && (graph.neurons.is_empty() || graph.parameters.len() != 2 * graph.edges.len()) {
            return Err(FieldError::new(
                "representation.brain",
                "seeded = true needs the seed graph in the brain: neurons, edges and 2 parameters per edge",
            ));
        }
        Ok(())
    }

    fn size(&self, experiment: &Experiment) -> Result<GenotypeSize, FieldError> {
        let (variation, _) = build(experiment, self)?;
        let (neurons, edges) = (variation.start.neurons.len(), variation.start.edges.len());
        Ok(GenotypeSize {
            genes: 2 * edges,
            text: format!("graph genotypes from {neurons} neurons and {edges} edges"),
        })
    }

    fn run(
        &self,
        experiment: &Experiment,
        out: &Path,
        options: &RunOptions,
        observer: &mut dyn Observer,
    ) -> Result<Vec<RunSummary>, RunError> {
        let (variation, mapper) = build(experiment, self)?;
        let genes = 2 * variation.start.edges.len();
        run_with_operators(experiment, variation, mapper, genes, out, options, observer)
    }

    fn time_evaluations(&self, experiment: &Experiment, count: usize) -> Result<(), FieldError> {
        let (variation, mapper) = build(experiment, self)?;
        time_with_operators(experiment, &variation, mapper, count)
    }

    fn stored(&self, experiment: &Experiment) -> Result<Arc<dyn StoredGenotypes>, FieldError> {
        let (_, mapper) = build(experiment, self)?;
        Ok(Arc::new(Stored::<GraphSpec, _>::new(mapper)))
    }

    fn column_figures(&self) -> Vec<super::ColumnFigure> {
        vec![super::ColumnFigure {
            column: "size",
            file: "graph-size",
            title: "Size of the best controller graph during evolution",
            axis: "|G| = neurons + edges",
            description: "size |G| of the best controller graph vs evaluations, median ± sd across runs",
        }]
    }
}

/// The graph operators as an [`evolution` representation](Variation): initial graphs, mutation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GraphVariation {
    /// The starting graph (neurons listed); its parameters are the seed's when `seeded`.
    start: GraphSpec,
    seeded: bool,
    topology: Topology,
    operators: Vec<(Operator, f64)>,
    initial_operators: Vec<(Operator, f64)>,
}

impl Variation for GraphVariation {
    type Genotype = GraphSpec;

    /// The start graph with parameters U[−1, 1], or a mutant of the seed.
    fn random(&self, rng: &mut SeededRng) -> GraphSpec {
        if self.seeded {
            apply(&self.start, draw(&self.initial_operators, rng), &self.topology, rng)
        } else {
            let mut g = self.start.clone();
            g.parameters = rng.uniform_vec(2 * g.edges.len(), -1.0, 1.0);
            g
        }
    }

    /// Member 0 of a seeded population is the seed itself.
    fn initial(&self, index: usize, rng: &mut SeededRng) -> GraphSpec {
        if self.seeded && index == 0 {
            self.start.clone()
        } else {
            self.random(rng)
        }
    }

    fn mutate(&self, parent: &GraphSpec, rng: &mut SeededRng) -> GraphSpec {
        apply(parent, draw(&self.operators, rng), &self.topology, rng)
    }

    /// Graphs have no crossover: the first parent's mutation (unused: validation requires a
    /// mutation probability of 1).
    fn crossover(&self, first: &GraphSpec, _second: &GraphSpec, rng: &mut SeededRng) -> GraphSpec {
        self.mutate(first, rng)
    }
}

impl Genotype for GraphSpec {
    /// FNV-1a over the JSON form.
    fn key(&self) -> u64 {
        fnv1a(serde_json::to_vec(self).expect("graphs serialise"))
    }
}

/// Graph → robot with the experiment's body, sensors and preset; logs the graph's statistics.
#[derive(Debug, Clone)]
pub struct GraphMapper {
    representation: Representation,
    modules: ModuleMap,
}

/// The statistics logged per generation (prefixed `best_` in `generations.csv`).
pub const GRAPH_COLUMNS: [&str; 5] = ["neurons", "edges", "size", "connection_cost", "within_module"];

impl Mapper<GraphSpec> for GraphMapper {
    fn robot(&self, genotype: &GraphSpec) -> Result<Box<dyn Robot>, EvaluationError> {
        let Some(body) = self.representation.body.fixed_grid() else {
            return Err(EvaluationError::Representation(vsrlab_tasks::FieldError::new(
                "body",
                "not fixed",
            )));
        };
        Ok(Box::new(RobotSpec {
            body: body.clone(),
            preset: self.representation.preset,
            voxel: None,
            sensors: self.representation.sensors()?.clone(),
            brain: BrainSpec::Graph(genotype.clone()),
        }))
    }

    fn stats_columns(&self) -> &'static [&'static str] {
        &GRAPH_COLUMNS
    }

    fn stats(&self, g: &GraphSpec) -> Vec<f64> {
        let s = graph_modules::stats(g, &self.modules);
        vec![
            s.neurons as f64,
            s.edges as f64,
            s.size as f64,
            s.connection_cost,
            s.within_module,
        ]
    }
}

/// The variation operators and the mapper of a graph experiment (validated).
pub fn build(
    experiment: &Experiment,
    config: &GraphGenotypeConfig,
) -> Result<(GraphVariation, GraphMapper), FieldError> {
    let representation = &experiment.representation;
    let body = fixed_body(representation)?;
    let brain = graph_brain(representation)?;
    let sensors = representation.sensors().map_err(|e| {
        e.field_error()
            .unwrap_or_else(|| FieldError::new("representation", e.to_string()))
    })?;
    let suite =
        SensorSuite::new(sensors, body, 0).map_err(|e| FieldError::new("representation.sensors", e.to_string()))?;
    let per_voxel: Vec<usize> = (0..body.voxel_count()).map(|v| suite.readings_per_voxel(v)).collect();
    let (neurons, edges) = brain.topology(&BrainShape::grid(body, &per_voxel));
    let start = GraphSpec {
        neurons,
        edges,
        parameters: if config.seeded {
            brain.parameters.clone()
        } else {
            Vec::new()
        },
        grow: 0,
    };
    let modules =
        ModuleMap::parse(&config.modules, body).map_err(|m| FieldError::new("genotype.modules", m.to_string()))?;
    let omega = match config.modularity {
        Modularity::Plain => [1.0, 1.0],
        Modularity::Modular => [config.omega, 1.0],
        Modularity::Unmodular => [1.0, config.omega],
    };
    let variation = GraphVariation {
        start,
        seeded: config.seeded,
        topology: Topology {
            max_dist: config.connectivity.max_dist(),
            omega,
            modules: Some(modules.clone()),
            sigma: config.sigma,
        },
        operators: config.operators.resolve().map_err(|e| e.at("genotype.operators"))?,
        initial_operators: config
            .initial_operators
            .resolve()
            .map_err(|e| e.at("genotype.initial_operators"))?,
    };
    let mapper = GraphMapper {
        representation: representation.clone(),
        modules,
    };
    Ok((variation, mapper))
}

/// The registry entry of `kind = "graph"`.
pub(crate) const ENTRY: GenotypeEntry = GenotypeEntry {
    name: "graph",
    decode: |v| crate::optimizers::decode::<GraphGenotypeConfig>(v).map(GenotypeConfig::new),
};
