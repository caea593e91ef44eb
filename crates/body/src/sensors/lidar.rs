//! Lidar ray directions (vsr-model.md §3.1): rays on the side of the voxel that faces out of the
//! body, chosen from the voxel's relative position in the grid.

use std::f64::consts::FRAC_PI_4;

/// The side a lidar looks from, by relative grid position (x, y in [0, 1]).
pub fn side_span(x: f64, y: f64) -> (f64, f64) {
    if y > x && y > 1.0 - x {
        (FRAC_PI_4, 3.0 * FRAC_PI_4) // N
    } else if y >= x && y <= 1.0 - x {
        (3.0 * FRAC_PI_4, 5.0 * FRAC_PI_4) // W
    } else if y < x && y < 1.0 - x {
        (5.0 * FRAC_PI_4, 7.0 * FRAC_PI_4) // S
    } else {
        (-FRAC_PI_4, FRAC_PI_4) // E
    }
}

/// Ray directions relative to the voxel angle: `rays` evenly spaced over the side's span, both ends
/// included. Quirk kept from the original: a single ray points at half the span's width (π/4)
/// whatever the side, not at the side's centre.
pub fn ray_angles(x: f64, y: f64, rays: usize) -> Vec<f64> {
    let (start, end) = side_span(x, y);
    if rays == 1 {
        return vec![(end - start) / 2.0];
    }
    (0..rays).map(|i| start + (end - start) * i as f64 / (rays - 1) as f64).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_follow_position() {
        assert_eq!(side_span(1.0, 0.5).0, -FRAC_PI_4); // rightmost column looks east
        assert_eq!(side_span(0.5, 1.0).0, FRAC_PI_4); // top looks north
        assert_eq!(side_span(0.0, 0.5).0, 3.0 * FRAC_PI_4); // left looks west
        assert_eq!(side_span(0.5, 0.0).0, 5.0 * FRAC_PI_4); // bottom looks south
    }

    #[test]
    fn rays_span_the_side_and_one_ray_keeps_the_quirk() {
        let r = ray_angles(1.0, 0.5, 5);
        assert_eq!(r.len(), 5);
        assert!((r[0] + FRAC_PI_4).abs() < 1e-12 && (r[4] - FRAC_PI_4).abs() < 1e-12);
        assert_eq!(ray_angles(0.5, 0.0, 1), vec![FRAC_PI_4]);
    }
}
