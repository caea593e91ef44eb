//! Property test of the graph operators: from the initial graph of a biped, any sequence of the
//! five operators, with any connectivity and modularity bias, gives a valid graph (the brain
//! builds), no edge longer than the connectivity allows, no hidden neuron without edges, and one
//! weight and bias per edge.

use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use vsrlab_body::Morphology;
use vsrlab_brain::graph_modules::ModuleMap;
use vsrlab_brain::graph_ops::{apply, draw, Operator, Topology, EDGE_SIGMA, THESIS_OPERATORS};
use vsrlab_brain::BrainShape;
use vsrlab_brain::{BrainKind, GraphSpec, NeuronSpec};

/// The thesis' biped modules: column 0, column 3, the middle columns.
fn biped_modules() -> ModuleMap {
    ModuleMap::parse("legs-torso", &Morphology::named("biped-4x3").unwrap()).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn every_operator_keeps_the_graph_valid(
        seed in any::<u64>(),
        steps in 1usize..300,
        max_dist in prop_oneof![Just(0.0f64), Just(1.0), Just(f64::INFINITY)],
        omega in prop_oneof![Just([1.0, 1.0]), Just([10.0, 1.0]), Just([1.0, 10.0])],
        uniform in any::<bool>(),
    ) {
        let m = Morphology::named("biped-4x3").unwrap();
        let rpv = vec![2; 10];
        let (neurons, edges) = GraphSpec::initial(&BrainShape::grid(&m, &rpv));
        let mut g = GraphSpec { parameters: vec![0.1; 2 * edges.len()], neurons, edges, grow: 0 };
        let topology = Topology { max_dist, omega, modules: Some(biped_modules()), sigma: EDGE_SIGMA };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let uniform_ops = [
            (Operator::AddNode, 1.0), (Operator::RemoveNode, 1.0), (Operator::AddEdge, 1.0),
            (Operator::RemoveEdge, 1.0), (Operator::MutateEdge, 1.0), (Operator::RemoveCrossingEdge, 1.0),
        ];
        for step in 0..steps {
            let op = draw(if uniform { &uniform_ops } else { &THESIS_OPERATORS }, &mut rng);
            g = apply(&g, op, &topology, &mut rng);
            prop_assert_eq!(g.parameters.len(), 2 * g.edges.len());
            let count = g.parameter_count(&BrainShape::grid(&m, &rpv));
            prop_assert!(count.is_ok(), "step {} ({:?}): {:?}", step, op, count);
            for e in &g.edges {
                let ((ax, ay), (bx, by)) = (g.neurons[e.from].cell(), g.neurons[e.to].cell());
                let d = (ax as f64 - bx as f64).hypot(ay as f64 - by as f64);
                prop_assert!(d <= max_dist, "edge {:?} of length {} > {}", e, d, max_dist);
            }
            for (i, n) in g.neurons.iter().enumerate() {
                if matches!(n, NeuronSpec::Hidden { .. }) {
                    prop_assert!(g.edges.iter().any(|e| e.from == i || e.to == i), "orphan hidden neuron {}", i);
                }
            }
            prop_assert!(g.parameters.iter().all(|p| p.is_finite()));
        }
        // the sensing neurons and actuators are never removed
        prop_assert_eq!(g.neurons.iter().filter(|n| !matches!(n, NeuronSpec::Hidden { .. })).count(), 30);
    }
}

#[test]
fn the_modularity_bias_favours_its_kind_of_edge() {
    // from the initial biped graph (max_dist ∞), count crossing edges among 2 000 additions
    let m = Morphology::named("biped-4x3").unwrap();
    let rpv = vec![2; 10];
    let (neurons, edges) = GraphSpec::initial(&BrainShape::grid(&m, &rpv));
    let g = GraphSpec {
        parameters: vec![0.0; 2 * edges.len()],
        neurons,
        edges,
        grow: 0,
    };
    let crossing_share = |omega: [f64; 2]| {
        let t = Topology {
            max_dist: f64::INFINITY,
            omega,
            modules: Some(biped_modules()),
            sigma: EDGE_SIGMA,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let mut crossing = 0;
        for _ in 0..2000 {
            let added = apply(&g, Operator::AddEdge, &t, &mut rng);
            let e = added.edges.last().unwrap();
            let (a, b) = (added.neurons[e.from].cell(), added.neurons[e.to].cell());
            crossing += usize::from(!biped_modules().same(a, b));
        }
        crossing as f64 / 2000.0
    };
    let (plain, modular, unmodular) = (
        crossing_share([1.0, 1.0]),
        crossing_share([10.0, 1.0]),
        crossing_share([1.0, 10.0]),
    );
    assert!(modular < plain && plain < unmodular, "{modular} {plain} {unmodular}");
    assert!(modular < 0.2 && unmodular > 0.8, "{modular} {unmodular}");
}
