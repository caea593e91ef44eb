//! Time of CMA-ES's own work per generation (ask + tell, sphere fitness) at the ch. 6 escape
//! study's size, split into generations with and without an eigendecomposition.
//!
//! ```text
//! cargo run --release -p vsrlab-evolution --example cma_timing -- [n] [lambda] [generations] [updatecovwait]
//! ```

use std::time::Instant;
use vsrlab_evolution::test_functions::sphere;
use vsrlab_evolution::{CmaEs, CmaEsConfig, CmaSettings, Evaluation, Optimizer, Sense, Tell, Told};

fn main() {
    let args: Vec<f64> = std::env::args().skip(1).filter_map(|s| s.parse().ok()).collect();
    let n = args.first().map_or(784, |v| *v as usize);
    let lambda = args.get(1).map_or(24, |v| *v as usize);
    let generations = args.get(2).map_or(84, |v| *v as usize);
    let config = CmaEsConfig {
        sense: Sense::Minimize,
        settings: CmaSettings {
            population_size: Some(lambda),
            updatecovwait: args.get(3).copied(),
            ..CmaSettings::default()
        },
        ..CmaEsConfig::default()
    };
    let mut cma = CmaEs::new(config, n, 1).expect("valid settings");
    let mut times = Vec::with_capacity(generations);
    for _ in 0..generations {
        let start = Instant::now();
        let batch = cma.ask();
        let told: Vec<Told<()>> = batch
            .iter()
            .map(|c| Told {
                id: c.id,
                evaluation: Evaluation::single(sphere(&c.genotype)),
            })
            .collect();
        cma.tell(told).expect("a whole batch");
        times.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let mut sorted = times.clone();
    sorted.sort_by(f64::total_cmp);
    let total: f64 = times.iter().sum();
    println!(
        "n {n}, λ {lambda}, {generations} generations: {total:.0} ms in all, median {:.2} ms, slowest {:.0} ms",
        sorted[generations / 2],
        sorted[generations - 1]
    );
}
