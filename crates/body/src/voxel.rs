//! The voxel's mechanical layout (vsr-model.md §1): four corner squares, 18 springs, 4 ropes.

use crate::params::VoxelParams;
use vsrlab_physics::Vec2;

/// Corner indices: 0 = NW (top-left), 1 = NE, 2 = SE, 3 = SW.
pub const NW: usize = 0;
/// North-east corner.
pub const NE: usize = 1;
/// South-east corner.
pub const SE: usize = 2;
/// South-west corner.
pub const SW: usize = 3;

/// The three families of springs, which differ in rest length and actuation range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpringKind {
    /// Along the outer or inner edge of a side (SIDE_EXTERNAL, SIDE_INTERNAL).
    Parallel,
    /// The two crossing diagonals in the gap of a side (SIDE_CROSS).
    SideCross,
    /// Corner centre to corner centre across the voxel (CENTRAL_CROSS).
    Central,
}

/// One spring of the voxel: corner parts, anchors in each part's frame, and family.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringLayout {
    /// First corner (0..4).
    pub corner_a: usize,
    /// Anchor on the first corner, relative to its centre.
    pub anchor_a: Vec2,
    /// Second corner.
    pub corner_b: usize,
    /// Anchor on the second corner.
    pub anchor_b: Vec2,
    /// Family.
    pub kind: SpringKind,
}

/// Number of springs per voxel.
pub const SPRINGS_PER_VOXEL: usize = 18;

/// Offset of corner `i`'s centre from the voxel centre.
pub fn corner_offset(params: &VoxelParams, i: usize) -> Vec2 {
    let d = params.side_length / 2.0 - params.corner_side() / 2.0;
    match i {
        NW => Vec2::new(-d, d),
        NE => Vec2::new(d, d),
        SE => Vec2::new(d, -d),
        _ => Vec2::new(-d, -d),
    }
}

/// The 18 springs: 4 external, 4 internal and 8 crossing on the sides, then 2 central.
pub fn spring_layout(params: &VoxelParams) -> [SpringLayout; SPRINGS_PER_VOXEL] {
    let h = params.corner_side() / 2.0;
    // (first corner, direction towards the second corner, outward normal of the side)
    let sides = [
        (NW, NE, Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)),
        (NE, SE, Vec2::new(0.0, -1.0), Vec2::new(1.0, 0.0)),
        (SE, SW, Vec2::new(-1.0, 0.0), Vec2::new(0.0, -1.0)),
        (SW, NW, Vec2::new(0.0, 1.0), Vec2::new(-1.0, 0.0)),
    ];
    let spring = |a, pa: Vec2, b, pb: Vec2, kind| SpringLayout {
        corner_a: a,
        anchor_a: pa * h,
        corner_b: b,
        anchor_b: pb * h,
        kind,
    };
    let mut out = Vec::with_capacity(SPRINGS_PER_VOXEL);
    for &(p, q, d, o) in &sides {
        out.push(spring(p, d + o, q, o - d, SpringKind::Parallel));
    }
    for &(p, q, d, o) in &sides {
        out.push(spring(p, d - o, q, -d - o, SpringKind::Parallel));
    }
    for &(p, q, d, o) in &sides {
        out.push(spring(p, d + o, q, -d - o, SpringKind::SideCross));
        out.push(spring(p, d - o, q, o - d, SpringKind::SideCross));
    }
    out.push(spring(NW, Vec2::ZERO, SE, Vec2::ZERO, SpringKind::Central));
    out.push(spring(NE, Vec2::ZERO, SW, Vec2::ZERO, SpringKind::Central));
    out.try_into().expect("18 springs")
}

/// Rest length of a spring family for a voxel of side `side` (vsr-model.md §1.6).
pub fn rest_length(kind: SpringKind, side: f64, m: f64) -> f64 {
    match kind {
        SpringKind::Parallel => side - 2.0 * m,
        SpringKind::SideCross => (m * m + (side - 2.0 * m).powi(2)).sqrt(),
        SpringKind::Central => (side - m) * std::f64::consts::SQRT_2,
    }
}

/// (min, rest, max) rest lengths of a spring family: full contraction, neutral, full expansion.
pub fn rest_range(params: &VoxelParams, kind: SpringKind) -> (f64, f64, f64) {
    let (l, m) = (params.side_length, params.corner_side());
    (
        rest_length(kind, (l * l * params.min_area_ratio).sqrt(), m),
        rest_length(kind, l, m),
        rest_length(kind, (l * l * params.max_area_ratio).sqrt(), m),
    )
}

/// Rest length for actuation `f` (clipped to [-1, 1]; positive contracts), linear per spring.
#[inline]
pub fn actuated_rest_length(range: (f64, f64, f64), f: f64) -> f64 {
    let f = if f.is_nan() { 0.0 } else { f.clamp(-1.0, 1.0) };
    let (min, rest, max) = range;
    if f >= 0.0 {
        rest - (rest - min) * f
    } else {
        rest + (max - rest) * (-f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Preset;

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() < 5e-5
    }

    #[test]
    fn rest_ranges_match_the_published_table() {
        let p = VoxelParams::preset(Preset::Y2021);
        let (a, b, c) = rest_range(&p, SpringKind::Parallel);
        assert!(close(a, 0.2410) && close(b, 0.6) && close(c, 0.9204), "{a} {b} {c}");
        let (a, b, c) = rest_range(&p, SpringKind::SideCross);
        assert!(close(a, 1.2240) && close(b, 1.3416) && close(c, 1.5123), "{a} {b} {c}");
        let (a, b, c) = rest_range(&p, SpringKind::Central);
        assert!(close(a, 2.0379) && close(b, 2.5456) && close(c, 2.9987), "{a} {b} {c}");
        let q = VoxelParams::preset(Preset::Y2022);
        let (a, b, c) = rest_range(&q, SpringKind::SideCross);
        assert!(close(a, 1.2011) && close(b, 1.3829) && close(c, 1.5843), "{a} {b} {c}");
    }

    #[test]
    fn layout_rest_lengths_equal_anchor_distances_at_rest() {
        for preset in [Preset::Y2021, Preset::Y2022] {
            let p = VoxelParams::preset(preset);
            for s in spring_layout(&p) {
                let pa = corner_offset(&p, s.corner_a) + s.anchor_a;
                let pb = corner_offset(&p, s.corner_b) + s.anchor_b;
                let expected = rest_length(s.kind, p.side_length, p.corner_side());
                assert!(((pb - pa).length() - expected).abs() < 1e-12, "{s:?}");
            }
        }
    }

    #[test]
    fn actuation_is_clipped_and_positive_contracts() {
        let r = (1.0, 2.0, 4.0);
        assert_eq!(actuated_rest_length(r, 1.0), 1.0);
        assert_eq!(actuated_rest_length(r, 5.0), 1.0);
        assert_eq!(actuated_rest_length(r, -1.0), 4.0);
        assert_eq!(actuated_rest_length(r, -0.5), 3.0);
        assert_eq!(actuated_rest_length(r, f64::NAN), 2.0);
    }
}
