//! A NEAT genome: node genes (inputs, outputs, hidden nodes with a bias and an activation) and
//! connection genes (from, to, weight, enabled, innovation), feed-forward; its output for an
//! input, the compatibility distance, crossover and the mutations.

use super::{Activation, Innovations};
use crate::rng::SeededRng;
use serde::{Deserialize, Serialize};

/// What a node is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NodeKind {
    /// An input: its value is given.
    Input,
    /// An output.
    Output,
    /// A node added by mutation.
    Hidden,
}

/// A node: id, kind, and (for outputs and hidden nodes) bias and activation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodeGene {
    /// Its id: inputs 0..I, outputs I..I+O, then hidden nodes by [`Innovations::split`].
    pub id: u32,
    /// Its kind.
    pub kind: NodeKind,
    /// Added to its weighted inputs.
    pub bias: f64,
    /// Applied to the sum.
    pub activation: Activation,
}

/// A connection: from → to with a weight, possibly disabled, with its innovation number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ConnectionGene {
    /// Its innovation number ([`Innovations::connection`]).
    pub innovation: u32,
    /// Source node id.
    pub from: u32,
    /// Target node id.
    pub to: u32,
    /// Weight.
    pub weight: f64,
    /// Whether it is expressed.
    pub enabled: bool,
}

/// A feed-forward network genome, nodes by id and connections by innovation number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NetworkGenome {
    /// Node genes, by id.
    pub nodes: Vec<NodeGene>,
    /// Connection genes, by innovation.
    pub connections: Vec<ConnectionGene>,
}

/// Largest weight or bias magnitude (neat-python's default bounds).
pub const MAX_WEIGHT: f64 = 30.0;

/// How a genome's weights and structure change (NEAT's mutation settings).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Mutation {
    /// Probability that a weight or bias is changed (0.8).
    pub weight_rate: f64,
    /// Standard deviation of a weight perturbation (0.5).
    pub weight_power: f64,
    /// Probability that a changed weight is drawn anew from N(0, 1) instead (0.1).
    pub weight_replace_rate: f64,
    /// Probability of adding a connection (0.5).
    pub add_connection: f64,
    /// Probability of splitting a connection with a node (0.2).
    pub add_node: f64,
    /// Probability of deleting a connection gene (0; EvoGym's CPPN-NEAT: 0.2).
    pub delete_connection: f64,
    /// Probability of deleting a hidden node with its connections (0; EvoGym's CPPN-NEAT: 0.2).
    pub delete_node: f64,
    /// Probability that a node's activation is drawn anew (0.1).
    pub activation_rate: f64,
    /// Activations new and mutated nodes draw from.
    pub activations: Vec<Activation>,
}

impl Default for Mutation {
    fn default() -> Self {
        Mutation {
            weight_rate: 0.8,
            weight_power: 0.5,
            weight_replace_rate: 0.1,
            add_connection: 0.5,
            add_node: 0.2,
            delete_connection: 0.0,
            delete_node: 0.0,
            activation_rate: 0.1,
            activations: Activation::ALL.to_vec(),
        }
    }
}

impl NodeGene {
    /// Input node `id` (no bias, identity).
    pub fn input(id: u32) -> NodeGene {
        NodeGene {
            id,
            kind: NodeKind::Input,
            bias: 0.0,
            activation: Activation::Identity,
        }
    }
}

impl NetworkGenome {
    /// `inputs` inputs fully connected to `outputs` outputs, weights and biases from N(0, 1),
    /// output activation `output`.
    pub fn initial(
        inputs: usize,
        outputs: usize,
        output: Activation,
        innovations: &mut Innovations,
        rng: &mut SeededRng,
    ) -> NetworkGenome {
        let mut nodes: Vec<NodeGene> = (0..inputs as u32).map(NodeGene::input).collect();
        for o in 0..outputs as u32 {
            nodes.push(NodeGene {
                id: inputs as u32 + o,
                kind: NodeKind::Output,
                bias: rng.normal(),
                activation: output,
            });
        }
        let mut connections = Vec::new();
        for o in 0..outputs as u32 {
            for i in 0..inputs as u32 {
                let to = inputs as u32 + o;
                connections.push(ConnectionGene {
                    innovation: innovations.connection(i, to),
                    from: i,
                    to,
                    weight: rng.normal(),
                    enabled: true,
                });
            }
        }
        connections.sort_by_key(|c| c.innovation);
        NetworkGenome { nodes, connections }
    }

    fn node(&self, id: u32) -> Option<&NodeGene> {
        self.nodes.iter().find(|n| n.id == id)
    }

