//! Property tests of the graph brain: random valid graphs (hidden neurons anywhere in the body,
//! random edges obeying the rules, weights up to ±100) give finite actuations in [−1, 1], and
//! renumbering the neurons never changes them.

use proptest::prelude::*;
use vsrlab_body::Morphology;
use vsrlab_brain::BrainShape;
use vsrlab_brain::{Activation, Controller, EdgeSpec, GraphSpec, NeuronSpec};

/// A random valid graph on the biped-4x3 with 2 readings per voxel, from a list of draws.
fn graph(draws: &[u32], params: &[f64]) -> GraphSpec {
    let m = Morphology::named("biped-4x3").unwrap();
    let cells: Vec<(usize, usize)> = m.voxels().collect();
    let (mut neurons, mut edges) = GraphSpec::initial(&BrainShape::grid(&m, &[2; 10]));
    let activations = [
        Activation::Sigmoid,
        Activation::Tanh,
        Activation::Identity,
        Activation::Relu,
    ];
    for (k, d) in draws.iter().enumerate() {
        let n = neurons.len();
        match d % 3 {
            0 => {
                let (x, y) = cells[(*d as usize / 3) % cells.len()];
                neurons.push(NeuronSpec::Hidden {
                    x,
                    y,
                    activation: activations[k % 4],
                });
                // a self-loop on every other hidden neuron: feedback through unbounded activations
                if k % 2 == 0 {
                    edges.push(EdgeSpec { from: n, to: n });
                }
            }
            _ => {
                let from = (*d as usize / 3) % n;
                let to = (*d as usize / 7 + k) % n;
                let ok_from = !matches!(neurons[from], NeuronSpec::Actuator { .. });
                let ok_to = !matches!(neurons[to], NeuronSpec::Sensing { .. });
                if ok_from && ok_to {
                    edges.push(EdgeSpec { from, to });
                }
            }
        }
    }
    let parameters = (0..2 * edges.len()).map(|k| params[k % params.len()]).collect();
    GraphSpec {
        neurons,
        edges,
        parameters,
        grow: 0,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_graphs_stay_finite_and_ignore_neuron_order(
        draws in proptest::collection::vec(any::<u32>(), 0..120),
        params in proptest::collection::vec(-100.0f64..100.0, 1..50),
        readings in proptest::collection::vec(-10.0f64..10.0, 20 * 8),
        rotate in 1usize..50,
    ) {
        let m = Morphology::named("biped-4x3").unwrap();
        let g = graph(&draws, &params);
        let n = g.neurons.len();
        // renumber: neuron i becomes (i + rotate) mod n
        let new = |i: usize| (i + rotate) % n;
        let mut neurons = g.neurons.clone();
        for (i, neuron) in g.neurons.iter().enumerate() {
            neurons[new(i)] = neuron.clone();
        }
        let shuffled = GraphSpec {
            neurons,
            edges: g.edges.iter().map(|e| EdgeSpec { from: new(e.from), to: new(e.to) }).collect(),
            parameters: g.parameters.clone(),
            grow: 0,
        };
        let mut a = g.controller(&BrainShape::grid(&m, &[2; 10])).unwrap();
        let mut b = shuffled.controller(&BrainShape::grid(&m, &[2; 10])).unwrap();
        let (mut out_a, mut out_b) = (vec![0.0; 10], vec![0.0; 10]);
        for k in 0..200 {
            let r = &readings[(k % 8) * 20..(k % 8 + 1) * 20];
            a.control(k as f64 / 60.0, r, &mut out_a);
            b.control(k as f64 / 60.0, r, &mut out_b);
            prop_assert!(out_a.iter().all(|x| x.is_finite() && x.abs() <= 1.0), "{:?}", out_a);
            prop_assert_eq!(&out_a, &out_b);
            prop_assert!(a.outputs().iter().all(|x| x.is_finite()), "step {}: a neuron overflowed", k);
        }
    }
}
