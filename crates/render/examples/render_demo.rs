//! Renders a synthetic 30 s episode (a 5×2 robot wobbling over hills) and reports timings.
//!
//! `cargo run --release -p vsrlab-render --example render_demo -- OUT.gif [OUT2.png ...]`

use std::f64::consts::PI;
use std::time::Instant;
use vsrlab_physics::Vec2;
use vsrlab_render::{save_video, RenderOptions};
use vsrlab_tasks::channels::{ACTUATION, ANGLE, AREA_RATIO, CELLS, LIDAR, RAYS, READINGS, READINGS_PER_UNIT, TOUCH};
use vsrlab_tasks::Probe;
use vsrlab_tasks::Trace;

fn terrain() -> Vec<Vec2> {
    let mut pts = vec![Vec2::new(0.0, 100.0), Vec2::new(10.0, 5.0)];
    let mut x = 10.0;
    while x < 1990.0 {
        x += 4.0;
        pts.push(Vec2::new(x, 5.0 + 1.5 * (x * 0.07).sin() + 0.8 * (x * 0.23).cos()));
    }
    pts.push(Vec2::new(2000.0, 100.0));
    pts
}

fn height_at(t: &[Vec2], x: f64) -> f64 {
    let i = t.partition_point(|p| p.x < x).clamp(1, t.len() - 1);
    let (a, b) = (t[i - 1], t[i]);
    a.y + (b.y - a.y) * ((x - a.x) / (b.x - a.x)).clamp(0.0, 1.0)
}

/// Distance along the ray from `o` in direction `d` (unit) to the terrain, if within `range`.
fn cast(t: &[Vec2], o: Vec2, d: Vec2, range: f64) -> f64 {
    let mut best = range;
    for w in t.windows(2) {
        let (a, b) = (w[0], w[1]);
        let e = b - a;
        let den = d.cross(e);
        if den.abs() < 1e-12 {
            continue;
        }
        let s = (a - o).cross(e) / den;
        let u = (a - o).cross(d) / den;
        if s >= 0.0 && (0.0..=1.0).contains(&u) {
            best = best.min(s);
        }
    }
    best
}

fn synthetic(seconds: f64) -> Trace {
    let dt = 1.0 / 60.0;
    let side = 3.0;
    let terrain = terrain();
    let env = |k: &str, d: usize| std::env::var(k).ok().and_then(|v| v.parse().ok()).unwrap_or(d);
    let (w, h) = (env("DEMO_W", 5), env("DEMO_H", 2));
    let cells: Vec<(usize, usize)> = (0..h).flat_map(|j| (0..w).map(move |i| (i, j))).collect();
    let readings_per_voxel: Vec<usize> = cells.iter().map(|&(_, j)| if j + 1 == h { 3 } else { 2 }).collect();
    // (voxel, direction relative to the voxel, range)
    let rays: Vec<(usize, f64, f64)> = [-PI / 3.0, -PI / 6.0, 0.0, PI / 6.0]
        .iter()
        .map(|&a| (w * h - 1, a, 15.0))
        .collect();
    let mut tr = Trace {
        dt,
        side_length: side,
        terrain: terrain.clone(),
        outline_corners: vec![4; cells.len()],
        ..Trace::default()
    };
    let flat: Vec<f64> = cells.iter().flat_map(|&(i, j)| [i as f64, j as f64]).collect();
    tr.fixed(&CELLS, 2, &flat);
    let counts: Vec<f64> = readings_per_voxel.iter().map(|&n| n as f64).collect();
    tr.fixed(&READINGS_PER_UNIT, 1, &counts);
    let flat: Vec<f64> = rays.iter().flat_map(|&(v, a, r)| [v as f64, a, r]).collect();
    tr.fixed(&RAYS, 3, &flat);
    let steps = (seconds / dt).round() as usize;
    for k in 0..steps {
        let t = k as f64 * dt;
        let x0 = 20.0 + 1.2 * t + 0.4 * (2.0 * PI * t).sin();
        let theta = 0.12 * (1.3 * t).sin();
        let ground = (0..=15)
            .map(|q| height_at(&terrain, x0 + q as f64))
            .fold(f64::MIN, f64::max);
        let origin = Vec2::new(x0, ground + 0.4 + 0.3 * (2.0 * PI * t).cos().max(0.0));
        let rot = |p: Vec2| {
            Vec2::new(
                p.x * theta.cos() - p.y * theta.sin(),
                p.x * theta.sin() + p.y * theta.cos(),
            )
        };
        tr.times.push(t);
        let mut center = Vec2::ZERO;
        let (mut area, mut touch, mut readings) = (Vec::new(), Vec::new(), Vec::new());
        for (v, &(i, j)) in cells.iter().enumerate() {
            let s = 1.0 + 0.15 * (2.0 * PI * t - i as f64 * 0.9 + j as f64).sin();
            let c = Vec2::new((i as f64 + 0.5) * side, (h as f64 - 0.5 - j as f64) * side);
            let half = side * s / 2.0;
            let corners = [
                Vec2::new(-half, half),
                Vec2::new(half, half),
                Vec2::new(half, -half),
                Vec2::new(-half, -half),
            ];
            let poly = corners.map(|q| origin + rot(c + q));
            tr.outlines.extend_from_slice(&poly);
            area.push(s * s);
            touch.push(f64::from(u8::from(
                j + 1 == h && poly[3].y - height_at(&terrain, poly[3].x) < 0.5,
            )));
            center = center + origin + rot(c);
            for r in 0..readings_per_voxel[v] {
                readings.push(0.5 + 0.5 * (3.0 * t + v as f64 + r as f64 * 2.0).sin());
            }
        }
        tr.step(&AREA_RATIO, &area);
        tr.step(&ANGLE, &vec![theta; cells.len()]);
        tr.step(&TOUCH, &touch);
        tr.step(&ACTUATION, &vec![0.0; cells.len()]);
        tr.step(&READINGS, &readings);
        tr.centers.push(center * (1.0 / cells.len() as f64));
        let polys = &tr.outlines[k * 4 * cells.len()..];
        let distances: Vec<f64> = rays
            .iter()
            .map(|&(voxel, relative_angle, range)| {
                let p = &polys[4 * voxel..4 * voxel + 4];
                let c = (p[0] + p[1] + p[2] + p[3]) * 0.25;
                let a = theta + relative_angle;
                cast(&terrain, c, Vec2::new(a.cos(), a.sin()), range)
            })
            .collect();
        tr.step(&LIDAR, &distances);
    }
    tr
}

fn main() {
    let trace = synthetic(30.0);
    let plain = std::env::var_os("DEMO_PLAIN").is_some();
    let opts = RenderOptions {
        draw_sensors: !plain,
        draw_lidar: !plain,
        ..RenderOptions::default()
    };
    for out in std::env::args().skip(1) {
        let start = Instant::now();
        match save_video(&trace, &opts, &out) {
            Ok(info) => println!(
                "{out}: {} frames {}x{} in {:.2} s, {:.2} MB",
                info.frames,
                info.width,
                info.height,
                start.elapsed().as_secs_f64(),
                info.bytes as f64 / 1e6
            ),
            Err(e) => println!("{out}: error: {e}"),
        }
    }
}
