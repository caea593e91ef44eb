use vsrlab_body::*;
use vsrlab_physics::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let shape = args.get(1).map(|s| s.as_str()).unwrap_or("box-1x1");
    let preset: Preset = args.get(2).map(|s| s.parse().unwrap()).unwrap_or_default();
    let substeps: u32 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(4);
    for f in ["0", "1", "-1", "sin"] {
        let mut s = WorldSettings::default();
        s.substeps = substeps;
        let mut b = WorldBuilder::new(s);
        b.add_static_polygon(Polygon::rect(Vec2::new(1000.0, -22.5), 1000.0, 27.5), 0.2, 0.0);
        let m = Morphology::parse(shape).unwrap();
        let vsr = Vsr::assemble(&mut b, &m, &VoxelParams::preset(preset), Vec2::new(11.0, 6.0), 1);
        let mut w = b.build().unwrap();
        let mut t = 0.0;
        let mut lo: f64 = 9.0;
        let mut hi: f64 = 0.0;
        let mut first_min_y = 0.0;
        let mut n = 0;
        while t < 5.0 {
            t += 1.0 / 60.0;
            w.step().unwrap();
            n += 1;
            if n == 1 {
                first_min_y = vsr.bounding_box(&w).0.y;
            }
            let a = match f {
                "sin" => (2.0 * std::f64::consts::PI * t).sin(),
                x => x.parse().unwrap(),
            };
            vsr.actuate(&mut w, &vec![a; vsr.voxel_count()]);
            let ar = (0..vsr.voxel_count())
                .map(|i| vsr.voxel_state(&w, i).area_ratio)
                .sum::<f64>()
                / vsr.voxel_count() as f64;
            if t > 3.0 {
                lo = lo.min(ar);
                hi = hi.max(ar);
            }
        }
        let ar = (0..vsr.voxel_count())
            .map(|i| vsr.voxel_state(&w, i).area_ratio)
            .sum::<f64>()
            / vsr.voxel_count() as f64;
        println!(
            "f={f:>4} steps={n} area={ar:.4} range=[{lo:.4},{hi:.4}] center_y={:.4} first_min_y={first_min_y:.4}",
            vsr.center(&w).y
        );
    }
}
