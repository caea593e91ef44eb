//! The shape tasks of `change_shape.py` (base class `ShapeBase`): AreaMaximizer-v0
//! (`MaximizeShape`), AreaMinimizer-v0 (`MinimizeShape`), WingspanMazimizer-v0 (sic, EvoGym's
//! spelling; `MaximizeXShape`) and HeightMaximizer-v0 (`MaximizeYShape`): change the body's
//! shape in a pit, rewarded for the change of its convex hull's area or of its span.

use super::{Basics, Piece, TaskDefinition};
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds;

/// What a shape task measures of the robot's points.
#[derive(Clone, Copy)]
enum Shape {
    /// The convex hull's area, times `sign` in the reward (+10 to grow it, −10 to shrink it).
    Area(f64),
    /// The span along x.
    Width,
    /// The span along y.
    Height,
}

/// A shape task.
pub struct ShapeTask {
    basics: Basics,
    shape: Shape,
}

/// AreaMaximizer-v0: grow the hull's area.
pub const AREA_MAXIMIZER: ShapeTask = ShapeTask {
    basics: Basics {
        name: "AreaMaximizer-v0",
        short_name: "area-maximizer",
        world: shape_change,
        robot_origin: (7, 1),
        episode_steps: 600,
    },
    shape: Shape::Area(10.0),
};

/// AreaMinimizer-v0: shrink the hull's area.
pub const AREA_MINIMIZER: ShapeTask = ShapeTask {
    basics: Basics {
        name: "AreaMinimizer-v0",
        short_name: "area-minimizer",
        world: shape_change,
        robot_origin: (7, 1),
        episode_steps: 600,
    },
    shape: Shape::Area(-10.0),
};

/// WingspanMazimizer-v0 (EvoGym's spelling): grow the span along x.
pub const WINGSPAN_MAXIMIZER: ShapeTask = ShapeTask {
    basics: Basics {
        name: "WingspanMazimizer-v0",
        short_name: "wingspan-maximizer",
        world: shape_change,
        robot_origin: (7, 1),
        episode_steps: 600,
    },
    shape: Shape::Width,
};

/// HeightMaximizer-v0: grow the span along y.
pub const HEIGHT_MAXIMIZER: ShapeTask = ShapeTask {
    basics: Basics {
        name: "HeightMaximizer-v0",
        short_name: "height-maximizer",
        world: shape_change,
        robot_origin: (7, 1),
        episode_steps: 500,
    },
    shape: Shape::Height,
};

impl TaskDefinition for ShapeTask {
    fn basics(&self) -> &Basics {
        &self.basics
    }

    /// The relative positions only.
    fn observation(&self) -> &'static [Piece] {
        &[Piece::RobotPositions]
    }

    fn measure(&self, xs: &[f64], ys: &[f64]) -> f64 {
        match self.shape {
            Shape::Area(_) => hull_area(xs, ys),
            Shape::Width => span(xs),
            Shape::Height => span(ys),
        }
    }

    /// The change of the measure (the area's times ±10); no goal.
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = match self.shape {
            Shape::Area(sign) if sign > 0.0 => (after.own - before.own) * sign,
            Shape::Area(sign) => (before.own - after.own) * -sign,
            Shape::Width | Shape::Height => after.own - before.own,
        };
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        Reward { value, ends: false }
    }
}

/// `max − min` of `values` (numpy's `max` and `min`).
fn span(values: &[f64]) -> f64 {
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let min = values.iter().copied().fold(f64::INFINITY, f64::min);
    max - min
}

/// The area of the convex hull of the points, as `ShapeBase` finds it (`change_shape.py:46-83`):
/// a gift-wrapping march from the first point of least x, each next point the last in index
/// order that no other point lies clockwise of, until the start comes back; then the shoelace
/// sum over the hull in that order, halved. Counter-clockwise, so positive. Allocates nothing; a
/// march that does not close within the point count (non-finite points) gives NaN.
pub fn hull_area(xs: &[f64], ys: &[f64]) -> f64 {
    let n = xs.len();
    if n == 0 {
        return f64::NAN;
    }
    let least = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let Some(start) = xs.iter().position(|&x| x == least) else {
        return f64::NAN;
    };
    // `(p3.y − p1.y)(p2.x − p1.x) >= (p2.y − p1.y)(p3.x − p1.x)`: p1 → p2 → p3 turns
    // counter-clockwise (or is straight)
    let ccw = |p1: usize, p2: usize, p3: usize| {
        (ys[p3] - ys[p1]) * (xs[p2] - xs[p1]) >= (ys[p2] - ys[p1]) * (xs[p3] - xs[p1])
    };
    let same = |a: usize, b: usize| xs[a] == xs[b] && ys[a] == ys[b];
    let (mut area, mut on_hull) = (0.0, start);
    for _ in 0..n {
        let mut end = 0;
        for j in 1..n {
            if same(end, on_hull) || !ccw(j, on_hull, end) {
                end = j;
            }
        }
        area += xs[on_hull] * ys[end] - xs[end] * ys[on_hull];
        on_hull = end;
        if same(end, start) {
            return 0.5 * area;
        }
    }
    f64::NAN
}

/// The shape tasks' world (`ShapeChange.json`, 20 × 10): `new_object_4`, a floor with walls two
/// cells thick at each end.
fn shape_change() -> worlds::World {
    worlds::laid_out("new_object_4", &[(0, 0, "0-19"), (1, 9, "0-1, 18-19")])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit square with a point inside and one on its bottom edge: area 1; listed backwards,
    /// EvoGym's march takes the edge point and then cuts a corner, so its area is 0.75 (both
    /// measured with `ShapeBase.jarvis_march` and `convex_poly_area` of EvoGym 2.0).
    #[test]
    fn the_hull_of_a_square_with_inner_points_is_evogyms() {
        let xs = [0.5, 1.0, 0.0, 1.0, 0.0, 0.5];
        let ys = [0.5, 1.0, 1.0, 0.0, 0.0, 0.0];
        assert_eq!(hull_area(&xs, &ys), 1.0);
        let (rx, ry): (Vec<f64>, Vec<f64>) = xs.iter().rev().zip(ys.iter().rev()).unzip();
        assert_eq!(hull_area(&rx, &ry), 0.75);
        assert!(hull_area(&[0.0, f64::NAN], &[0.0, 1.0]).is_nan());
        assert_eq!(span(&[0.25, -1.0, 3.0]), 4.0);
    }
}
