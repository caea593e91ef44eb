//! The five topology operators of the self-organizing controller (thesis §4.1,
//! thesis-code-facts.md §4.3–4.4) on a [`GraphSpec`] with its neurons listed: add a node, remove
//! a node, add an edge, remove an edge, mutate an edge; and the sixth of the "resume" protocol
//! (§4.5), remove an edge crossing modules. Every operator returns a valid graph: no
//! edge into a sensing neuron or out of an actuator, no edge longer than `max_dist` (voxel cells,
//! Euclidean), no hidden neuron left without edges.
//!
//! The modularity bias ω weighs the candidate pairs of "add node" and "add edge": a pair whose
//! neurons lie in the same module gets `omega[0]`, a crossing pair `omega[1]` (thesis: plain
//! [1, 1], modular [10, 1], unmodular [1, 10]).

use crate::controllers::graph::{EdgeSpec, GraphSpec, NeuronSpec};
use crate::graph_modules::ModuleMap;
use crate::Activation;
use rand::Rng;
use serde::{Deserialize, Serialize};

/// The operators, with the thesis' probabilities ([`THESIS_OPERATORS`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Operator {
    /// A sigmoid hidden neuron between a candidate pair, with edges source → new → target.
    AddNode,
    /// A random hidden neuron and its edges go; isolated hidden neurons are pruned.
    RemoveNode,
    /// An edge between a candidate pair.
    AddEdge,
    /// A random edge goes; isolated hidden neurons are pruned.
    RemoveEdge,
    /// One random edge: weight and bias += N(0, σ²) (thesis σ = 0.7).
    MutateEdge,
    /// A random edge whose ends lie in different modules goes; isolated hidden neurons are
    /// pruned (the "resume" protocol, thesis-code-facts.md §4.5).
    RemoveCrossingEdge,
}

impl Operator {
    /// Every operator with its name in experiment files.
    pub const NAMED: [(&'static str, Operator); 6] = [
        ("add_node", Operator::AddNode),
        ("remove_node", Operator::RemoveNode),
        ("add_edge", Operator::AddEdge),
        ("remove_edge", Operator::RemoveEdge),
        ("mutate_edge", Operator::MutateEdge),
        ("remove_crossing_edge", Operator::RemoveCrossingEdge),
    ];

    /// Its name in experiment files.
    pub fn name(self) -> &'static str {
        Self::NAMED.iter().find(|n| n.1 == self).map_or("?", |n| n.0)
    }
}

/// The thesis' operator probabilities (they sum to 1).
pub const THESIS_OPERATORS: [(Operator, f64); 5] = [
    (Operator::AddNode, 0.15),
    (Operator::RemoveNode, 0.15),
    (Operator::AddEdge, 0.1),
    (Operator::RemoveEdge, 0.1),
    (Operator::MutateEdge, 0.5),
];

/// Standard deviation of "mutate edge" in the thesis.
pub const EDGE_SIGMA: f64 = 0.7;

/// Where new edges may go, and how far edges mutate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Topology {
    /// Longest edge, in voxel cells (minimal 0, hopping 1, full ∞; `"inf"` in JSON).
    #[serde(with = "distance")]
    pub max_dist: f64,
    /// Candidate weights [within a module, crossing modules].
    pub omega: [f64; 2],
    /// The modules of the body; `None`: every pair is within.
    pub modules: Option<ModuleMap>,
    /// Standard deviation of "mutate edge".
    pub sigma: f64,
}

impl Topology {
    /// Whether two cells lie in the same module.
    fn within(&self, a: (usize, usize), b: (usize, usize)) -> bool {
        self.modules.as_ref().is_none_or(|m| m.same(a, b))
    }
}

