//! The self-organizing embodied controller of thesis §4.1 (thesis-code-facts.md §4.1–4.2): a graph
//! of neurons, each located in a voxel, joined by weighted edges.
//!
//! # Neurons and edges
//!
//! - *sensing*: bound to one reading of its voxel; outputs tanh(reading);
//! - *actuator*: at most one per voxel; its output is the voxel's actuation (voxels without one
//!   get 0);
//! - *hidden*: any activation (node addition makes sigmoid ones).
//!
//! An edge from `from` to `to` adds w·out_from + b to its target's input (each edge has its own
//! bias). No edge goes into a sensing neuron or out of an actuator.
//!
//! # Per-step update
//!
//! Every neuron computes from the *previous* step's outputs of its sources, then all commit: every
//! edge carries one step of delay, so the order of the neurons never matters (tested by shuffling
//! them; bit for bit). A neuron without incoming edges outputs f(0). Outputs are clamped to
//! ±[`MAX_OUTPUT`], so that loops through identity or relu neurons cannot overflow. Incoming contributions are
//! summed in the order the edges are listed, so listing the edges in another order changes the
//! outputs only by rounding.
//!
//! # Parameters
//!
//! `[w, b]` per edge, in edge order (2·E). With no neurons listed, the graph is the thesis' initial
//! one for the body: one sensing neuron per reading and one actuator per voxel, in voxel order
//! (grid order, each voxel's readings then its actuator), and an edge from each sensing neuron to
//! its voxel's actuator. Evolving only the parameters of a fixed graph is the thesis'
//! "weights-only" control; evolving the topology needs the graph operators (not yet in vsrlab).

use crate::mlp::{check_at_most, Activation};
use crate::short_form::ShortForm;
use crate::validation::{check_count, check_units, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};
use vsrlab_body::{Channel, Probe};
use vsrlab_lanes::fdlibm_tanh;

/// Largest output of a neuron in absolute value: feedback loops through unbounded activations
/// (identity, relu) would otherwise overflow to infinity and then NaN.
pub const MAX_OUTPUT: f64 = 1e9;

/// Most neurons or edges of one graph.
pub const MAX_GRAPH_ITEMS: usize = 1_000_000;
/// Most neurons `grow` may add. Each addition draws its edge among all pairs of neurons, so
/// growing costs the cube of this (measured: 300 in 0.5 s, 1,000 in 19 s), and the thesis's
/// evolved graphs have tens to hundreds of neurons.
pub const MAX_GROW: usize = 500;

/// One neuron of a graph brain, located in the voxel at grid cell (x, y).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum NeuronSpec {
    /// Reads one of its voxel's readings (index among that voxel's readings).
    Sensing {
        /// Grid column.
        x: usize,
        /// Grid row (0 = bottom).
        y: usize,
        /// Which of the voxel's readings.
        reading: usize,
    },
    /// Drives its voxel.
    Actuator {
        /// Grid column.
        x: usize,
        /// Grid row (0 = bottom).
        y: usize,
    },
    /// Computes f(Σ w·in + b).
    Hidden {
        /// Grid column.
        x: usize,
        /// Grid row (0 = bottom).
        y: usize,
        /// Its activation (default sigmoid, as node addition makes them).
        #[serde(default = "sigmoid")]
        activation: Activation,
    },
}

fn sigmoid() -> Activation {
    Activation::Sigmoid
}

impl NeuronSpec {
    /// The grid cell of its voxel.
    pub fn cell(&self) -> (usize, usize) {
        match *self {
            NeuronSpec::Sensing { x, y, .. } | NeuronSpec::Actuator { x, y } | NeuronSpec::Hidden { x, y, .. } => {
                (x, y)
            }
        }
    }
}

/// One edge: from neuron `from` to neuron `to` (indices into `neurons`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EdgeSpec {
    /// Source neuron.
    pub from: usize,
    /// Target neuron.
    pub to: usize,
}

