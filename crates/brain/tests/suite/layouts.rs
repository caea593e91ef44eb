//! Brains on layouts other than the 2D voxel grid: a distributed MLP on a 3D voxel grid (6
//! neighbours per voxel) and on a ring (a membrane's units).

use vsrlab_body::Morphology;
use vsrlab_brain::layout::grid3::DIRECTION_OFFSETS;
use vsrlab_brain::{
    Activation, BrainShape, BrainSpec, Controller, DistributedConfig, DistributedMlpController, Grid3Layout, Layout,
    RingLayout, UnitLayout,
};

fn config(signals: usize, activation: Activation, input_activation: bool) -> DistributedConfig {
    DistributedConfig {
        signals,
        hidden: Vec::new(),
        activation,
        input_activation,
        layout: Layout::Homogeneous,
        positional: false,
    }
}

/// Weights of one network without hidden layer: output o's bias and input weights from `f(o, i)`
/// (i = None for the bias).
fn weights(n_in: usize, n_out: usize, f: impl Fn(usize, Option<usize>) -> f64) -> Vec<f64> {
    let mut w = Vec::new();
    for o in 0..n_out {
        w.push(f(o, None));
        w.extend((0..n_in).map(|i| f(o, Some(i))));
    }
    w
}

#[test]
fn on_a_3d_grid_a_voxel_network_has_six_signal_blocks() {
    let cube = Grid3Layout::from_fn([3, 3, 3], |_, _, _| true);
    let shape = BrainShape::new(cube, vec![4; 27]);
    // r + 6s = 10 inputs, 1 + 6s = 7 outputs: 7·11 = 77 weights (45 on a 2D grid)
    let homogeneous = BrainSpec::parse("distributed-mlp").unwrap();
    assert_eq!(homogeneous.parameter_count(&shape), Ok(77));
    let heterogeneous = BrainSpec::parse("distributed-mlp-hetero").unwrap();
    assert_eq!(heterogeneous.parameter_count(&shape), Ok(27 * 77));
    // a filled spec builds and runs
    let spec = homogeneous.with_random_parameters(3, &shape).unwrap();
    let mut brain = spec.build(&shape).unwrap();
    let mut actuations = vec![0.0; 27];
    brain.control(0.0, &[0.5; 27 * 4], &mut actuations);
    assert!(actuations.iter().all(|a| a.is_finite() && a.abs() <= 1.0));
}

#[test]
fn on_a_3d_grid_signals_arrive_from_every_present_neighbour() {
    let filled = |x: usize, y: usize, z: usize| (x + 2 * y + z) % 4 != 3;
    let extent = [3, 2, 3];
    let layout = Grid3Layout::from_fn(extent, filled);
    let n = layout.units();
    let shape = BrainShape::new(layout.clone(), vec![0; n]);
    // identity network: the signal towards direction d is its bias, d + 1
    let w = weights(6, 7, |o, i| if o >= 1 && i.is_none() { o as f64 } else { 0.0 });
    let mut c = DistributedMlpController::new(&shape, &config(1, Activation::Identity, false), &w).unwrap();
    assert_eq!(c.directions(), 6);
    let mut a = vec![0.0; n];
    c.control(0.0, &[], &mut a);
    c.control(0.1, &[], &mut a);
    let mut links = 0;
    for v in 0..n {
        let [x, y, z] = layout.cell(v);
        for (d, offset) in DIRECTION_OFFSETS.iter().enumerate() {
            let at = |c: usize, o: isize, size: usize| c.checked_add_signed(o).filter(|&c| c < size);
            let present = match (
                at(x, offset[0], extent[0]),
                at(y, offset[1], extent[1]),
                at(z, offset[2], extent[2]),
            ) {
                (Some(nx), Some(ny), Some(nz)) => filled(nx, ny, nz),
                _ => false,
            };
            links += usize::from(present);
            // the neighbour sent it towards the opposite direction: the one with the negated offset
            let back = DIRECTION_OFFSETS.iter().position(|o| o.map(|c| -c) == *offset).unwrap();
            let expected = if present { (back + 1) as f64 } else { 0.0 };
            assert_eq!(
                c.incoming(v)[d],
                expected,
                "voxel {v} at {:?}, direction {d}",
                [x, y, z]
            );
        }
    }
    // the test body has links along z as well as in the plane
    assert!(links > 2 * n, "{links} links");
}

#[test]
fn one_voxel_deep_a_3d_brain_acts_as_the_2d_brain() {
    let biped = Morphology::named("biped-4x3").unwrap();
    let (r, n) = (3, biped.voxel_count());
    let flat = Grid3Layout::from_fn([4, 3, 1], |x, y, _| biped.has(x, y));
    let planar = BrainShape::grid(&biped, &vec![r; n]);
    let deep = BrainShape::new(flat, vec![r; n]);
    // 2D network: r + 4 inputs, 5 outputs; the 3D one has 2 more of each (−z, +z), weighted 0
    let w2 = weights(r + 4, 5, |o, i| {
        ((o * 31 + i.map_or(0, |i| i + 1) * 17) % 13) as f64 / 6.5 - 1.0
    });
    let w3 = weights(r + 6, 7, |o, i| match (o, i) {
        (5.., _) => 0.0,
        (_, Some(i)) if i >= r + 4 => 0.0,
        (o, i) => w2[o * (r + 5) + i.map_or(0, |i| i + 1)],
    });
    let cfg = config(1, Activation::Tanh, true);
    let mut c2 = DistributedMlpController::new(&planar, &cfg, &w2).unwrap();
    let mut c3 = DistributedMlpController::new(&deep, &cfg, &w3).unwrap();
    let (mut a2, mut a3) = (vec![0.0; n], vec![0.0; n]);
    for step in 0..50 {
        let readings: Vec<f64> = (0..n * r)
            .map(|k| ((k * 7 + step * 3) % 11) as f64 / 5.5 - 1.0)
            .collect();
        c2.control(step as f64, &readings, &mut a2);
        c3.control(step as f64, &readings, &mut a3);
        for (x, y) in a2.iter().zip(&a3) {
            assert!((x - y).abs() < 1e-12, "step {step}: {a2:?} vs {a3:?}");
        }
    }
    assert!(a2.iter().any(|a| a.abs() > 1e-3), "the brain does something: {a2:?}");
}

#[test]
fn on_a_ring_signals_go_round_and_loose_units_get_none() {
    let ring = RingLayout::new(5, 1);
    let shape = BrainShape::new(ring, vec![0; 6]);
    // output 1 (towards the previous unit) carries the unit's index + 1 once it has heard its next
    // neighbour; here simply: signal = bias 1 towards previous, 2 towards next
    let w = weights(2, 3, |o, i| match (o, i) {
        (1, None) => 1.0,
        (2, None) => 2.0,
        _ => 0.0,
    });
    let mut c = DistributedMlpController::new(&shape, &config(1, Activation::Identity, false), &w).unwrap();
    let mut a = vec![0.0; 6];
    c.control(0.0, &[], &mut a);
    c.control(0.1, &[], &mut a);
    for v in 0..5 {
        // from the previous unit (direction 0) comes what it sent towards its next: 2; from the
        // next unit what it sent towards its previous: 1
        assert_eq!(c.incoming(v), [2.0, 1.0], "unit {v}");
        assert_eq!(c.neighbours(v), [Some((v + 4) % 5), Some((v + 1) % 5)]);
    }
    assert_eq!(c.incoming(5), [0.0, 0.0]);
}
