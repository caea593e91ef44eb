//! Lidar (vsr-model.md §3.1): distances from the voxel centre to static geometry (ground,
//! obstacles) along a fan of rays on one side of the voxel.
//!
//! The side is chosen once, from the voxel's relative grid position (x, y in [0, 1]): north if
//! y > x and y > 1 − x; west if x ≤ y ≤ 1 − x; south if y < x and y < 1 − x; east otherwise. Each
//! side spans a quarter turn (E [−π/4, π/4], N [π/4, 3π/4], W [3π/4, 5π/4], S [5π/4, 7π/4]). How
//! n ≥ 2 rays spread over it depends on the simulator version ([`RayLayout`], vsr-model.md §9.1):
//! 2D-VSR-Sim HEAD (preset 2022) includes both ends (5 rays on E: −π/4, −π/8, 0, π/8, π/4);
//! v1.10.0 (preset 2021) points each ray at the centre of one of n equal bins (−π/5, −π/10, 0,
//! π/10, π/5). Directions are relative to the voxel's angle, so the fan turns with the voxel.
//!
//! **Quirk kept from the original:** a lidar with a single ray points at half the side's angular
//! width, π/4 relative to the voxel, whatever the side, and not at the side's centre. So `l1` on a
//! bottom voxel looks up-right, not down. It is kept because published robots were evolved with it.
//!
//! Only static geometry is hit (the original skipped robot fixtures; here other robots are
//! dynamic parts and are not seen either). A ray that hits nothing within its range reads the range.

use super::kind::{check_positive, SensorKind};
use super::node::{Frame, Node, Site};
use serde::{Deserialize, Serialize};
use std::f64::consts::FRAC_PI_4;
use vsrlab_field::FieldError;
use vsrlab_physics::Vec2;

/// Most rays one lidar may cast.
pub const MAX_RAYS: usize = 1024;

/// Declared domain of each ray: [0, range].
pub(crate) fn domain(range: f64) -> (f64, f64) {
    (0.0, range)
}

/// The side of a voxel a lidar looks from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    North,
    East,
    South,
    West,
}

impl Side {
    /// The side for a voxel at relative grid position (x, y), each in [0, 1].
    pub(crate) fn of(x: f64, y: f64) -> Side {
        if y > x && y > 1.0 - x {
            Side::North
        } else if y >= x && y <= 1.0 - x {
            Side::West
        } else if y < x && y < 1.0 - x {
            Side::South
        } else {
            Side::East
        }
    }

    /// First and last direction of the side's quarter turn (radians, relative to the voxel).
    pub(crate) fn span(self) -> (f64, f64) {
        let start = match self {
            Side::East => -1.0,
            Side::North => 1.0,
            Side::West => 3.0,
            Side::South => 5.0,
        } * FRAC_PI_4;
        (start, start + 2.0 * FRAC_PI_4)
    }

    /// Directions of `rays` rays on this side (relative to the voxel), with the one-ray quirk.
    pub(crate) fn ray_directions(self, rays: usize, layout: RayLayout) -> Vec<f64> {
        let (start, end) = self.span();
        if rays == 1 {
            return vec![(end - start) / 2.0];
        }
        match layout {
            RayLayout::Ends => {
                let step = (end - start) / (rays - 1) as f64;
                (0..rays).map(|i| start + step * i as f64).collect()
            }
            RayLayout::Bins => {
                let step = (end - start) / rays as f64;
                (0..rays).map(|i| start + step * (i as f64 + 0.5)).collect()
            }
        }
    }
}

/// How n ≥ 2 lidar rays spread over their side's quarter turn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RayLayout {
    /// Evenly, both ends included (2D-VSR-Sim HEAD, preset 2022).
    #[default]
    Ends,
    /// At the centres of n equal bins (2D-VSR-Sim v1.10.0, preset 2021).
    Bins,
}

impl RayLayout {
    fn is_ends(&self) -> bool {
        *self == RayLayout::Ends
    }
}

/// A fan of rays cast against static geometry.
#[derive(Debug, Clone)]
pub(crate) struct Lidar {
    range: f64,
    /// Ray directions relative to the voxel angle.
    directions: Vec<f64>,
    /// Distances measured at the last reading (the range before the first).
    last: Vec<f64>,
}

impl Lidar {
    /// A lidar of `rays` rays of length `range` for a voxel at relative grid position `rel`.
    pub(crate) fn new(range: f64, rays: usize, rel: (f64, f64), layout: RayLayout) -> Lidar {
        Lidar {
            range,
            directions: Side::of(rel.0, rel.1).ray_directions(rays, layout),
            last: vec![range; rays],
        }
    }

    /// Casts every ray from the voxel centre and writes the distances.
    pub(crate) fn sense(&mut self, frame: &Frame, out: &mut [f64]) {
        let s = frame.state;
        for ((direction, last), o) in self.directions.iter().zip(&mut self.last).zip(out) {
            let (sin, cos) = (s.angle + direction).sin_cos();
            let hit = frame.world.ray_cast_static(s.center, Vec2::new(cos, sin), self.range);
            *last = hit.unwrap_or(self.range).min(self.range);
            *o = *last;
        }
    }

    /// Forgets the last distances.
    pub(crate) fn reset(&mut self) {
        self.last.fill(self.range);
    }

    /// Maximum distance.
    pub(crate) fn range(&self) -> f64 {
        self.range
    }

    /// Ray directions relative to the voxel angle.
    pub(crate) fn directions(&self) -> &[f64] {
        &self.directions
    }

    /// Distances measured at the last reading.
    pub(crate) fn last_distances(&self) -> &[f64] {
        &self.last
    }
}