/// Description of a graph brain (`{"kind": "graph", "neurons": […], "edges": […], "parameters":
/// […]}`), module documentation.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct GraphSpec {
    /// The neurons; empty = the initial graph of the body (module documentation).
    pub neurons: Vec<NeuronSpec>,
    /// The edges (with `neurons` empty, must be empty too).
    pub edges: Vec<EdgeSpec>,
    /// `[w, b]` per edge.
    pub parameters: Vec<f64>,
    /// With no neurons listed: grow the initial graph by this many "add node" operations (a
    /// sigmoid hidden neuron between a random pair, anywhere in the body, fixed seed): a synthetic
    /// evolved-looking graph of |G| = initial + 3·grow, for benchmarks and demos.
    #[serde(skip_serializing_if = "is_zero")]
    pub grow: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Seed of [`GraphSpec::grow`]'s operations.
const GROW_SEED: u64 = 4_1;

impl GraphSpec {
    /// The thesis' initial graph for a body whose voxels have these readings counts: sensing
    /// neurons and an actuator per voxel, every sensing neuron wired to its voxel's actuator.
    pub fn initial(shape: &BrainShape) -> (Vec<NeuronSpec>, Vec<EdgeSpec>) {
        let mut neurons = Vec::new();
        let mut edges = Vec::new();
        let layout = shape.layout();
        for (unit, &count) in shape.readings().iter().enumerate().take(layout.units()) {
            let [x, y, _] = layout.cell(unit);
            let first = neurons.len();
            neurons.extend((0..count).map(|reading| NeuronSpec::Sensing { x, y, reading }));
            let actuator = neurons.len();
            neurons.push(NeuronSpec::Actuator { x, y });
            edges.extend((first..actuator).map(|from| EdgeSpec { from, to: actuator }));
        }
        (neurons, edges)
    }

    /// The neurons and edges in force for a body: the listed ones, or the initial graph (grown
    /// by `grow` additions).
    pub fn topology(&self, shape: &BrainShape) -> (Vec<NeuronSpec>, Vec<EdgeSpec>) {
        if !self.neurons.is_empty() {
            return (self.neurons.clone(), self.edges.clone());
        }
        let (neurons, edges) = Self::initial(shape);
        if self.grow == 0 {
            return (neurons, edges);
        }
        let mut g = GraphSpec {
            parameters: vec![0.0; 2 * edges.len()],
            neurons,
            edges,
            grow: 0,
        };
        let anywhere = crate::graph_ops::Topology {
            max_dist: f64::INFINITY,
            omega: [1.0, 1.0],
            modules: None,
            sigma: 0.0,
        };
        let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(GROW_SEED);
        for _ in 0..self.grow.min(MAX_GROW) {
            g = crate::graph_ops::apply(&g, crate::graph_ops::Operator::AddNode, &anywhere, &mut rng);
        }
        (g.neurons, g.edges)
    }

    /// Checks the graph against the body; errors name the neuron or edge.
    fn check(&self, shape: &BrainShape, neurons: &[NeuronSpec], edges: &[EdgeSpec]) -> Result<(), BrainError> {
        check_units(shape)?;
        let layout = shape.layout();
        if layout.extent()[2] > 1 {
            return Err(invalid(
                "kind",
                "a graph brain names its voxels by (x, y): it does not take a 3D body yet".into(),
            ));
        }
        let readings_per_voxel = shape.readings();
        check_at_most("neurons", "neurons", neurons.len(), MAX_GRAPH_ITEMS)?;
        check_at_most("edges", "edges", edges.len(), MAX_GRAPH_ITEMS)?;
        if !self.neurons.is_empty() && self.grow > 0 {
            return Err(invalid("grow", "grows the initial graph: leave the neurons out".into()));
        }
        if self.neurons.is_empty() && !self.edges.is_empty() {
            return Err(invalid(
                "edges",
                "edges need their neurons: list the neurons too".into(),
            ));
        }
        let voxel_of = |(x, y): (usize, usize)| layout.unit_at([x, y, 0]);
        let mut actuators = vec![None; shape.units()];
        for (i, n) in neurons.iter().enumerate() {
            let Some(v) = voxel_of(n.cell()) else {
                return Err(invalid(
                    "neurons",
                    format!("neurons[{i}]: cell {:?} holds no voxel of the body", n.cell()),
                ));
            };
            match *n {
                NeuronSpec::Sensing { reading, .. } if reading >= readings_per_voxel[v] => {
                    return Err(invalid(
                        "neurons",
                        format!(
                            "neurons[{i}]: reading {reading}, but the voxel at {:?} has {} readings",
                            n.cell(),
                            readings_per_voxel[v]
                        ),
                    ))
                }
                NeuronSpec::Actuator { .. } => {
                    if let Some(j) = actuators[v].replace(i) {
                        return Err(invalid(
                            "neurons",
                            format!(
                                "neurons[{i}]: a second actuator in the voxel at {:?} (the first is neurons[{j}])",
                                n.cell()
                            ),
                        ));
                    }
                }
                _ => {}
            }
        }
        for (k, e) in edges.iter().enumerate() {
            for (end, index) in [("from", e.from), ("to", e.to)] {
                if index >= neurons.len() {
                    return Err(invalid(
                        "edges",
                        format!(
                            "edges[{k}]: {end} {index}: no such neuron (there are {})",
                            neurons.len()
                        ),
                    ));
                }
            }
            if matches!(neurons[e.to], NeuronSpec::Sensing { .. }) {
                return Err(invalid("edges", format!("edges[{k}]: into sensing neuron {}", e.to)));
            }
            if matches!(neurons[e.from], NeuronSpec::Actuator { .. }) {
                return Err(invalid(
                    "edges",
                    format!("edges[{k}]: out of actuator neuron {}", e.from),
                ));
            }
        }
        Ok(())
    }
}

