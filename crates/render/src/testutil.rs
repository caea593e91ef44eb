//! Synthetic traces for the tests: one 3×3 voxel above flat ground at y = 5.

use vsrlab_physics::Vec2;
use vsrlab_tasks::Probe;
use vsrlab_tasks::{channels, Trace};

/// Flat terrain at y = 5 between two walls far from the robot.
pub fn flat_terrain() -> Vec<Vec2> {
    vec![
        Vec2::new(-1000.0, 100.0),
        Vec2::new(-990.0, 5.0),
        Vec2::new(1990.0, 5.0),
        Vec2::new(2000.0, 100.0),
    ]
}

/// The outer polygon (NW, NE, SE, SW) of a 3×3 voxel whose bottom-left corner is at (x, 5).
pub fn square_at(x: f64) -> [Vec2; 4] {
    [
        Vec2::new(x, 8.0),
        Vec2::new(x + 3.0, 8.0),
        Vec2::new(x + 3.0, 5.0),
        Vec2::new(x, 5.0),
    ]
}

/// One voxel whose left edge is at `xs[k]` at step k (60 Hz), area ratio 1, no sensors.
pub fn trace_from_positions(xs: &[f64]) -> Trace {
    let dt = 1.0 / 60.0;
    let mut trace = Trace {
        dt,
        side_length: 3.0,
        terrain: flat_terrain(),
        times: (0..xs.len()).map(|k| k as f64 * dt).collect(),
        centers: xs.iter().map(|&x| Vec2::new(x + 1.5, 6.5)).collect(),
        outline_corners: vec![4],
        outlines: xs.iter().flat_map(|&x| square_at(x)).collect(),
        ..Trace::default()
    };
    trace.fixed(&channels::CELLS, 2, &[0.0, 0.0]);
    trace.fixed(&channels::READINGS_PER_UNIT, 1, &[0.0]);
    for _ in xs {
        trace.step(&channels::AREA_RATIO, &[1.0]);
        trace.step(&channels::ANGLE, &[0.0]);
        trace.step(&channels::TOUCH, &[0.0]);
        trace.step(&channels::ACTUATION, &[0.0]);
    }
    trace
}

/// A single step: the voxel at x ∈ [10, 13], y ∈ [5, 8], with the given area ratio.
pub fn square_trace(area_ratio: f64) -> Trace {
    let mut t = trace_from_positions(&[10.0]);
    t.values_mut("area_ratio")[0] = area_ratio;
    t
}

/// `steps` steps at 60 Hz of the voxel moving right from x = 10 at `speed` units per second.
pub fn moving_square(steps: usize, speed: f64) -> Trace {
    let xs: Vec<f64> = (0..steps).map(|k| 10.0 + speed * k as f64 / 60.0).collect();
    trace_from_positions(&xs)
}
