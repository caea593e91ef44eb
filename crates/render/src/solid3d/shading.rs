//! Colours of 3D frames: the palette (sky, floor, fixed voxels, default voxel) and the Lambert
//! shading of faces against a fixed light.

use super::vec3::Vec3;
use crate::draw::Rgba;

/// The sky, above the horizon.
pub(crate) const SKY: Rgba = [214, 230, 245, 255];
/// Light squares of the floor.
pub(crate) const FLOOR_LIGHT: Rgba = [226, 226, 226, 255];
/// Dark squares of the floor.
pub(crate) const FLOOR_DARK: Rgba = [196, 196, 196, 255];
/// The floor far away, where its squares fade: between the two.
pub(crate) const FLOOR_FAR: Rgba = [211, 211, 211, 255];
/// Voxels that never move (walls, obstacles), before shading.
pub(crate) const FIXED_VOXEL: Rgba = [140, 140, 140, 255];
/// Voxels when the trace gives no colour, before shading.
pub(crate) const DEFAULT_VOXEL: Rgba = [79, 155, 217, 255];
/// What a fully contracted voxel (actuation −1) tends to when the trace gives no colour.
const CONTRACTED: Rgba = [222, 84, 84, 255];
/// What a fully expanded voxel (actuation +1) tends to when the trace gives no colour.
const EXPANDED: Rgba = [92, 196, 92, 255];
/// How far full actuation moves the default colour towards its extreme.
const TINT: f64 = 0.6;
/// A voxel voting "passable" (vote > 0), as the thesis's figures.
pub(crate) const VOTE_PASSABLE: Rgba = [40, 90, 225, 255];
/// A voxel voting "impassable" (vote ≤ 0).
pub(crate) const VOTE_IMPASSABLE: Rgba = [220, 45, 45, 255];
/// A vote of 0 tends to this: votes near 0 look pale.
const VOTE_PALE: Rgba = [205, 205, 215, 255];
/// The border of a voxel that touches another (its touch sensor fires).
pub(crate) const TOUCH_BORDER: Rgba = [250, 205, 0, 255];

/// Light reaching a face regardless of its direction (fraction of full).
pub(crate) const AMBIENT: f64 = 0.35;

/// Direction towards the light: above, in front, a little right, so the top, front and side
/// faces of a cube get three different shades.
fn light() -> Vec3 {
    Vec3::new(0.35, -0.55, 0.76).normalized()
}

/// Brightness of a face with outward normal `normal`: ambient plus a Lambert term.
pub(crate) fn brightness(normal: Vec3) -> f64 {
    AMBIENT + (1.0 - AMBIENT) * normal.normalized().dot(light()).max(0.0)
}

/// `c` scaled by `factor` (alpha kept).
pub(crate) fn scaled(c: Rgba, factor: f64) -> Rgba {
    let k = |v: u8| (f64::from(v) * factor).round().clamp(0.0, 255.0) as u8;
    [k(c[0]), k(c[1]), k(c[2]), c[3]]
}

/// `a` moved a fraction `t` (clamped to [0, 1]) towards `b`.
pub(crate) fn mix(a: Rgba, b: Rgba, t: f64) -> Rgba {
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    std::array::from_fn(|i| (f64::from(a[i]) + (f64::from(b[i]) - f64::from(a[i])) * t).round() as u8)
}

/// The colour of a face of base colour `c` facing `normal`.
pub(crate) fn shaded(c: Rgba, normal: Vec3) -> Rgba {
    scaled(c, brightness(normal))
}

/// The thin outline around a face of colour `c`: a darker version of it.
pub(crate) fn outline(c: Rgba) -> Rgba {
    scaled(c, 0.55)
}

/// The base colour of a moving voxel: its own fill when the trace gives one, else the default,
/// tinted red when contracting and green when expanding by its actuation in [−1, 1] if known.
pub(crate) fn voxel_color(fill: Option<Rgba>, actuation: Option<f64>) -> Rgba {
    if let Some(fill) = fill {
        return fill;
    }
    let a = actuation.filter(|a| a.is_finite()).unwrap_or(0.0).clamp(-1.0, 1.0);
    if a < 0.0 {
        mix(DEFAULT_VOXEL, CONTRACTED, -a * TINT)
    } else {
        mix(DEFAULT_VOXEL, EXPANDED, a * TINT)
    }
}

/// The base colour of a voxel voting `vote` in [−1, 1]: blue when > 0 ("passable"), red
/// otherwise, paler the closer the vote is to 0.
pub(crate) fn vote_color(vote: f64) -> Rgba {
    let v = if vote.is_finite() { vote.clamp(-1.0, 1.0) } else { 0.0 };
    let strong = if v > 0.0 { VOTE_PASSABLE } else { VOTE_IMPASSABLE };
    mix(VOTE_PALE, strong, 0.35 + 0.65 * v.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn top_front_and_side_faces_get_three_shades_and_hidden_ones_only_ambient() {
        let top = brightness(Vec3::new(0.0, 0.0, 1.0));
        let front = brightness(Vec3::new(0.0, -1.0, 0.0));
        let side = brightness(Vec3::new(1.0, 0.0, 0.0));
        assert!(top > front && front > side && side > AMBIENT, "{top} {front} {side}");
        assert_eq!(brightness(Vec3::new(0.0, 0.0, -1.0)), AMBIENT);
        assert!(top <= 1.0);
    }

    #[test]
    fn votes_are_blue_when_passable_and_red_otherwise() {
        assert_eq!(vote_color(1.0), VOTE_PASSABLE);
        assert_eq!(vote_color(-1.0), VOTE_IMPASSABLE);
        assert_eq!(vote_color(-7.0), VOTE_IMPASSABLE, "clamped");
        let (weak, zero) = (vote_color(0.1), vote_color(0.0));
        assert!(
            weak[2] > weak[0] && zero[0] > zero[2],
            "{weak:?} {zero:?}: a 0 vote is a no"
        );
        assert_eq!(vote_color(f64::NAN), zero);
    }

    #[test]
    fn actuation_tints_only_the_default_colour() {
        let red = [200, 0, 0, 255];
        assert_eq!(voxel_color(Some(red), Some(1.0)), red);
        assert_eq!(voxel_color(None, None), DEFAULT_VOXEL);
        assert_eq!(voxel_color(None, Some(f64::NAN)), DEFAULT_VOXEL);
        let contracted = voxel_color(None, Some(-1.0));
        let expanded = voxel_color(None, Some(1.0));
        assert!(contracted[0] > DEFAULT_VOXEL[0] && expanded[1] > DEFAULT_VOXEL[1]);
        assert_eq!(
            voxel_color(None, Some(-5.0)),
            contracted,
            "actuation is clamped to [-1, 1]"
        );
    }
}
