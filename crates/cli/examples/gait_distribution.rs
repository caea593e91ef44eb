//! Phase-gait velocities as distributions over slightly perturbed starts (vsr-model.md §9 says the
//! original's single runs can only be compared this way). Usage: gait_distribution [N]
use rayon::prelude::*;
use vsrlab_body::sensors::SensorConfig;
use vsrlab_body::{Morphology, Preset};
use vsrlab_brain::BrainSpec;
use vsrlab_tasks::{episode, Locomotion, RobotSpec, TraceLevel};

fn main() {
    let n: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(50);
    let cases = [
        ("biped-4x3", Preset::Y2021, 0.1339),
        ("worm-10x4", Preset::Y2021, 0.0493),
        ("biped-4x3", Preset::Y2022, 0.6709),
        ("worm-10x4", Preset::Y2022, 0.7035),
    ];
    println!("| robot | preset | original (one run) | vsrlab median | IQR | min | max | n |");
    println!("|---|---|---|---|---|---|---|---|");
    for (body, preset, original) in cases {
        let robot = RobotSpec {
            body: Morphology::parse(body).unwrap(),
            preset,
            voxel: None,
            sensors: SensorConfig::parse("uniform-a+vxy+t-0").unwrap(),
            brain: BrainSpec::default(),
        };
        let mut v: Vec<f64> = (0..n)
            .into_par_iter()
            .map(|k| {
                let task = Locomotion {
                    initial_x: 11.0 + k as f64 * 1e-6,
                    ..Default::default()
                };
                episode::run(&robot, &task, 0, TraceLevel::None)
                    .unwrap()
                    .metric("velocity")
            })
            .collect();
        v.sort_by(f64::total_cmp);
        let q = |p: f64| v[((v.len() - 1) as f64 * p).round() as usize];
        println!(
            "| {body} | {preset} | {original:.4} | {:.4} | [{:.4}, {:.4}] | {:.4} | {:.4} | {n} |",
            q(0.5),
            q(0.25),
            q(0.75),
            v[0],
            v[v.len() - 1]
        );
    }
}