/// A distance that may be ∞, as a number or `"inf"` (JSON has no infinity, and checkpoints hold
/// topologies).
mod distance {
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(d: &f64, s: S) -> Result<S::Ok, S::Error> {
        if d.is_infinite() && *d > 0.0 {
            s.serialize_str("inf")
        } else {
            s.serialize_f64(*d)
        }
    }

    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Written {
        Number(f64),
        Text(String),
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        match Written::deserialize(d)? {
            Written::Number(x) => Ok(x),
            Written::Text(t) if t == "inf" => Ok(f64::INFINITY),
            Written::Text(t) => Err(serde::de::Error::custom(format!(
                "expected a distance or \"inf\", got \"{t}\""
            ))),
        }
    }
}

/// Applies `op` to `graph` (neurons listed); returns the new graph. Operators that find nothing
/// to act on (no hidden neuron to remove, no candidate pair) return the graph unchanged.
pub fn apply<R: Rng>(graph: &GraphSpec, op: Operator, topology: &Topology, rng: &mut R) -> GraphSpec {
    let mut g = graph.clone();
    match op {
        Operator::AddEdge => {
            if let Some((from, to)) = pick_pair(&g, topology, None, rng) {
                push_edge(&mut g, from, to, rng);
            }
        }
        Operator::AddNode => {
            if g.neurons.is_empty() {
                return g;
            }
            let at = g.neurons[rng.random_range(0..g.neurons.len())].cell();
            if let Some((from, to)) = pick_pair(&g, topology, Some(at), rng) {
                let new = g.neurons.len();
                g.neurons.push(NeuronSpec::Hidden {
                    x: at.0,
                    y: at.1,
                    activation: Activation::Sigmoid,
                });
                push_edge(&mut g, from, new, rng);
                push_edge(&mut g, new, to, rng);
            }
        }
        Operator::RemoveNode => {
            let hidden: Vec<usize> = (0..g.neurons.len())
                .filter(|&i| matches!(g.neurons[i], NeuronSpec::Hidden { .. }))
                .collect();
            if !hidden.is_empty() {
                let victim = hidden[rng.random_range(0..hidden.len())];
                remove_edges(&mut g, |e| e.from == victim || e.to == victim);
                prune(&mut g);
            }
        }
        Operator::RemoveEdge => {
            if !g.edges.is_empty() {
                let k = rng.random_range(0..g.edges.len());
                let mut index = 0;
                remove_edges(&mut g, |_| {
                    index += 1;
                    index - 1 == k
                });
                prune(&mut g);
            }
        }
        Operator::MutateEdge => {
            if !g.edges.is_empty() {
                let k = rng.random_range(0..g.edges.len());
                g.parameters[2 * k] += topology.sigma * gaussian(rng);
                g.parameters[2 * k + 1] += topology.sigma * gaussian(rng);
            }
        }
        Operator::RemoveCrossingEdge => {
            let crossing: Vec<usize> = (0..g.edges.len())
                .filter(|&k| !topology.within(g.neurons[g.edges[k].from].cell(), g.neurons[g.edges[k].to].cell()))
                .collect();
            if !crossing.is_empty() {
                let k = crossing[rng.random_range(0..crossing.len())];
                let mut index = 0;
                remove_edges(&mut g, |_| {
                    index += 1;
                    index - 1 == k
                });
                prune(&mut g);
            }
        }
    }
    g
}

/// An operator drawn with the given probabilities.
pub fn draw<R: Rng>(operators: &[(Operator, f64)], rng: &mut R) -> Operator {
    let total: f64 = operators.iter().map(|o| o.1).sum();
    let mut u = rng.random::<f64>() * total;
    for &(op, p) in operators {
        if u < p {
            return op;
        }
        u -= p;
    }
    operators.last().map_or(Operator::MutateEdge, |o| o.0)
}

/// Euclidean distance between two neurons' cells.
fn distance(a: &NeuronSpec, b: &NeuronSpec) -> f64 {
    let ((ax, ay), (bx, by)) = (a.cell(), b.cell());
    (ax as f64 - bx as f64).hypot(ay as f64 - by as f64)
}

