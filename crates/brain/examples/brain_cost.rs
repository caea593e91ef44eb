//! The cost of one control step of each brain alone, without physics: random readings in [0, 1],
//! seeded random parameters, 200 000 steps each after a warm-up, nanoseconds per step.
//!
//!     cargo run --release -p vsrlab-brain --example brain_cost -- biped-4x3 4 mlp hebbian attention
//!
//! Arguments: a body, readings per voxel, then brain short forms (default: a list of every kind).

use std::time::Instant;
use vsrlab_body::Morphology;
use vsrlab_brain::BrainShape;
use vsrlab_brain::BrainSpec;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let body = args.first().map_or("biped-4x3", String::as_str);
    let per_voxel: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(4);
    let default = [
        "phase",
        "mlp",
        "distributed-mlp",
        "local-mlp",
        "local-mlp:1",
        "attention",
        "hebbian:dew",
        "hebbian",
        "hebbian:incoming",
        "hebbian:l2",
        "graph",
        "graph:37",
    ];
    let brains: Vec<&str> = if args.len() > 2 {
        args[2..].iter().map(String::as_str).collect()
    } else {
        default.to_vec()
    };
    let m = Morphology::parse(body).expect("a body");
    let rpv = vec![per_voxel; m.voxel_count()];
    // 64 reading vectors, cycled, so that branch predictors see varied input
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let readings: Vec<f64> = (0..64 * per_voxel * m.voxel_count())
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect();
    let n = per_voxel * m.voxel_count();
    println!("{body}, {per_voxel} readings per voxel ({n} in all)");
    println!("{:<20} {:>10} {:>12}", "brain", "parameters", "ns/step");
    for form in brains {
        let spec = BrainSpec::parse(form)
            .and_then(|s| s.with_random_parameters(1, &BrainShape::grid(&m, &rpv)))
            .unwrap_or_else(|e| panic!("{form}: {e}"));
        let mut brain = spec
            .build(&BrainShape::grid(&m, &rpv))
            .unwrap_or_else(|e| panic!("{form}: {e}"));
        let mut actuations = vec![0.0; m.voxel_count()];
        let steps = 200_000;
        for k in 0..1000 {
            brain.control(
                k as f64 / 60.0,
                &readings[(k % 64) * n..(k % 64 + 1) * n],
                &mut actuations,
            );
        }
        brain.reset();
        let start = Instant::now();
        for k in 0..steps {
            brain.control(
                k as f64 / 60.0,
                &readings[(k % 64) * n..(k % 64 + 1) * n],
                &mut actuations,
            );
        }
        let ns = start.elapsed().as_secs_f64() * 1e9 / steps as f64;
        std::hint::black_box(&actuations);
        println!("{form:<20} {:>10} {ns:>12.0}", spec.parameters().len());
    }
}