fn invalid(field: &'static str, msg: String) -> BrainError {
    BrainError::Invalid { field, msg }
}

impl BrainKind for GraphSpec {
    fn name(&self) -> &'static str {
        "graph"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_at_most("grow", "added neurons", self.grow, MAX_GROW)?;
        let (neurons, edges) = self.topology(shape);
        self.check(shape, &neurons, &edges)?;
        Ok(2 * edges.len())
    }

    fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("parameters", &mut self.parameters, params)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        Ok(Box::new(self.controller(shape)?))
    }
}

impl GraphSpec {
    /// [`BrainKind::build`], as the concrete controller (to look at its neurons' outputs).
    pub fn controller(&self, shape: &BrainShape) -> Result<GraphController, BrainError> {
        check_at_most("grow", "added neurons", self.grow, MAX_GROW)?;
        let (neurons, edges) = self.topology(shape);
        self.check(shape, &neurons, &edges)?;
        check_count("parameters", 2 * edges.len(), self.parameters.len())?;
        Ok(GraphController::new(shape, &neurons, &edges, &self.parameters))
    }
}

/// What a neuron computes, at run time.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Role {
    /// tanh of this index into the flat readings.
    Sensing(usize),
    /// f(Σ w·in + b).
    Computing(Activation),
}

/// The running graph: neurons with their incoming edges in compressed form, and two output
/// buffers (previous step, this step). [`Controller::control`] allocates nothing.
#[derive(Debug, Clone)]
pub struct GraphController {
    roles: Vec<Role>,
    /// Incoming edges of neuron i: `incoming[starts[i]..starts[i + 1]]`, as (source, w, b).
    starts: Vec<usize>,
    incoming: Vec<(usize, f64, f64)>,
    /// Per voxel, its actuator neuron.
    actuator_of: Vec<Option<usize>>,
    /// For drawing: each neuron's voxel and kind, and the edges with their weights.
    layout: Vec<(usize, u8)>,
    edges: Vec<(usize, usize, f64)>,
    previous: Vec<f64>,
    current: Vec<f64>,
}

