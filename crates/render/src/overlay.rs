//! What frames show besides the world: distance ticks on the ground (so a walker visibly moves
//! even on flat ground), the centre's trail, a text overlay with time, distance and velocity, and
//! the legend of the area-ratio colours.

use crate::camera::View;
use crate::draw::{area_color, pressure_color, Rgba, BROKEN};
use crate::text;
use tiny_skia::{Color, LineCap, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};
use vsrlab_physics::Vec2;
use vsrlab_tasks::Trace;

/// Tick marks and their labels.
const TICK: Rgba = [70, 70, 70, 255];
/// Trail of the centre.
const TRAIL: Rgba = [40, 40, 160, 150];
/// Text colour.
const INK: [u8; 3] = [20, 20, 20];
/// Backing box of the overlay text.
const BACKING: Rgba = [255, 255, 255, 200];
/// A long tick every this many short ones.
const MAJOR_EVERY: i64 = 5;
/// Most centre positions a trail is drawn through (older ones are thinned out).
const TRAIL_POINTS: usize = 400;

fn paint(c: Rgba) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], c[3]));
    p.anti_alias = true;
    p
}

/// Text height in pixels for a frame `height` pixels high.
pub(crate) fn text_size(height: u32) -> f32 {
    (height as f32 / 28.0).clamp(9.0, 28.0)
}

/// Height of the terrain polyline (increasing x) at `x`, if `x` is within it.
fn height_at(terrain: &[Vec2], x: f64) -> Option<f64> {
    let i = terrain.partition_point(|p| p.x < x);
    match (i.checked_sub(1).and_then(|j| terrain.get(j)), terrain.get(i)) {
        (Some(a), Some(b)) if b.x > a.x => Some(a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x)),
        (_, Some(b)) if b.x == x => Some(b.y),
        _ => None,
    }
}

/// Vertical ticks into the ground every voxel side (`spacing` world units), longer every
/// [`MAJOR_EVERY`] sides: fixed to the world, so they slide by when the camera follows the robot.
pub(crate) fn draw_ticks(pm: &mut Pixmap, terrain: &[Vec2], view: &View, spacing: f64, width: u32) {
    if !(spacing.is_finite() && spacing > 0.0) {
        return;
    }
    let first = (view.min_x / spacing).ceil() as i64;
    let last = (view.max_x / spacing).floor() as i64;
    if last < first || last - first > 10_000 {
        return;
    }
    let mut pb = PathBuilder::new();
    for k in first..=last {
        let x = k as f64 * spacing;
        let Some(y) = height_at(terrain, x) else { continue };
        let depth = if k % MAJOR_EVERY == 0 { 0.6 } else { 0.25 } * spacing;
        let (x0, y0) = view.to_pixel(Vec2::new(x, y), width);
        let (_, y1) = view.to_pixel(Vec2::new(x, y - depth), width);
        pb.move_to(x0, y0);
        pb.line_to(x0, y1);
    }
    if let Some(path) = pb.finish() {
        let stroke = Stroke {
            width: 1.5,
            line_cap: LineCap::Butt,
            ..Stroke::default()
        };
        pm.stroke_path(&path, &paint(TICK), &stroke, Transform::identity(), None);
    }
}

/// The path of the robot's centre from the first step to `step`.
pub(crate) fn draw_trail(pm: &mut Pixmap, trace: &Trace, view: &View, step: usize, width: u32) {
    let centers = &trace.centers[..(step + 1).min(trace.centers.len())];
    let stride = centers.len().div_ceil(TRAIL_POINTS).max(1);
    let mut pb = PathBuilder::new();
    let mut started = false;
    for c in centers.iter().step_by(stride).chain(centers.last()) {
        if !(c.x.is_finite() && c.y.is_finite()) {
            continue;
        }
        let (x, y) = view.to_pixel(*c, width);
        if started {
            pb.line_to(x, y);
        } else {
            pb.move_to(x, y);
            started = true;
        }
    }
    if let Some(path) = pb.finish() {
        pm.stroke_path(&path, &paint(TRAIL), &Stroke::default(), Transform::identity(), None);
    }
}

/// The overlay's lines at `step`: time, the centre's displacement since the start (in length
/// units and voxel sides), and the average velocity so far.
pub(crate) fn overlay_lines(trace: &Trace, step: usize) -> Vec<String> {
    let t0 = trace.times.first().copied().unwrap_or(0.0);
    let t = trace.times.get(step).copied().unwrap_or(t0);
    let mut lines = vec![format!("t = {:.2} s", t)];
    if let (Some(start), Some(now)) = (trace.centers.first(), trace.centers.get(step)) {
        let distance = now.x - start.x;
        let side = trace.side_length;
        // a PSA (its trace has pressures) is not measured in voxels
        let sides = if side > 0.0 && !trace.has(vsrlab_tasks::channels::PRESSURE.name) {
            format!(" ({:+.1} voxels)", distance / side)
        } else {
            String::new()
        };
        lines.push(format!("distance {distance:+.1}{sides}"));
        let elapsed = t - t0;
        if elapsed > 0.0 {
            lines.push(format!("velocity {:+.2} /s", distance / elapsed));
        }
        if let Some(p) = trace.value(vsrlab_tasks::channels::PRESSURE.name, step, 0) {
            lines.push(format!("pressure {:.2} p_max", p));
        }
    }
    lines
}