/// A candidate pair (source not an actuator, target not sensing, not the same neuron, not
/// already joined, both within `max_dist` of each other and, for node addition, of `near`),
/// drawn with the ω weights; `None` when there is none.
fn pick_pair<R: Rng>(g: &GraphSpec, t: &Topology, near: Option<(usize, usize)>, rng: &mut R) -> Option<(usize, usize)> {
    let n = g.neurons.len();
    let near_ok = |i: usize| {
        near.is_none_or(|(x, y)| {
            let (cx, cy) = g.neurons[i].cell();
            (cx as f64 - x as f64).hypot(cy as f64 - y as f64) <= t.max_dist
        })
    };
    let mut existing: Vec<(usize, usize)> = g.edges.iter().map(|e| (e.from, e.to)).collect();
    existing.sort_unstable();
    let mut candidates: Vec<(usize, usize, f64)> = Vec::new();
    for from in (0..n).filter(|&i| !matches!(g.neurons[i], NeuronSpec::Actuator { .. }) && near_ok(i)) {
        for to in (0..n).filter(|&j| !matches!(g.neurons[j], NeuronSpec::Sensing { .. }) && near_ok(j)) {
            if from == to || distance(&g.neurons[from], &g.neurons[to]) > t.max_dist {
                continue;
            }
            // node addition puts a neuron between them, so an existing edge does not matter
            if near.is_none() && existing.binary_search(&(from, to)).is_ok() {
                continue;
            }
            let within = t.within(g.neurons[from].cell(), g.neurons[to].cell());
            let weight = if within { t.omega[0] } else { t.omega[1] };
            if weight > 0.0 {
                candidates.push((from, to, weight));
            }
        }
    }
    let total: f64 = candidates.iter().map(|c| c.2).sum();
    let mut u = rng.random::<f64>() * total;
    for &(from, to, w) in &candidates {
        if u < w {
            return Some((from, to));
        }
        u -= w;
    }
    candidates.last().map(|c| (c.0, c.1))
}

fn push_edge<R: Rng>(g: &mut GraphSpec, from: usize, to: usize, rng: &mut R) {
    g.edges.push(EdgeSpec { from, to });
    g.parameters.push(rng.random_range(-1.0..=1.0));
    g.parameters.push(rng.random_range(-1.0..=1.0));
}

/// Removes the edges for which `gone` is true, with their parameters.
fn remove_edges(g: &mut GraphSpec, mut gone: impl FnMut(&EdgeSpec) -> bool) {
    let mut edges = Vec::with_capacity(g.edges.len());
    let mut parameters = Vec::with_capacity(g.parameters.len());
    for (k, e) in g.edges.iter().enumerate() {
        if !gone(e) {
            edges.push(*e);
            parameters.extend_from_slice(&g.parameters[2 * k..2 * k + 2]);
        }
    }
    g.edges = edges;
    g.parameters = parameters;
}

/// Removes hidden neurons without edges and renumbers the edges.
pub(crate) fn prune(g: &mut GraphSpec) {
    let mut used: Vec<bool> = g
        .neurons
        .iter()
        .map(|n| !matches!(n, NeuronSpec::Hidden { .. }))
        .collect();
    for e in &g.edges {
        used[e.from] = true;
        used[e.to] = true;
    }
    let mut new_index = vec![usize::MAX; g.neurons.len()];
    let mut neurons = Vec::with_capacity(g.neurons.len());
    for (i, n) in g.neurons.iter().enumerate() {
        if used[i] {
            new_index[i] = neurons.len();
            neurons.push(n.clone());
        }
    }
    g.neurons = neurons;
    for e in &mut g.edges {
        e.from = new_index[e.from];
        e.to = new_index[e.to];
    }
}

/// A standard normal draw (Box–Muller).
fn gaussian<R: Rng>(rng: &mut R) -> f64 {
    let u: f64 = 1.0 - rng.random::<f64>();
    let v: f64 = rng.random();
    (-2.0 * u.ln()).sqrt() * (2.0 * std::f64::consts::PI * v).cos()
}