    /// The outputs for `inputs` (one value per input node): each node, in an order where every
    /// source comes first, gets its activation of bias plus the weighted values of its enabled
    /// incoming connections.
    pub fn evaluate(&self, inputs: &[f64]) -> Vec<f64> {
        let mut value: std::collections::BTreeMap<u32, f64> = std::collections::BTreeMap::new();
        let input_nodes = self.nodes.iter().filter(|n| n.kind == NodeKind::Input);
        for (i, n) in input_nodes.enumerate() {
            value.insert(n.id, inputs.get(i).copied().unwrap_or(0.0));
        }
        for id in self.order() {
            let node = self.node(id).expect("ordered nodes exist");
            let sum: f64 = self
                .connections
                .iter()
                .filter(|c| c.enabled && c.to == id)
                .map(|c| c.weight * value.get(&c.from).copied().unwrap_or(0.0))
                .sum();
            value.insert(id, node.activation.apply(node.bias + sum));
        }
        self.nodes
            .iter()
            .filter(|n| n.kind == NodeKind::Output)
            .map(|n| value[&n.id])
            .collect()
    }

    /// Non-input node ids, each after every node it receives an enabled connection from.
    fn order(&self) -> Vec<u32> {
        let mut done: Vec<u32> = self
            .nodes
            .iter()
            .filter(|n| n.kind == NodeKind::Input)
            .map(|n| n.id)
            .collect();
        let mut left: Vec<u32> = self
            .nodes
            .iter()
            .filter(|n| n.kind != NodeKind::Input)
            .map(|n| n.id)
            .collect();
        let mut order = Vec::new();
        while !left.is_empty() {
            let ready: Vec<u32> = left
                .iter()
                .copied()
                .filter(|&id| {
                    self.connections
                        .iter()
                        .filter(|c| c.enabled && c.to == id)
                        .all(|c| done.contains(&c.from) || !left.contains(&c.from))
                })
                .collect();
            // a cycle cannot arise (add_connection refuses one); take the rest as they come
            let ready = if ready.is_empty() { left.clone() } else { ready };
            left.retain(|id| !ready.contains(id));
            done.extend(&ready);
            order.extend(ready);
        }
        order
    }

    /// Whether `to` reaches `from` through enabled or disabled connections (so that a new
    /// connection from → to would close a cycle).
    fn reaches(&self, to: u32, from: u32) -> bool {
        let mut stack = vec![to];
        let mut seen = vec![to];
        while let Some(n) = stack.pop() {
            if n == from {
                return true;
            }
            for c in self.connections.iter().filter(|c| c.from == n) {
                if !seen.contains(&c.to) {
                    seen.push(c.to);
                    stack.push(c.to);
                }
            }
        }
        false
    }

    /// The compatibility distance δ = c1·E/N + c2·D/N + c3·W̄ (excess, disjoint, mean weight
    /// difference of matching genes; N the larger genome's connection count, at least 1).
    pub fn distance(&self, other: &NetworkGenome, c1: f64, c2: f64, c3: f64) -> f64 {
        let last = |g: &NetworkGenome| g.connections.last().map_or(0, |c| c.innovation);
        let cut = last(self).min(last(other));
        let (mut excess, mut disjoint, mut matching, mut difference) = (0.0, 0.0, 0.0, 0.0);
        for c in &self.connections {
            match other.connections.iter().find(|o| o.innovation == c.innovation) {
                Some(o) => {
                    matching += 1.0;
                    difference += (c.weight - o.weight).abs();
                }
                None if c.innovation > cut => excess += 1.0,
                None => disjoint += 1.0,
            }
        }
        for o in &other.connections {
            if !self.connections.iter().any(|c| c.innovation == o.innovation) {
                if o.innovation > cut {
                    excess += 1.0;
                } else {
                    disjoint += 1.0;
                }
            }
        }
        let n = self.connections.len().max(other.connections.len()).max(1) as f64;
        let mean = if matching > 0.0 { difference / matching } else { 0.0 };
        c1 * excess / n + c2 * disjoint / n + c3 * mean
    }

