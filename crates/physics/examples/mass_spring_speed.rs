//! Time of one environment step (30 substeps) of the mass-spring engine on EvoGym's Walker
//! scene: a 5 × 5 block of square cells (36 points, sides and diagonals) standing on a fixed
//! 100 × 1 strip of terrain cells above the ground plane, cells cycling through the four kinds
//! EvoGym has (rigid, soft, horizontal and vertical actuator), actuators driven by sines.
//!
//! Run with `cargo run --release -p vsrlab-physics --example mass_spring_speed`.

use std::time::Instant;
use vsrlab_physics::mass_spring::{
    BodyDesc, MassSpringBuilder, MassSpringSettings, PointDesc, QuadDesc, SpringDesc, SpringId,
};

const CELL: f64 = 0.1;
const RIGID: f64 = 3e8 / 3.5;
const ACTUATOR: f64 = 3e8 / 5.0;
const SOFT: f64 = 3e8 / 6.0;

/// Cell kinds of the example block.
#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Rigid,
    Soft,
    Horizontal,
    Vertical,
}

impl Kind {
    /// Side and diagonal stiffness.
    fn stiffness(self) -> (f64, f64) {
        match self {
            Kind::Rigid => (RIGID, RIGID / 2.0),
            Kind::Soft => (SOFT, SOFT / 4.0),
            _ => (ACTUATOR, ACTUATOR / 2.0),
        }
    }
}

/// Adds a `w × h` grid of cells with lower-left corner at `(x0, y0)`; returns each cell's sides
/// (bottom, right, top, left).
fn add_grid(
    b: &mut MassSpringBuilder,
    (x0, y0): (f64, f64),
    (w, h): (usize, usize),
    kind: impl Fn(usize, usize) -> Kind,
    fixed: bool,
) -> Vec<[SpringId; 4]> {
    let body = b.add_body(if fixed {
        BodyDesc::new()
    } else {
        BodyDesc::new().watch_self_overlap()
    });
    let points: Vec<_> = (0..=h)
        .flat_map(|j| (0..=w).map(move |i| (i, j)))
        .map(|(i, j)| {
            let p = PointDesc::at(x0 + i as f64 * CELL, y0 + j as f64 * CELL);
            b.add_point(if fixed { p.fixed() } else { p })
        })
        .collect();
    let at = |i: usize, j: usize| points[j * (w + 1) + i];
    let side = |b: &mut MassSpringBuilder, p, q| b.add_spring(SpringDesc::between(p, q, RIGID));
    let horizontal: Vec<_> = (0..=h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| side(b, at(i, j), at(i + 1, j)))
        .collect();
    let vertical: Vec<_> = (0..h)
        .flat_map(|j| (0..=w).map(move |i| (i, j)))
        .map(|(i, j)| side(b, at(i, j), at(i, j + 1)))
        .collect();
    let mut cells = Vec::new();
    for j in 0..h {
        for i in 0..w {
            let sides = [
                horizontal[j * w + i],
                vertical[j * (w + 1) + i + 1],
                horizontal[(j + 1) * w + i],
                vertical[j * (w + 1) + i],
            ];
            let (side_k, diag_k) = kind(i, j).stiffness();
            // Like EvoGym, the cell visited last sets a shared side's stiffness.
            for s in sides {
                b.set_stiffness(s, side_k);
            }
            b.add_spring(SpringDesc::between(at(i, j), at(i + 1, j + 1), diag_k));
            b.add_spring(SpringDesc::between(at(i + 1, j), at(i, j + 1), diag_k));
            if kind(i, j) == Kind::Rigid {
                sides.iter().for_each(|&s| b.limit_length(s, 0.03));
            }
            let outline = [j == 0, i == w - 1, j == h - 1, i == 0];
            b.add_quad(QuadDesc::new(body, [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)]).boundary(outline));
            cells.push(sides);
        }
    }
    cells
}

fn main() {
    let mut b = MassSpringBuilder::new(MassSpringSettings::evogym());
    add_grid(&mut b, (0.0, 0.0), (100, 1), |_, _| Kind::Rigid, true);
    let kinds = [Kind::Rigid, Kind::Soft, Kind::Horizontal, Kind::Vertical];
    let kind = |i: usize, j: usize| kinds[(i + 2 * j) % 4];
    let cells = add_grid(&mut b, (CELL, CELL), (5, 5), kind, false);
    let mut phases = Vec::new();
    for (c, sides) in cells.iter().enumerate() {
        match kind(c % 5, c / 5) {
            Kind::Horizontal => b.add_actuator(&[sides[0], sides[2]]),
            Kind::Vertical => b.add_actuator(&[sides[1], sides[3]]),
            _ => continue,
        };
        phases.push(c as f64 * 0.7);
    }
    let mut world = b.build().expect("valid scene");
    let mut targets = vec![1.0; phases.len()];
    let steps = 3000;
    let start = Instant::now();
    for t in 0..steps {
        for (target, phase) in targets.iter_mut().zip(&phases) {
            *target = 1.1 + 0.5 * (t as f64 * 0.1 + phase).sin();
        }
        if let Err(e) = world.step(&targets) {
            println!("stopped at step {t}: {e}");
            break;
        }
    }
    let micros = start.elapsed().as_secs_f64() * 1e6 / steps as f64;
    let robot = 202..world.point_count();
    let x: f64 = world.positions_x()[robot.clone()].iter().sum::<f64>() / robot.len() as f64;
    println!(
        "{} points ({} moving), {} springs, {} actuators: {micros:.1} µs per step of 30 substeps (centre moved to x = {x:.3})",
        world.point_count(),
        robot.len(),
        world.spring_count(),
        world.actuator_count()
    );
}