impl GraphController {
    fn new(shape: &BrainShape, neurons: &[NeuronSpec], edges: &[EdgeSpec], parameters: &[f64]) -> Self {
        let layout = shape.layout();
        let voxel_of = |(x, y): (usize, usize)| layout.unit_at([x, y, 0]).expect("checked");
        let mut first_reading = Vec::with_capacity(shape.units());
        let mut total = 0;
        for &count in shape.readings() {
            first_reading.push(total);
            total += count;
        }
        let mut actuator_of = vec![None; shape.units()];
        let roles = neurons
            .iter()
            .enumerate()
            .map(|(i, n)| match *n {
                NeuronSpec::Sensing { reading, .. } => Role::Sensing(first_reading[voxel_of(n.cell())] + reading),
                NeuronSpec::Actuator { .. } => {
                    actuator_of[voxel_of(n.cell())] = Some(i);
                    Role::Computing(Activation::Tanh)
                }
                NeuronSpec::Hidden { activation, .. } => Role::Computing(activation),
            })
            .collect();
        let mut order: Vec<usize> = (0..edges.len()).collect();
        order.sort_by_key(|&k| edges[k].to);
        let mut starts = vec![0; neurons.len() + 1];
        for e in edges {
            starts[e.to + 1] += 1;
        }
        for i in 0..neurons.len() {
            starts[i + 1] += starts[i];
        }
        let incoming = order
            .iter()
            .map(|&k| (edges[k].from, parameters[2 * k], parameters[2 * k + 1]))
            .collect();
        let layout = neurons
            .iter()
            .map(|n| {
                let kind = match n {
                    NeuronSpec::Sensing { .. } => 0,
                    NeuronSpec::Hidden { .. } => 1,
                    NeuronSpec::Actuator { .. } => 2,
                };
                (voxel_of(n.cell()), kind)
            })
            .collect();
        let edges = edges
            .iter()
            .enumerate()
            .map(|(k, e)| (e.from, e.to, parameters[2 * k]))
            .collect();
        GraphController {
            roles,
            starts,
            incoming,
            actuator_of,
            layout,
            edges,
            previous: vec![0.0; neurons.len()],
            current: vec![0.0; neurons.len()],
        }
    }
}

impl GraphController {
    /// Every neuron's output after the last step, in neuron order.
    pub fn outputs(&self) -> &[f64] {
        &self.previous
    }
}

/// A graph brain's neurons: (unit, kind) per neuron, kind 0 sensing, 1 hidden, 2 actuator.
pub const GRAPH_NEURONS: Channel = Channel::traced("graph_neurons");
/// A graph brain's edges: (source, target, weight) per edge.
pub const GRAPH_EDGES: Channel = Channel::traced("graph_edges");
/// A graph brain's neuron outputs after each step, in neuron order.
pub const GRAPH_OUTPUTS: Channel = Channel::replayed("graph_outputs", 1e-3).single();

impl Controller for GraphController {
    fn describe(&self, probe: &mut dyn Probe) {
        let neurons: Vec<f64> = self
            .layout
            .iter()
            .flat_map(|&(unit, kind)| [unit as f64, f64::from(kind)])
            .collect();
        probe.fixed(&GRAPH_NEURONS, 2, &neurons);
        let edges: Vec<f64> = self
            .edges
            .iter()
            .flat_map(|&(a, b, w)| [a as f64, b as f64, w])
            .collect();
        probe.fixed(&GRAPH_EDGES, 3, &edges);
    }

    fn publish(&self, probe: &mut dyn Probe) {
        probe.step(&GRAPH_OUTPUTS, &self.previous);
    }

    fn reset(&mut self) {
        self.previous.fill(0.0);
        self.current.fill(0.0);
    }

    fn control(&mut self, _t: f64, readings: &[f64], actuations: &mut [f64]) {
        for (i, role) in self.roles.iter().enumerate() {
            self.current[i] = match *role {
                Role::Sensing(r) => fdlibm_tanh(readings[r]),
                Role::Computing(f) => {
                    let sum: f64 = self.incoming[self.starts[i]..self.starts[i + 1]]
                        .iter()
                        .map(|&(src, w, b)| w * self.previous[src] + b)
                        .sum();
                    f.apply(sum).clamp(-MAX_OUTPUT, MAX_OUTPUT)
                }
            };
        }
        std::mem::swap(&mut self.previous, &mut self.current);
        for (a, actuator) in actuations.iter_mut().zip(&self.actuator_of) {
            *a = actuator.map_or(0.0, |n| self.previous[n].clamp(-1.0, 1.0));
        }
    }
}