/// The overlay: its lines in a translucent box at the top left, below the time bar.
pub(crate) fn draw_overlay(pm: &mut Pixmap, trace: &Trace, step: usize) {
    let size = text_size(pm.height());
    let lines = overlay_lines(trace, step);
    let line_height = size * 1.25;
    let box_width = lines.iter().map(|l| text::width(l, size)).fold(0.0, f32::max) + size;
    let box_height = line_height * lines.len() as f32 + size * 0.5;
    if let Some(rect) = Rect::from_xywh(4.0, 6.0, box_width, box_height) {
        pm.fill_rect(rect, &paint(BACKING), Transform::identity(), None);
    }
    for (i, line) in lines.iter().enumerate() {
        text::draw(
            pm,
            line,
            4.0 + size * 0.5,
            6.0 + size * 0.25 + line_height * i as f32,
            size,
            INK,
        );
    }
}

/// The legend of voxel colours at the top right: a bar from contracted (area ratio 0.75, red)
/// through rest (1, yellow) to expanded (1.25, green), labelled at both ends.
/// The colour bar of voxel areas, and, when the episode has damage, the broken voxels' swatch.
pub(crate) fn draw_legend(pm: &mut Pixmap, damage: bool, pressure: bool) {
    let size = text_size(pm.height()) * 0.85;
    let (left_label, right_label) = if pressure {
        ("pressure 0", "p_max")
    } else {
        ("contracted", "expanded")
    };
    let bar = (size * 6.0).round();
    let total = text::width(left_label, size) + bar + text::width(right_label, size) + size;
    let x0 = pm.width() as f32 - total - 6.0;
    let y0 = 8.0;
    if x0 < 0.0 {
        return;
    }
    if let Some(rect) = Rect::from_xywh(x0 - 4.0, y0 - 2.0, total + 8.0, size * 1.4) {
        pm.fill_rect(rect, &paint(BACKING), Transform::identity(), None);
    }
    text::draw(pm, left_label, x0, y0, size, INK);
    let bar_x = x0 + text::width(left_label, size) + size * 0.5;
    for i in 0..bar as i64 {
        let fraction = i as f64 / (bar as f64 - 1.0).max(1.0);
        let [r, g, b, a] = if pressure {
            pressure_color(fraction)
        } else {
            area_color(0.75 + 0.5 * fraction)
        };
        for y in 0..(size as i64) {
            text::blend(pm, bar_x as i64 + i, y0 as i64 + 2 + y, [r, g, b], f32::from(a) / 255.0);
        }
    }
    text::draw(pm, right_label, bar_x + bar + size * 0.5, y0, size, INK);
    if damage {
        let label = "broken (no actuation)";
        let y1 = y0 + size * 1.6;
        let width = size * 1.5 + text::width(label, size);
        if let Some(rect) = Rect::from_xywh(x0 - 4.0, y1 - 2.0, width + 8.0, size * 1.4) {
            pm.fill_rect(rect, &paint(BACKING), Transform::identity(), None);
        }
        let [r, g, b, a] = BROKEN;
        for i in 0..size as i64 {
            for y in 0..(size as i64) {
                text::blend(pm, x0 as i64 + i, y1 as i64 + 2 + y, [r, g, b], f32::from(a) / 255.0);
            }
        }
        text::draw(pm, label, x0 + size * 1.5, y1, size, INK);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn terrain_heights_interpolate_and_stop_at_the_ends() {
        let terrain = [Vec2::new(0.0, 0.0), Vec2::new(10.0, 5.0), Vec2::new(20.0, 5.0)];
        assert_eq!(height_at(&terrain, 5.0), Some(2.5));
        assert_eq!(height_at(&terrain, 15.0), Some(5.0));
        assert_eq!(height_at(&terrain, 0.0), Some(0.0));
        assert_eq!(height_at(&terrain, -1.0), None);
        assert_eq!(height_at(&terrain, 21.0), None);
    }

    #[test]
    fn overlay_reports_time_distance_and_velocity() {
        let mut trace = Trace {
            side_length: 3.0,
            ..Trace::default()
        };
        trace.times = vec![0.0, 1.0, 2.0];
        trace.centers = vec![Vec2::new(10.0, 1.0), Vec2::new(13.0, 1.0), Vec2::new(16.0, 1.0)];
        assert_eq!(
            overlay_lines(&trace, 2),
            ["t = 2.00 s", "distance +6.0 (+2.0 voxels)", "velocity +3.00 /s"]
        );
        assert_eq!(overlay_lines(&trace, 0), ["t = 0.00 s", "distance +0.0 (+0.0 voxels)"]);
    }
}
