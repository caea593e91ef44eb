//! Disassembly and reassembly of graph brains (thesis §4.1.5.2–4.1.5.4, thesis-code-facts.md
//! §4.5): a hybrid brain keeps one donor's graph outside a body region and takes the other
//! donor's graph inside it. Edges that cross the region's boundary are dropped from both donors
//! and not re-created (the original's rewiring step is disabled).
//!
//! The original relies on both donors numbering their sensing neurons and actuators alike; here
//! the inside donor's edges are re-attached by what their ends are (an actuator of a cell, a
//! sensing neuron of a cell and reading), so the two graphs may list neurons in any order. An
//! inside edge whose end has no counterpart in the kept graph (donors with other sensors) is
//! dropped and counted as such.

use crate::controllers::graph::{EdgeSpec, GraphSpec, NeuronSpec};
use crate::graph_modules::{is_hidden, mass, Cell};
use crate::graph_ops::prune;

/// What disassembly cost one donor's module: its edges before (those with at least one end in
/// the module) and those dropped (crossing its boundary), by count and by |w| + |b| mass.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Cut {
    /// Edges with at least one end in the module.
    pub edges: usize,
    /// Of those, the ones crossing the boundary (dropped).
    pub dropped: usize,
    /// Mass of `edges`.
    pub mass: f64,
    /// Mass of `dropped`.
    pub dropped_mass: f64,
}

impl Cut {
    /// The cut of the module of `g` made of the cells for which `inside` holds.
    fn of(g: &GraphSpec, inside: impl Fn(Cell) -> bool) -> Cut {
        let mut cut = Cut::default();
        for (k, e) in g.edges.iter().enumerate() {
            let (a, b) = (inside(g.neurons[e.from].cell()), inside(g.neurons[e.to].cell()));
            if a || b {
                cut.edges += 1;
                cut.mass += mass(g, k);
                if a != b {
                    cut.dropped += 1;
                    cut.dropped_mass += mass(g, k);
                }
            }
        }
        cut
    }

    /// Both cuts together.
    pub fn plus(self, other: Cut) -> Cut {
        Cut {
            edges: self.edges + other.edges,
            dropped: self.dropped + other.dropped,
            mass: self.mass + other.mass,
            dropped_mass: self.dropped_mass + other.dropped_mass,
        }
    }

    /// η_num: the share of the module's edges dropped (0 when it had none).
    pub fn eta_num(&self) -> f64 {
        if self.edges == 0 {
            0.0
        } else {
            self.dropped as f64 / self.edges as f64
        }
    }

    /// η_weight: the share of the module's |w| + |b| mass dropped (0 when it had none).
    pub fn eta_weight(&self) -> f64 {
        if self.mass > 0.0 {
            self.dropped_mass / self.mass
        } else {
            0.0
        }
    }
}

/// A reassembled brain and what disassembly cost each donor.
#[derive(Debug, Clone, PartialEq)]
pub struct Reassembly {
    /// The hybrid graph.
    pub graph: GraphSpec,
    /// The kept donor's module (the cells outside the region).
    pub outside: Cut,
    /// The inside donor's module (the cells of the region).
    pub inside: Cut,
    /// Inside edges dropped because the kept graph has no counterpart for an end.
    pub unmatched: usize,
}

impl Reassembly {
    /// Both modules' cuts together (η over the reassembled robot's two modules).
    pub fn total(&self) -> Cut {
        self.outside.plus(self.inside)
    }
}

/// What a non-hidden neuron is, for matching across graphs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Identity {
    Sensing(Cell, usize),
    Actuator(Cell),
}

fn identity(n: &NeuronSpec) -> Option<Identity> {
    match *n {
        NeuronSpec::Sensing { x, y, reading } => Some(Identity::Sensing((x, y), reading)),
        NeuronSpec::Actuator { x, y } => Some(Identity::Actuator((x, y))),
        NeuronSpec::Hidden { .. } => None,
    }
}

