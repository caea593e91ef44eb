//! Fixtures shared by the unit tests.

use vsrlab_physics::Vec2;

/// The outline (NW, NE, SE, SW) of the square of side `s` whose bottom-left corner is at (x, y).
pub(crate) fn square(x: f64, y: f64, s: f64) -> [Vec2; 4] {
    [
        Vec2::new(x, y + s),
        Vec2::new(x + s, y + s),
        Vec2::new(x + s, y),
        Vec2::new(x, y),
    ]
}