    /// A child of `self` (the fitter parent) and `other`: matching genes from either at random,
    /// the others from `self`; a gene disabled in either parent stays disabled with probability
    /// 0.75.
    pub fn crossover(&self, other: &NetworkGenome, rng: &mut SeededRng) -> NetworkGenome {
        let connections = self
            .connections
            .iter()
            .map(
                |c| match other.connections.iter().find(|o| o.innovation == c.innovation) {
                    Some(o) => {
                        let mut gene = if rng.uniform() < 0.5 { c.clone() } else { o.clone() };
                        gene.enabled = if !c.enabled || !o.enabled {
                            rng.uniform() >= 0.75
                        } else {
                            true
                        };
                        gene
                    }
                    None => c.clone(),
                },
            )
            .collect();
        let nodes = self
            .nodes
            .iter()
            .map(|n| match other.node(n.id) {
                Some(o) if rng.uniform() < 0.5 => NodeGene {
                    id: n.id,
                    kind: n.kind,
                    ..o.clone()
                },
                _ => n.clone(),
            })
            .collect();
        NetworkGenome { nodes, connections }
    }

    /// Applies NEAT's mutations: structural ones (a node, a connection) with their
    /// probabilities, then weights, biases and activations.
    pub fn mutate(&mut self, settings: &Mutation, innovations: &mut Innovations, rng: &mut SeededRng) {
        if rng.uniform() < settings.add_node {
            self.add_node(settings, innovations, rng);
        }
        if rng.uniform() < settings.add_connection {
            self.add_connection(innovations, rng);
        }
        // the deletions draw only when they may happen, so that runs without them keep their
        // random streams
        if settings.delete_node > 0.0 && rng.uniform() < settings.delete_node {
            self.delete_node(rng);
        }
        if settings.delete_connection > 0.0 && rng.uniform() < settings.delete_connection {
            self.delete_connection(rng);
        }
        let change = |value: &mut f64, rng: &mut SeededRng| {
            if rng.uniform() < settings.weight_rate {
                *value = if rng.uniform() < settings.weight_replace_rate {
                    rng.normal()
                } else {
                    *value + settings.weight_power * rng.normal()
                }
                .clamp(-MAX_WEIGHT, MAX_WEIGHT);
            }
        };
        for c in &mut self.connections {
            change(&mut c.weight, rng);
        }
        for n in self.nodes.iter_mut().filter(|n| n.kind != NodeKind::Input) {
            change(&mut n.bias, rng);
            if !settings.activations.is_empty() && rng.uniform() < settings.activation_rate {
                n.activation = settings.activations[rng.below(settings.activations.len())];
            }
        }
    }

    /// Splits a random enabled connection a → b into a → new (weight 1) and new → b (the old
    /// weight), disabling it.
    fn add_node(&mut self, settings: &Mutation, innovations: &mut Innovations, rng: &mut SeededRng) {
        let enabled: Vec<usize> = (0..self.connections.len())
            .filter(|&i| self.connections[i].enabled)
            .collect();
        if enabled.is_empty() {
            return;
        }
        let k = enabled[rng.below(enabled.len())];
        let (from, to, weight) = (
            self.connections[k].from,
            self.connections[k].to,
            self.connections[k].weight,
        );
        let id = innovations.split(from, to);
        if self.node(id).is_some() {
            return; // this genome split it before
        }
        self.connections[k].enabled = false;
        let activation = match settings.activations.len() {
            0 => Activation::Sigmoid,
            n => settings.activations[rng.below(n)],
        };
        self.nodes.push(NodeGene {
            id,
            kind: NodeKind::Hidden,
            bias: 0.0,
            activation,
        });
        self.nodes.sort_by_key(|n| n.id);
        for (a, b, w) in [(from, id, 1.0), (id, to, weight)] {
            self.connections.push(ConnectionGene {
                innovation: innovations.connection(a, b),
                from: a,
                to: b,
                weight: w,
                enabled: true,
            });
        }
        self.connections.sort_by_key(|c| c.innovation);
    }

    /// Removes a random hidden node and every connection into or out of it (neat-python's
    /// node deletion); nothing when there is no hidden node.
    fn delete_node(&mut self, rng: &mut SeededRng) {
        let hidden: Vec<u32> = self
            .nodes
            .iter()
            .filter(|n| n.kind == NodeKind::Hidden)
            .map(|n| n.id)
            .collect();
        if hidden.is_empty() {
            return;
        }
        let id = hidden[rng.below(hidden.len())];
        self.nodes.retain(|n| n.id != id);
        self.connections.retain(|c| c.from != id && c.to != id);
    }

    /// Removes a random connection gene; nothing when there is none.
    fn delete_connection(&mut self, rng: &mut SeededRng) {
        if !self.connections.is_empty() {
            let k = rng.below(self.connections.len());
            self.connections.remove(k);
        }
    }

