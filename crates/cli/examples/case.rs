// Debug helper: replays one robustness case and reports when the smallest area ratio occurs.
use vsrlab_body::sensors::SensorConfig;
use vsrlab_body::{Morphology, Preset};
use vsrlab_brain::BrainSpec;
use vsrlab_tasks::*;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let body = Morphology::parse(&a[1]).unwrap();
    let preset: Preset = a[2].parse().unwrap();
    let terrain: Terrain = a[3].parse().unwrap();
    let brain: BrainSpec = serde_json::from_str(&a[4]).unwrap();
    let substeps: u32 = a.get(5).map(|s| s.parse().unwrap()).unwrap_or(4);
    let seed: u64 = a.get(6).map(|s| s.parse().unwrap()).unwrap_or(0);
    let r = RobotSpec {
        body,
        preset,
        voxel: None,
        sensors: SensorConfig::parse("uniform-a+vxy+t-0").unwrap(),
        brain,
    };
    let mut t = Locomotion {
        terrain,
        duration: 30.0,
        ..Default::default()
    };
    t.physics.substeps = substeps;
    if let Ok(v) = std::env::var("PUSH") {
        t.physics.contact_push_max = v.parse().unwrap();
    }
    if let Ok(v) = std::env::var("HZ") {
        t.physics.contact_hertz = v.parse().unwrap();
    }
    if let Ok(v) = std::env::var("ZETA") {
        t.physics.contact_damping_ratio = v.parse().unwrap();
    }
    let o = locomotion::run(&r, &t, seed, TraceLevel::Full).unwrap();
    let tr = o.trace.unwrap();
    let n = tr.voxels();
    let mut worst = (f64::INFINITY, 0, 0);
    for k in 0..tr.len() {
        for v in 0..n {
            let a = tr.area_ratios[k * n + v];
            if a < worst.0 {
                worst = (a, k, v);
            }
        }
    }
    let hi = tr.area_ratios.iter().cloned().fold(0.0, f64::max);
    println!(
        "min area {:.3} at step {} voxel {} (t={:.2}); max {:.3}; velocity {:.3}",
        worst.0, worst.1, worst.2, tr.times[worst.1], hi, o.velocity
    );
    for sec in 0..30 {
        let ks: Vec<usize> = (0..tr.len())
            .filter(|&k| tr.times[k] >= sec as f64 && tr.times[k] < sec as f64 + 1.0)
            .collect();
        let m = ks
            .iter()
            .flat_map(|&k| tr.area_ratios[k * n..(k + 1) * n].iter().cloned())
            .fold(9.0, f64::min);
        let c = tr.centers[ks[0]];
        print!("{sec}:{m:.2}@({:.0},{:.0}) ", c.x, c.y);
    }
    println!();
    if let Some(p) = a.get(7) {
        vsrlab_render::save_png(&tr, worst.1, &Default::default(), p).unwrap();
    }
}