/// The hybrid of `outside_donor` (kept outside `region`) and `inside_donor` (taken inside it),
/// both with their neurons listed and for the same body. From a copy of the outside donor, every
/// edge touching the region and every hidden neuron in it go; the inside donor's hidden neurons in
/// the region and its edges with both ends there come in; hidden neurons left without edges are
/// pruned.
pub fn reassemble(outside_donor: &GraphSpec, inside_donor: &GraphSpec, region: &[Cell]) -> Reassembly {
    let inside = |c: Cell| region.contains(&c);
    let outside_cut = Cut::of(outside_donor, |c| !inside(c));
    let inside_cut = Cut::of(inside_donor, inside);

    // the outside donor without anything touching the region
    let mut g = GraphSpec::default();
    let mut new_index = vec![usize::MAX; outside_donor.neurons.len()];
    for (i, n) in outside_donor.neurons.iter().enumerate() {
        if !(is_hidden(n) && inside(n.cell())) {
            new_index[i] = g.neurons.len();
            g.neurons.push(n.clone());
        }
    }
    for (k, e) in outside_donor.edges.iter().enumerate() {
        let (a, b) = (&outside_donor.neurons[e.from], &outside_donor.neurons[e.to]);
        if !inside(a.cell()) && !inside(b.cell()) {
            g.edges.push(EdgeSpec {
                from: new_index[e.from],
                to: new_index[e.to],
            });
            g.parameters
                .extend_from_slice(&outside_donor.parameters[2 * k..2 * k + 2]);
        }
    }

    // the inside donor's neurons in the region: hidden ones appended, the others matched
    let mut mapped = vec![None; inside_donor.neurons.len()];
    for (i, n) in inside_donor.neurons.iter().enumerate() {
        if !inside(n.cell()) {
            continue;
        }
        mapped[i] = match identity(n) {
            None => {
                g.neurons.push(n.clone());
                Some(g.neurons.len() - 1)
            }
            Some(id) => g.neurons.iter().position(|m| identity(m) == Some(id)),
        };
    }
    let mut unmatched = 0;
    for (k, e) in inside_donor.edges.iter().enumerate() {
        let (a, b) = (&inside_donor.neurons[e.from], &inside_donor.neurons[e.to]);
        if !(inside(a.cell()) && inside(b.cell())) {
            continue;
        }
        match (mapped[e.from], mapped[e.to]) {
            (Some(from), Some(to)) => {
                g.edges.push(EdgeSpec { from, to });
                g.parameters
                    .extend_from_slice(&inside_donor.parameters[2 * k..2 * k + 2]);
            }
            _ => unmatched += 1,
        }
    }
    prune(&mut g);
    Reassembly {
        graph: g,
        outside: outside_cut,
        inside: inside_cut,
        unmatched,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::graph_modules::compactness;
    use crate::Activation;

    fn hidden(x: usize, y: usize) -> NeuronSpec {
        NeuronSpec::Hidden {
            x,
            y,
            activation: Activation::Sigmoid,
        }
    }

    /// worm-2x1 with one reading per voxel: s0 s1 a0 a1, then the hidden neurons given.
    fn worm(hidden_neurons: &[NeuronSpec], edges: &[(usize, usize, f64)]) -> GraphSpec {
        let mut neurons = vec![
            NeuronSpec::Sensing { x: 0, y: 0, reading: 0 },
            NeuronSpec::Sensing { x: 1, y: 0, reading: 0 },
            NeuronSpec::Actuator { x: 0, y: 0 },
            NeuronSpec::Actuator { x: 1, y: 0 },
        ];
        neurons.extend_from_slice(hidden_neurons);
        GraphSpec {
            edges: edges.iter().map(|&(from, to, _)| EdgeSpec { from, to }).collect(),
            parameters: edges.iter().flat_map(|&(_, _, w)| [w, 0.0]).collect(),
            neurons,
            grow: 0,
        }
    }

    #[test]
    fn the_hybrid_keeps_each_side_and_drops_crossing_edges() {
        // A: s0→a0 (outside), s1→a0 (crossing), s0→h(1)→a1 (crossing, inside)
        let a = worm(&[hidden(1, 0)], &[(0, 2, 1.0), (1, 2, 2.0), (0, 4, 3.0), (4, 3, 4.0)]);
        // B lists its hidden neuron first in the region and uses other numbers: h(1) is index 4
        let b = worm(
            &[hidden(1, 0), hidden(0, 0)],
            &[(1, 4, 5.0), (4, 3, 6.0), (5, 2, 7.0), (0, 5, 8.0), (4, 2, 9.0)],
        );
        let r = reassemble(&a, &b, &[(1, 0)]);
        // outside (A's cell 0): s0→a0 kept; s1→a0 and s0→h dropped; h→a1 is inside A's region
        assert_eq!(
            r.outside,
            Cut {
                edges: 3,
                dropped: 2,
                mass: 6.0,
                dropped_mass: 5.0
            }
        );
        // inside (B's cell 1): s1→h, h→a1 kept; h→a0 (mass 9) dropped
        assert_eq!(
            r.inside,
            Cut {
                edges: 3,
                dropped: 1,
                mass: 20.0,
                dropped_mass: 9.0
            }
        );
        let g = &r.graph;
        assert_eq!(
            g.neurons.len(),
            5,
            "A's hidden neuron goes, B's hidden neuron in the region comes"
        );
        let described: Vec<(NeuronSpec, NeuronSpec, f64)> = g
            .edges
            .iter()
            .enumerate()
            .map(|(k, e)| (g.neurons[e.from].clone(), g.neurons[e.to].clone(), g.parameters[2 * k]))
            .collect();
        assert_eq!(
            described,
            vec![
                (a.neurons[0].clone(), a.neurons[2].clone(), 1.0),
                (a.neurons[1].clone(), hidden(1, 0), 5.0),
                (hidden(1, 0), a.neurons[3].clone(), 6.0),
            ]
        );
        let total = r.total();
        assert_eq!(total.eta_num(), 3.0 / 6.0);
        assert_eq!(total.eta_weight(), 14.0 / 26.0);
        assert_eq!(r.unmatched, 0);
    }

    #[test]
    fn eta_weight_is_one_minus_compactness_for_one_module() {
        let b = worm(&[hidden(1, 0)], &[(1, 4, 0.5), (4, 3, 1.5), (4, 2, 2.0)]);
        let r = reassemble(&b, &b, &[(1, 0)]);
        assert_eq!(r.inside.eta_weight(), 1.0 - compactness(&b, &[(1, 0)]));
        // the hybrid of a graph with itself loses exactly the crossing edges
        assert_eq!(r.graph.edges.len(), 2);
    }
}