    /// Adds a connection between two unconnected nodes (never into an input, never closing a
    /// cycle), weight from N(0, 1); re-enables it if it exists disabled.
    fn add_connection(&mut self, innovations: &mut Innovations, rng: &mut SeededRng) {
        let from = self.nodes[rng.below(self.nodes.len())].id;
        let targets: Vec<u32> = self
            .nodes
            .iter()
            .filter(|n| n.kind != NodeKind::Input)
            .map(|n| n.id)
            .collect();
        if targets.is_empty() {
            return;
        }
        let to = targets[rng.below(targets.len())];
        if from == to || self.reaches(to, from) {
            return;
        }
        if let Some(existing) = self.connections.iter_mut().find(|c| c.from == from && c.to == to) {
            existing.enabled = true;
            return;
        }
        self.connections.push(ConnectionGene {
            innovation: innovations.connection(from, to),
            from,
            to,
            weight: rng.normal().clamp(-MAX_WEIGHT, MAX_WEIGHT),
            enabled: true,
        });
        self.connections.sort_by_key(|c| c.innovation);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Stream;

    fn rng(i: u64) -> SeededRng {
        SeededRng::derive(1, 0, i, Stream::Variation)
    }

    #[test]
    fn deletions_remove_a_hidden_node_with_its_connections_or_one_connection() {
        let mut innovations = Innovations::new(3);
        let mut g = NetworkGenome::initial(2, 1, Activation::Identity, &mut innovations, &mut rng(0));
        let settings = Mutation::default();
        g.add_node(&settings, &mut innovations, &mut rng(1));
        let hidden = g.nodes.iter().find(|n| n.kind == NodeKind::Hidden).unwrap().id;
        g.delete_node(&mut rng(2));
        assert_eq!(g.nodes.len(), 3, "the inputs and the output stay");
        assert!(g.connections.iter().all(|c| c.from != hidden && c.to != hidden));
        assert_eq!(g.connections.len(), 2, "the disabled original and the other input's");
        g.delete_node(&mut rng(3));
        assert_eq!(g.nodes.len(), 3, "no hidden node: nothing deleted");
        g.delete_connection(&mut rng(4));
        g.delete_connection(&mut rng(5));
        g.delete_connection(&mut rng(6));
        assert!(g.connections.is_empty());
        assert_eq!(
            g.evaluate(&[0.3, 0.4]).len(),
            1,
            "a network without connections still answers"
        );
    }

    #[test]
    fn a_split_keeps_the_function_of_an_identity_path_and_structure_stays_acyclic() {
        let mut innovations = Innovations::new(3);
        let mut g = NetworkGenome::initial(2, 1, Activation::Identity, &mut innovations, &mut rng(0));
        let before = g.evaluate(&[0.3, -0.2]);
        let settings = Mutation {
            activations: vec![Activation::Identity],
            ..Mutation::default()
        };
        g.add_node(&settings, &mut innovations, &mut rng(1));
        assert_eq!(g.nodes.len(), 4);
        assert_eq!(g.connections.iter().filter(|c| c.enabled).count(), 3);
        // identity hidden node, weight 1 in, old weight out, bias 0: the same output
        assert!((g.evaluate(&[0.3, -0.2])[0] - before[0]).abs() < 1e-12);
        for i in 0..200 {
            g.mutate(&Mutation::default(), &mut innovations, &mut rng(10 + i));
            assert!(
                g.connections.iter().all(|c| !g.reaches(c.to, c.from) || c.from == c.to),
                "acyclic"
            );
            assert!(g.evaluate(&[0.5, 0.5]).iter().all(|v| v.is_finite()));
        }
        assert!(g.nodes.len() > 10, "{} nodes", g.nodes.len());
    }

    #[test]
    fn distance_counts_excess_disjoint_and_weight_differences() {
        let mut innovations = Innovations::new(3);
        let a = NetworkGenome::initial(2, 1, Activation::Sigmoid, &mut innovations, &mut rng(0));
        assert_eq!(a.distance(&a, 1.0, 1.0, 0.4), 0.0);
        let mut b = a.clone();
        b.connections[0].weight += 1.0;
        assert!((a.distance(&b, 1.0, 1.0, 0.4) - 0.4 * 0.5).abs() < 1e-12);
        let mut c = a.clone();
        c.add_node(&Mutation::default(), &mut innovations, &mut rng(3));
        // two new genes beyond a's last innovation, out of 4: excess 2/4
        assert!((a.distance(&c, 1.0, 1.0, 0.0) - 0.5).abs() < 1e-12);
        // crossover with the fitter parent's structure
        let child = c.crossover(&a, &mut rng(4));
        assert_eq!(child.connections.len(), c.connections.len());
        assert_eq!(child.nodes.len(), c.nodes.len());
    }
}