/// `graph[:<grow>]`: the initial graph of the body (thesis §4.1), grown by `grow` node
/// additions, parameters to be filled.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "graph",
    usage: "graph[:<added hidden neurons>]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let grow = match argument {
        None => 0,
        Some(a) => crate::short_form::count(a)?,
    };
    Some(BrainSpec::Graph(GraphSpec {
        grow,
        ..GraphSpec::default()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped};
    use vsrlab_body::Morphology;

    fn sensing(x: usize, y: usize, reading: usize) -> NeuronSpec {
        NeuronSpec::Sensing { x, y, reading }
    }

    #[test]
    fn the_initial_graph_wires_each_reading_to_its_actuator() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("graph").unwrap();
        // 10 voxels × 4 readings → 40 edges, 80 parameters
        assert_eq!(spec.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap(), 80);
        let (neurons, edges) = GraphSpec::initial(&BrainShape::grid(&m, &rpv));
        assert_eq!(neurons.len(), 50);
        assert_eq!(edges[0], EdgeSpec { from: 0, to: 4 });
        assert_eq!(neurons[4], NeuronSpec::Actuator { x: 0, y: 0 });
    }

    #[test]
    fn growing_beyond_the_limit_is_refused_before_any_growing() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("graph:100000").unwrap();
        let start = std::time::Instant::now();
        assert_invalid(&spec.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap_err(), "grow");
        assert_invalid(&spec.build(&BrainShape::grid(&m, &rpv)).err().unwrap(), "grow");
        assert!(start.elapsed().as_secs_f64() < 1.0, "refused at once");
    }

    #[test]
    fn a_grown_graph_adds_a_neuron_and_two_edges_per_step_deterministically() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("graph:37").unwrap();
        // 40 + 2·37 edges
        assert_eq!(
            spec.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap(),
            2 * (40 + 74)
        );
        let BrainSpec::Graph(g) = &spec else { unreachable!() };
        let (n1, e1) = g.topology(&BrainShape::grid(&m, &rpv));
        let (n2, e2) = g.topology(&BrainShape::grid(&m, &rpv));
        assert_eq!((n1.len(), e1.len()), (50 + 37, 40 + 74));
        assert_eq!((n1, e1), (n2, e2));
        let (neurons, edges) = GraphSpec::initial(&BrainShape::grid(&m, &rpv));
        let listed = GraphSpec {
            parameters: vec![0.0; 2 * edges.len()],
            neurons,
            edges,
            grow: 3,
        };
        assert_invalid(&listed.build(&BrainShape::grid(&m, &rpv)).err().unwrap(), "grow");
    }

    #[test]
    fn every_edge_has_one_step_of_delay() {
        // worm-2x1, one reading each: s0 → h → a1, and s1 → a0
        let m = Morphology::named("worm-2x1").unwrap();
        let neurons = vec![
            sensing(0, 0, 0),
            sensing(1, 0, 0),
            NeuronSpec::Hidden {
                x: 0,
                y: 0,
                activation: Activation::Identity,
            },
            NeuronSpec::Actuator { x: 0, y: 0 },
            NeuronSpec::Actuator { x: 1, y: 0 },
        ];
        let edges = vec![
            EdgeSpec { from: 0, to: 2 },
            EdgeSpec { from: 2, to: 4 },
            EdgeSpec { from: 1, to: 3 },
        ];
        let spec = BrainSpec::Graph(GraphSpec {
            neurons,
            edges,
            parameters: vec![2.0, 0.0, 1.0, 0.5, 1.0, 0.0],
            grow: 0,
        });
        let mut c = spec.build(&BrainShape::grid(&m, &[1, 1])).unwrap();
        let mut a = [0.0; 2];
        c.control(0.0, &[0.3, 0.6], &mut a);
        // step 1: every computing neuron reads zeros: h = 0, a1 = tanh(0·1 + 0.5)
        assert_eq!(a, [0.0, 0.5f64.tanh()]);
        c.control(0.0, &[0.3, 0.6], &mut a);
        // step 2: h = 2·tanh(0.3); a0 = tanh(tanh(0.6)); a1 still sees h of step 1 (0)
        assert_eq!(a, [0.6f64.tanh().tanh(), 0.5f64.tanh()]);
        c.control(0.0, &[0.3, 0.6], &mut a);
        assert_eq!(a[1], (2.0 * 0.3f64.tanh() + 0.5).tanh());
        c.reset();
        c.control(0.0, &[0.3, 0.6], &mut a);
        assert_eq!(a, [0.0, 0.5f64.tanh()], "reset clears the outputs");
    }

    #[test]
    fn shuffling_the_neurons_changes_nothing() {
        let (m, rpv) = biped();
        let (neurons, mut edges) = GraphSpec::initial(&BrainShape::grid(&m, &rpv));
        // add a hidden neuron bridging two voxels, and a feedback edge between hidden neurons
        let mut neurons = neurons;
        neurons.push(NeuronSpec::Hidden {
            x: 1,
            y: 1,
            activation: Activation::Sigmoid,
        });
        neurons.push(NeuronSpec::Hidden {
            x: 2,
            y: 2,
            activation: Activation::Tanh,
        });
        edges.extend([
            EdgeSpec { from: 0, to: 50 },
            EdgeSpec { from: 50, to: 51 },
            EdgeSpec { from: 51, to: 50 },
            EdgeSpec { from: 51, to: 49 },
        ]);
        let params: Vec<f64> = (0..2 * edges.len())
            .map(|k| ((k * 37 % 19) as f64 / 9.0) - 1.0)
            .collect();
        let original = GraphSpec {
            neurons: neurons.clone(),
            edges: edges.clone(),
            parameters: params.clone(),
            grow: 0,
        };
        // a fixed permutation of the neuron indices, the edges in their order
        let n = neurons.len();
        let new_index: Vec<usize> = (0..n).map(|i| (i * 31 + 7) % n).collect();
        let mut shuffled_neurons = neurons.clone();
        for (i, neuron) in neurons.iter().enumerate() {
            shuffled_neurons[new_index[i]] = neuron.clone();
        }
        let mut shuffled_edges = Vec::new();
        let mut shuffled_params = Vec::new();
        for (k, e) in edges.iter().enumerate() {
            shuffled_edges.push(EdgeSpec {
                from: new_index[e.from],
                to: new_index[e.to],
            });
            shuffled_params.extend_from_slice(&params[2 * k..2 * k + 2]);
        }
        let shuffled = GraphSpec {
            neurons: shuffled_neurons,
            edges: shuffled_edges,
            parameters: shuffled_params,
            grow: 0,
        };
        let mut a = original.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mut b = shuffled.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let (mut out_a, mut out_b) = (vec![0.0; 10], vec![0.0; 10]);
        for k in 0..50 {
            let readings: Vec<f64> = (0..40).map(|i| ((i * 7 + k * 3) as f64 * 0.13).sin()).collect();
            a.control(k as f64 / 60.0, &readings, &mut out_a);
            b.control(k as f64 / 60.0, &readings, &mut out_b);
            assert_eq!(out_a, out_b, "step {k}");
        }
    }

    #[test]
    fn bad_graphs_are_refused_naming_the_item() {
        let m = Morphology::named("worm-2x1").unwrap();
        let spec = |neurons: Vec<NeuronSpec>, edges: Vec<EdgeSpec>| GraphSpec {
            parameters: vec![0.0; 2 * edges.len()],
            neurons,
            edges,
            grow: 0,
        };
        let message = |s: GraphSpec, field: &str| {
            let err = s.build(&BrainShape::grid(&m, &[2, 2])).err().expect("refused");
            assert_invalid(&err, field);
            err.to_string()
        };
        let two = || vec![sensing(0, 0, 0), NeuronSpec::Actuator { x: 0, y: 0 }];
        let e = |from, to| EdgeSpec { from, to };
        assert!(message(spec(two(), vec![e(0, 5)]), "edges").contains("edges[0]: to 5: no such neuron"));
        assert!(message(spec(two(), vec![e(1, 0)]), "edges").contains("into sensing neuron 0"));
        assert!(message(spec(two(), vec![e(0, 1), e(1, 1)]), "edges").contains("edges[1]: out of actuator neuron 1"));
        let outside = vec![sensing(0, 0, 0), NeuronSpec::Actuator { x: 3, y: 0 }];
        assert!(message(spec(outside, vec![]), "neurons").contains("neurons[1]: cell (3, 0) holds no voxel"));
        let bad_reading = vec![sensing(1, 0, 2)];
        assert!(message(spec(bad_reading, vec![]), "neurons").contains("reading 2, but the voxel at (1, 0) has 2"));
        let twice = vec![NeuronSpec::Actuator { x: 0, y: 0 }, NeuronSpec::Actuator { x: 0, y: 0 }];
        assert!(message(spec(twice, vec![]), "neurons").contains("second actuator"));
        let err =
            serde_json::from_str::<BrainSpec>(r#"{"kind": "graph", "neurons": [{"kind": "glial", "x": 0, "y": 0}]}"#)
                .unwrap_err();
        assert!(
            err.to_string().contains("neurons") && err.to_string().contains("glial"),
            "{err}"
        );
    }
}
