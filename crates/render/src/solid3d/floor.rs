//! The world around a 3D body: sky above the horizon, and the floor (the plane z = −side/2) as a
//! checkerboard of two light greys that fades into the distance.

use super::camera::Camera;
use super::painter::fill_polygon;
use super::shading::{FLOOR_DARK, FLOOR_FAR, FLOOR_LIGHT, SKY};
use super::vec3::Vec3;
use crate::draw::{paint, Rgba};
use tiny_skia::{Color, GradientStop, LinearGradient, Paint, Pixmap, Point, Rect, SpreadMode, Transform};

/// Depth where the floor starts to fade, in multiples of the camera's distance to its target.
const FADE_START: f64 = 1.5;
/// Depth from where the floor shows only its far colour, in multiples of that distance.
const FADE_FULL: f64 = 4.0;
/// Half-side of the square of floor squares drawn around the target, in multiples of that distance.
const REACH: f64 = 7.0;
/// Most squares drawn along each half-side (larger squares beyond it).
const MAX_SQUARES: f64 = 60.0;

/// The floor of a 3D scene: its height and the size of its squares.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Floor {
    /// Height of the floor plane (m).
    pub z: f64,
    /// Side of a square (m).
    pub square: f64,
}

impl Floor {
    /// Draws the sky, the floor's squares around `target` seen by `camera` from `distance`, and
    /// the fading towards the horizon.
    pub fn draw(&self, pm: &mut Pixmap, camera: &Camera, target: Vec3, distance: f64, anti_alias: bool) {
        let [r, g, b, a] = SKY;
        pm.fill(Color::from_rgba8(r, g, b, a));
        // whole pixels: tiny-skia rounds a fractional rectangle's top and height apart
        let horizon = camera.horizon_y().max(0.0).floor();
        let (width, height) = (pm.width() as f32, pm.height() as f32);
        if let Some(rect) = Rect::from_ltrb(0.0, horizon, width, height) {
            pm.fill_rect(rect, &paint(FLOOR_LIGHT, false), Transform::identity(), None);
        }
        self.draw_dark_squares(pm, camera, target, distance, anti_alias);
        self.draw_fade(pm, camera, distance);
    }

    /// The dark squares of the checkerboard (the light ones are the floor's own colour), those
    /// nearer than the full fade only.
    fn draw_dark_squares(&self, pm: &mut Pixmap, camera: &Camera, target: Vec3, distance: f64, anti_alias: bool) {
        let reach = REACH * distance;
        let square = self.square.max(reach / MAX_SQUARES);
        if !(square > 0.0 && square.is_finite() && reach.is_finite()) {
            return;
        }
        let range = |c: f64| ((c - reach) / square).floor() as i64..=((c + reach) / square).ceil() as i64;
        let farthest = FADE_FULL * distance;
        for i in range(target.x) {
            for j in range(target.y) {
                if (i + j).rem_euclid(2) == 0 {
                    continue;
                }
                let corner = |di: i64, dj: i64| Vec3::new((i + di) as f64 * square, (j + dj) as f64 * square, self.z);
                let corners = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
                if corners.iter().all(|&c| camera.depth(c) > farthest) {
                    continue;
                }
                fill_polygon(pm, &camera.project_polygon(&corners), FLOOR_DARK, None, anti_alias);
            }
        }
    }

    /// A gradient from clear (where fading starts) to the far colour (full fade and beyond, up to
    /// the horizon), over the floor.
    fn draw_fade(&self, pm: &mut Pixmap, camera: &Camera, distance: f64) {
        let horizon = camera.horizon_y();
        let start = camera.floor_row(self.z, FADE_START * distance);
        let full = camera.floor_row(self.z, FADE_FULL * distance);
        let clear = |c: Rgba| Color::from_rgba8(c[0], c[1], c[2], 0);
        let [r, g, b, a] = FLOOR_FAR;
        let stops = vec![
            GradientStop::new(0.0, Color::from_rgba8(r, g, b, a)),
            GradientStop::new(1.0, clear(FLOOR_FAR)),
        ];
        let (Some(shader), Some(rect)) = (
            LinearGradient::new(
                Point::from_xy(0.0, full),
                Point::from_xy(0.0, start),
                stops,
                SpreadMode::Pad,
                Transform::identity(),
            ),
            Rect::from_ltrb(
                0.0,
                horizon.max(0.0).floor(),
                pm.width() as f32,
                start.min(pm.height() as f32).ceil(),
            ),
        ) else {
            return;
        };
        let paint = Paint {
            shader,
            ..Paint::default()
        };
        pm.fill_rect(rect, &paint, Transform::identity(), None);
    }
}
