use std::time::Instant;
use vsrlab_body::*;
use vsrlab_physics::*;
fn main() {
    let substeps: u32 = std::env::args().nth(1).map(|s| s.parse().unwrap()).unwrap_or(4);
    for shape in ["biped-4x3", "worm-10x4", "box-10x10"] {
        for preset in [Preset::Y2021, Preset::Y2022] {
            let mut s = WorldSettings::default();
            s.substeps = substeps;
            let mut b = WorldBuilder::new(s);
            b.add_static_polygon(Polygon::rect(Vec2::new(1000.0, -22.5), 1000.0, 27.5), 0.2, 0.0);
            let m = Morphology::parse(shape).unwrap();
            let vsr = Vsr::assemble(&mut b, &m, &VoxelParams::preset(preset), Vec2::new(11.0, 6.0), 1);
            let mut w = b.build().unwrap();
            let phases: Vec<f64> = vsr
                .voxels()
                .iter()
                .map(|v| std::f64::consts::PI * v.cell.0 as f64 / m.width() as f64)
                .collect();
            let mut vals = vec![0.0; vsr.voxel_count()];
            let start = Instant::now();
            let mut t = 0.0;
            let n = 1801 * 3;
            for _ in 0..n {
                t += 1.0 / 60.0;
                w.step().unwrap();
                for (v, p) in vals.iter_mut().zip(&phases) {
                    *v = (2.0 * std::f64::consts::PI * t + p).sin();
                }
                vsr.actuate(&mut w, &vals);
            }
            let el = start.elapsed().as_secs_f64();
            println!(
                "{shape} {preset}: {:.0} steps/s, x={:.2} contacts={}",
                n as f64 / el,
                vsr.center(&w).x,
                w.contact_count()
            );
        }
    }
}