/// Description of a lidar (`{"kind": "lidar", "range": 10.0, "rays": 5}`, optionally
/// `"layout": "bins"`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LidarSpec {
    /// Ray length (> 0); a ray that hits nothing reads this.
    pub range: f64,
    /// Number of rays (1 to [`MAX_RAYS`]).
    pub rays: usize,
    /// How the rays spread over the side (default: both ends included).
    #[serde(default, skip_serializing_if = "RayLayout::is_ends")]
    pub layout: RayLayout,
}

impl SensorKind for LidarSpec {
    fn dimension(&self) -> usize {
        self.rays
    }

    fn domains(&self) -> Vec<(f64, f64)> {
        vec![domain(self.range); self.rays]
    }

    fn validate(&self, _noisy_depth: usize) -> Result<(), FieldError> {
        check_positive("range", "lidar range", self.range)?;
        if (1..=MAX_RAYS).contains(&self.rays) {
            Ok(())
        } else {
            Err(FieldError::new(
                "rays",
                format!("lidar rays must be 1 to {MAX_RAYS}, got {}", self.rays),
            ))
        }
    }

    fn build(&self, site: Site) -> Node {
        Node::Lidar(Lidar::new(self.range, self.rays, site.rel, self.layout))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{frame, still_state};
    use std::f64::consts::{FRAC_PI_2, SQRT_2};
    use vsrlab_physics::{Polygon, WorldBuilder, WorldSettings};

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 1e-9
    }

    #[test]
    fn the_side_follows_the_grid_position() {
        assert_eq!(Side::of(1.0, 0.5), Side::East);
        assert_eq!(Side::of(0.5, 1.0), Side::North);
        assert_eq!(Side::of(0.0, 0.5), Side::West);
        assert_eq!(Side::of(0.5, 0.0), Side::South);
        // the centre of a grid (and a 1×1 body) looks west; the corners break ties as documented
        assert_eq!(Side::of(0.5, 0.5), Side::West);
        assert_eq!(Side::of(0.0, 0.0), Side::West);
        assert_eq!(Side::of(1.0, 1.0), Side::East);
        assert_eq!(Side::of(0.0, 1.0), Side::West);
        assert_eq!(Side::of(1.0, 0.0), Side::East);
    }

    #[test]
    fn rays_cover_the_side_with_both_ends() {
        let r = Side::East.ray_directions(5, RayLayout::Ends);
        assert_eq!(r.len(), 5);
        assert!(
            close(r[0], -FRAC_PI_4) && close(r[2], 0.0) && close(r[4], FRAC_PI_4),
            "{r:?}"
        );
        let s = Side::South.ray_directions(3, RayLayout::Ends);
        assert!(close(s[0], 5.0 * FRAC_PI_4) && close(s[1], 3.0 * FRAC_PI_2) && close(s[2], 7.0 * FRAC_PI_4));
    }

    /// v1.10.0's five rays on the east side (vsr-model.md §9.1): −π/5, −π/10, 0, π/10, π/5.
    #[test]
    fn binned_rays_point_at_the_bin_centres() {
        use std::f64::consts::PI;
        let r = Side::East.ray_directions(5, RayLayout::Bins);
        let expected = [-PI / 5.0, -PI / 10.0, 0.0, PI / 10.0, PI / 5.0];
        assert!(r.iter().zip(expected).all(|(a, b)| close(*a, b)), "{r:?}");
        let n = Side::North.ray_directions(2, RayLayout::Bins);
        assert!(close(n[0], 3.0 * PI / 8.0) && close(n[1], 5.0 * PI / 8.0), "{n:?}");
    }

    #[test]
    fn one_ray_keeps_the_quirk() {
        for side in [Side::North, Side::East, Side::South, Side::West] {
            for layout in [RayLayout::Ends, RayLayout::Bins] {
                assert_eq!(side.ray_directions(1, layout), vec![FRAC_PI_4], "{side:?}");
            }
        }
    }

    #[test]
    fn measures_the_distance_to_flat_ground() {
        let mut b = WorldBuilder::new(WorldSettings::default());
        // ground: top surface at y = 0
        b.add_static_polygon(Polygon::rect(Vec2::new(0.0, -5.0), 100.0, 5.0), 1.0, 0.0);
        let world = b.build().unwrap();
        // a bottom voxel (south side) 4 above the ground: rays at 225°, 270°, 315°
        let mut lidar = Lidar::new(10.0, 3, (0.5, 0.0), RayLayout::Ends);
        let mut state = still_state();
        state.center = Vec2::new(0.0, 4.0);
        let mut out = [0.0; 3];
        lidar.sense(&frame(&world, &state, 0.0), &mut out);
        assert!(
            close(out[1], 4.0) && close(out[0], 4.0 * SQRT_2) && close(out[2], 4.0 * SQRT_2),
            "{out:?}"
        );
        assert_eq!(lidar.last_distances(), &out);
        // tilted by 45°: the first ray now points straight down
        state.angle = FRAC_PI_4;
        lidar.sense(&frame(&world, &state, 0.0), &mut out);
        assert!(
            close(out[0], 4.0) && close(out[1], 4.0 * SQRT_2) && close(out[2], 10.0),
            "{out:?}"
        );
        // out of range: every ray reads the range
        state.angle = 0.0;
        state.center = Vec2::new(0.0, 40.0);
        lidar.sense(&frame(&world, &state, 0.0), &mut out);
        assert_eq!(out, [10.0; 3]);
        lidar.reset();
        assert_eq!(lidar.last_distances(), &[10.0; 3]);
    }
}
