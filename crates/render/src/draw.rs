//! Drawing one frame with tiny-skia (vsr-model.md §6).

use crate::camera::{self, BBox, View};
use crate::overlay;
use crate::{RenderOptions, MAX_SIDE};
use std::f64::consts::PI;
use tiny_skia::{Color, FillRule, LineCap, LineJoin, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};
use vsrlab_physics::Vec2;
use vsrlab_tasks::{channels, Polygons, Trace};

/// Whole numbers of a fixed channel (counts, indices).
fn whole(values: &[f64]) -> impl Iterator<Item = usize> + '_ {
    values.iter().map(|&v| v as usize)
}

/// An opaque or translucent colour: red, green, blue, alpha.
pub(crate) type Rgba = [u8; 4];

/// Background.
pub(crate) const BACKGROUND: Rgba = [255, 255, 255, 255];
/// Ground fill.
pub(crate) const GROUND: Rgba = [180, 180, 180, 255];
/// Ground outline.
pub(crate) const GROUND_OUTLINE: Rgba = [0, 0, 0, 255];
/// Voxel outline.
pub(crate) const VOXEL_OUTLINE: Rgba = [0, 0, 255, 255];
/// Outline of a voxel touching the ground.
pub(crate) const TOUCH_OUTLINE: Rgba = [0, 0, 120, 255];
/// Fill of a contracted voxel (area ratio ≤ 0.75).
pub(crate) const RED: Rgba = [255, 0, 0, 128];
/// Fill of a voxel at rest (area ratio 1).
pub(crate) const YELLOW: Rgba = [255, 255, 0, 128];
/// Fill of an expanded voxel (area ratio ≥ 1.25).
pub(crate) const GREEN: Rgba = [0, 255, 0, 128];
/// Fill of a sensor reading sector.
/// Fill of a broken voxel (it no longer actuates, [`vsrlab_tasks::Damage`]).
pub(crate) const BROKEN: Rgba = [60, 60, 60, 150];
/// Fill of sensor glyphs.
pub(crate) const SENSOR_FILL: Rgba = [0, 0, 0, 84];
/// Outline of a sensor half-disk.
pub(crate) const SENSOR_OUTLINE: Rgba = [0, 0, 0, 255];
/// Lidar rays and hit circles.
pub(crate) const LIDAR: Rgba = [255, 0, 0, 255];
/// The elapsed-time bar.
pub(crate) const TIME_BAR: Rgba = [90, 90, 90, 255];
/// Height of the time bar in pixels.
const TIME_BAR_HEIGHT: f32 = 3.0;

/// An opaque colour from `0xRRGGBB` held in a channel value (out-of-range values are clamped).
pub(crate) fn packed_rgb(value: f64) -> Rgba {
    let c = if value.is_finite() {
        value.clamp(0.0, 16_777_215.0) as u32
    } else {
        0
    };
    [(c >> 16) as u8, (c >> 8 & 0xff) as u8, (c & 0xff) as u8, 255]
}

/// Voxel fill for an area ratio: piecewise linear red (≤ 0.75) → yellow (1) → green (≥ 1.25).
pub(crate) fn area_color(ratio: f64) -> Rgba {
    let ratio = if ratio.is_finite() { ratio } else { 1.0 };
    let lerp = |a: Rgba, b: Rgba, t: f64| -> Rgba {
        std::array::from_fn(|i| (f64::from(a[i]) + (f64::from(b[i]) - f64::from(a[i])) * t).round() as u8)
    };
    if ratio <= 1.0 {
        lerp(RED, YELLOW, ((ratio - 0.75) / 0.25).clamp(0.0, 1.0))
    } else {
        lerp(YELLOW, GREEN, ((ratio - 1.0) / 0.25).clamp(0.0, 1.0))
    }
}

/// Membrane fill of a pressurised body for p/p_max: blue (0) → violet → red (1).
pub(crate) fn pressure_color(ratio: f64) -> Rgba {
    let t = if ratio.is_finite() { ratio.clamp(0.0, 1.0) } else { 0.0 };
    let lerp = |a: f64, b: f64| (a + (b - a) * t).round() as u8;
    [lerp(40.0, 230.0), lerp(90.0, 40.0), lerp(230.0, 40.0), 110]
}

/// Fill of static obstacles (walls, a cage's roof) and of loose balls.
pub(crate) const OBSTACLE: Rgba = [150, 150, 150, 255];
/// Fill of a loose ball.
pub(crate) const BALL: Rgba = [230, 60, 60, 230];

/// A solid paint of colour `c`.
pub(crate) fn paint(c: Rgba, anti_alias: bool) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(c[0], c[1], c[2], c[3]));
    p.anti_alias = anti_alias;
    p
}

/// A round-capped, round-joined stroke `width` pixels wide.
pub(crate) fn stroke(width: f32) -> Stroke {
    Stroke {
        width,
        line_cap: LineCap::Round,
        line_join: LineJoin::Round,
        ..Stroke::default()
    }
}

/// Everything about a trace that does not change from frame to frame.
pub(crate) struct Scene<'a> {
    trace: &'a Trace,
    opts: RenderOptions,
    boxes: Vec<Option<BBox>>,
    /// First reading of each voxel within a step's readings, and each voxel's count.
    reading_offsets: Vec<usize>,
    readings_per_unit: Vec<usize>,
    /// A graph brain's neurons (unit, kind) and edges (source, target, weight), if any.
    neurons: Vec<(usize, u8)>,
    edges: Vec<(usize, usize, f32)>,
    /// The lidar rays: (unit, direction relative to the unit, range).
    rays: Vec<(usize, f64, f64)>,
    /// Side of each unit's attention matrix (0 without).
    attention_side: usize,
    /// The polygon of each brain unit, where it is not the unit's own index.
    unit_polygons: Vec<usize>,
    /// The kind's fill colour of each polygon (channel `unit_fill`), where it gives one.
    unit_fill: Vec<Rgba>,
    anti_alias: bool,
    /// The 3D drawing of a 3D trace (channel `voxel_xyz`), which replaces the 2D one.
    solid: Option<crate::solid3d::SolidScene<'a>>,
}

impl<'a> Scene<'a> {
    /// Prepares to draw frames of `trace` (sizes clamped to 1..=MAX_SIDE), anti-aliased or not.
    pub fn new(trace: &'a Trace, opts: &RenderOptions, anti_alias: bool) -> Self {
        let mut opts = opts.clone();
        opts.width = opts.width.clamp(1, MAX_SIDE);
        opts.height = opts.height.clamp(1, MAX_SIDE);
        let readings_per_unit: Vec<usize> = whole(trace.fixed_values(channels::READINGS_PER_UNIT.name)).collect();
        let mut reading_offsets = Vec::with_capacity(readings_per_unit.len());
        let mut total = 0;
        for &n in &readings_per_unit {
            reading_offsets.push(total);
            total += n;
        }
        let rows = |name: &str| trace.channel(name).into_iter().flat_map(|c| c.rows());
        let unit_polygons: Vec<usize> = whole(trace.fixed_values(channels::UNIT_POLYGONS.name)).collect();
        let polygon = |unit: usize| unit_polygons.get(unit).copied().unwrap_or(unit);
        Scene {
            trace,
            boxes: camera::step_boxes(trace),
            reading_offsets,
            readings_per_unit,
            neurons: rows(channels::GRAPH_NEURONS.name)
                .map(|n| (polygon(n[0] as usize), n[1] as u8))
                .collect(),
            edges: rows(channels::GRAPH_EDGES.name)
                .map(|e| (e[0] as usize, e[1] as usize, e[2] as f32))
                .collect(),
            rays: rows(channels::RAYS.name).map(|r| (r[0] as usize, r[1], r[2])).collect(),
            attention_side: whole(trace.fixed_values(channels::ATTENTION_SIDE.name))
                .next()
                .unwrap_or(0),
            unit_polygons: unit_polygons.clone(),
            unit_fill: trace
                .fixed_values(channels::UNIT_FILL.name)
                .iter()
                .map(|&c| packed_rgb(c))
                .collect(),
            anti_alias,
            solid: crate::solid3d::SolidScene::of(trace, &opts, anti_alias),
            opts,
        }
    }

    /// A blank pixmap of the frame size.
    pub fn new_pixmap(&self) -> Pixmap {
        Pixmap::new(self.opts.width, self.opts.height).expect("frame size is within tiny-skia's limits")
    }

    /// Draws step `step` (clamped to the last one) into `pm`, which must have the frame size.
    pub fn draw(&self, step: usize, pm: &mut Pixmap) {
        let t = self.trace;
        let paint = |c: Rgba| paint(c, self.anti_alias);
        let [r, g, b, a] = BACKGROUND;
        pm.fill(Color::from_rgba8(r, g, b, a));
        let step = step.min(t.len().saturating_sub(1));
        if let Some(solid) = &self.solid {
            solid.draw(step, pm);
            self.draw_time_bar(pm, step);
            if self.opts.draw_overlay {
                overlay::draw_overlay(pm, t, step);
            }
            return;
        }
        let view = camera::view_at(t, &self.boxes, step, self.opts.width, self.opts.height);
        let px = |p: Vec2| view.to_pixel(p, self.opts.width);
        self.draw_ground(pm, &view);
        self.draw_obstacles(pm, &view);
        if self.opts.draw_ticks {
            overlay::draw_ticks(pm, &t.terrain, &view, camera::side(t), self.opts.width);
        }
        if t.is_empty() {
            return;
        }
        if self.opts.draw_trail {
            overlay::draw_trail(pm, t, &view, step, self.opts.width);
        }
        let polys = t.polygons_at(step);
        let area_ratios = t.at(channels::AREA_RATIO.name, step);
        let touching = t.at(channels::TOUCH.name, step);
        let pressure = t.value(channels::PRESSURE.name, step, 0);
        for (v, poly) in polys.iter().enumerate() {
            let Some(path) = closed_path(poly, px) else { continue };
            let ratio = area_ratios
                .and_then(|a| a.get(v))
                .copied()
                .unwrap_or_else(|| area(poly) / camera::side(t).powi(2));
            let broken = t.is_broken(step, v);
            let fill = match pressure {
                // a PSA: the membrane (polygon 0) shows the pressure
                Some(p) if v == 0 => pressure_color(p),
                _ if broken => BROKEN,
                _ => self.unit_fill.get(v).copied().unwrap_or_else(|| area_color(ratio)),
            };
            pm.fill_path(&path, &paint(fill), FillRule::Winding, Transform::identity(), None);
            if broken && poly.len() == 4 {
                // a cross over the broken voxel, corner to corner
                let mut cross = PathBuilder::new();
                for (a, b) in [(0, 2), (1, 3)] {
                    let (ax, ay) = px(poly[a]);
                    let (bx, by) = px(poly[b]);
                    cross.move_to(ax, ay);
                    cross.line_to(bx, by);
                }
                if let Some(cross) = cross.finish() {
                    pm.stroke_path(&cross, &paint(VOXEL_OUTLINE), &stroke(1.0), Transform::identity(), None);
                }
            }
            let touching = touching.and_then(|t| t.get(v)).is_some_and(|&t| t > 0.5);
            let (color, width) = if touching {
                (TOUCH_OUTLINE, 2.0)
            } else {
                (VOXEL_OUTLINE, 1.0)
            };
            pm.stroke_path(&path, &paint(color), &stroke(width), Transform::identity(), None);
        }
        self.draw_balls(pm, &view, step);
        let side = self.attention_side;
        let attention = self.opts.draw_attention && side > 0;
        let graph = self.opts.draw_graph && !self.neurons.is_empty();
        if self.opts.draw_sensors && !attention && !graph {
            self.draw_sensors(pm, &view, step, polys);
        }
        if attention {
            let px = |p: Vec2| view.to_pixel(p, self.opts.width);
            let matrices = t.at(channels::ATTENTION.name, step).unwrap_or(&[]);
            for (v, matrix) in matrices.chunks_exact(side * side).enumerate() {
                let unit = self.unit_polygons.get(v).copied().unwrap_or(v);
                if let Some(poly) = polys.get(unit) {
                    let c = center(poly);
                    let half = area(poly).sqrt() * 0.3;
                    let (x0, y0) = px(c - Vec2::new(half, -half));
                    let (x1, _) = px(c + Vec2::new(half, half));
                    crate::attention::draw_matrix(pm, (x0, y0), x1 - x0, side, matrix);
                }
            }
        }
        if graph {
            let px = |p: Vec2| view.to_pixel(p, self.opts.width);
            let polys: Vec<&[Vec2]> = polys.iter().collect();
            crate::graph::draw_graph(
                pm,
                &polys,
                &self.neurons,
                &self.edges,
                t.at(channels::GRAPH_OUTPUTS.name, step),
                px,
                self.anti_alias,
            );
        }
        if self.opts.draw_lidar {
            self.draw_lidar(pm, &view, step, polys);
        }
        self.draw_time_bar(pm, step);
        if self.opts.draw_overlay {
            overlay::draw_overlay(pm, t, step);
        }
        // the legend explains the area colours, which a kind that colours its units replaces
        if self.opts.draw_legend && self.unit_fill.is_empty() {
            overlay::draw_legend(pm, t.damage.is_some(), t.has(channels::PRESSURE.name));
        }
    }

    /// The ground polygon: the terrain within (a margin around) the view, closed below it.
    fn draw_ground(&self, pm: &mut Pixmap, view: &View) {
        let paint = |c: Rgba| paint(c, self.anti_alias);
        let margin = (view.max_x - view.min_x) * 0.1;
        let pts = clip_polyline(&self.trace.terrain, view.min_x - margin, view.max_x + margin);
        let (Some(first), Some(last)) = (pts.first(), pts.last()) else {
            return;
        };
        let bottom = view.min_y - margin;
        let px = |p: Vec2| view.to_pixel(p, self.opts.width);
        let mut pb = PathBuilder::new();
        let (x, y) = px(pts[0]);
        pb.move_to(x, y);
        for &p in &pts[1..] {
            let (x, y) = px(p);
            pb.line_to(x, y);
        }
        let lowest = pts.iter().map(|p| p.y).fold(bottom, f64::min) - margin;
        for p in [Vec2::new(last.x, lowest), Vec2::new(first.x, lowest)] {
            let (x, y) = px(p);
            pb.line_to(x, y);
        }
        pb.close();
        if let Some(path) = pb.finish() {
            pm.fill_path(&path, &paint(GROUND), FillRule::Winding, Transform::identity(), None);
            pm.stroke_path(&path, &paint(GROUND_OUTLINE), &stroke(1.5), Transform::identity(), None);
        }
    }

    /// Static polygons besides the ground (a cage).
    fn draw_obstacles(&self, pm: &mut Pixmap, view: &View) {
        let px = |p: Vec2| view.to_pixel(p, self.opts.width);
        for poly in &channels::obstacles(self.trace) {
            if let Some(path) = closed_path(poly, px) {
                pm.fill_path(
                    &path,
                    &paint(OBSTACLE, self.anti_alias),
                    FillRule::Winding,
                    Transform::identity(),
                    None,
                );
                let outline = paint(GROUND_OUTLINE, self.anti_alias);
                pm.stroke_path(&path, &outline, &stroke(1.0), Transform::identity(), None);
            }
        }
    }

    /// Loose balls at `step`, with a spoke that shows their rotation.
    fn draw_balls(&self, pm: &mut Pixmap, view: &View, step: usize) {
        let px = |p: Vec2| view.to_pixel(p, self.opts.width);
        for (centre, angle, radius) in channels::balls(self.trace, step) {
            let (cx, cy) = px(centre);
            let (ex, _) = px(centre + Vec2::new(radius, 0.0));
            let r = (ex - cx).abs();
            let Some(circle) = PathBuilder::from_circle(cx, cy, r.max(1.0)) else {
                continue;
            };
            pm.fill_path(
                &circle,
                &paint(BALL, self.anti_alias),
                FillRule::Winding,
                Transform::identity(),
                None,
            );
            let outline = paint(GROUND_OUTLINE, self.anti_alias);
            pm.stroke_path(&circle, &outline, &stroke(1.0), Transform::identity(), None);
            let (sx, sy) = px(centre + Vec2::new(angle.cos(), angle.sin()) * radius);
            let mut spoke = PathBuilder::new();
            spoke.move_to(cx, cy);
            spoke.line_to(sx, sy);
            if let Some(spoke) = spoke.finish() {
                pm.stroke_path(&spoke, &outline, &stroke(1.0), Transform::identity(), None);
            }
        }
    }

    /// Half-disks of sensor readings, one sector per reading.
    fn draw_sensors(&self, pm: &mut Pixmap, view: &View, step: usize, polys: Polygons<'_>) {
        let t = self.trace;
        let px = |p: Vec2| view.to_pixel(p, self.opts.width);
        let fill = paint(SENSOR_FILL, self.anti_alias);
        let outline = paint(SENSOR_OUTLINE, self.anti_alias);
        // without anti-aliasing, strokes under a pixel wide come out dotted
        let thin = stroke(if self.anti_alias { 0.75 } else { 1.0 });
        for (v, poly) in polys.iter().enumerate() {
            let count = self.readings_per_unit.get(v).copied().unwrap_or(0);
            if count == 0 {
                continue;
            }
            let c = center(poly);
            let radius = area(poly).sqrt() / 2.0;
            let angle = self.angle(step, v, poly);
            let slice = PI / count as f64;
            let readings = t.at(channels::READINGS.name, step).unwrap_or(&[]);
            let base = self.reading_offsets[v];
            for i in 0..count {
                let Some(&value) = readings.get(base + i) else { break };
                let value = if value.is_finite() { value.clamp(0.0, 1.0) } else { 0.0 };
                let a0 = angle + i as f64 * slice;
                if let Some(path) = sector(c, radius * value, a0, a0 + slice, px) {
                    pm.fill_path(&path, &fill, FillRule::Winding, Transform::identity(), None);
                }
            }
            if let Some(path) = sector(c, radius, angle, angle + PI, px) {
                pm.stroke_path(&path, &outline, &thin, Transform::identity(), None);
            }
        }
    }

    /// Lidar rays from each voxel centre, with a circle at each hit closer than the range.
    fn draw_lidar(&self, pm: &mut Pixmap, view: &View, step: usize, polys: Polygons<'_>) {
        let t = self.trace;
        let px = |p: Vec2| view.to_pixel(p, self.opts.width);
        let red = paint(LIDAR, self.anti_alias);
        let line = stroke(1.0);
        let hit_radius = (0.25 * view.scale(self.opts.width)) as f32;
        for (i, &(unit, relative_angle, range)) in self.rays.iter().enumerate() {
            let Some(poly) = polys.get(unit) else { continue };
            let measured = t.value(channels::LIDAR.name, step, i);
            let (length, hit) = match measured {
                Some(d) if d.is_finite() && d >= 0.0 && d < range => (d, true),
                _ => (range, false),
            };
            if !length.is_finite() {
                continue;
            }
            let c = center(poly);
            let dir = self.angle(step, unit, poly) + relative_angle;
            let end = c + Vec2::new(dir.cos(), dir.sin()) * length;
            let (x0, y0) = px(c);
            let (x1, y1) = px(end);
            let mut pb = PathBuilder::new();
            pb.move_to(x0, y0);
            pb.line_to(x1, y1);
            if let Some(path) = pb.finish() {
                pm.stroke_path(&path, &red, &line, Transform::identity(), None);
            }
            if hit {
                if let Some(path) = PathBuilder::from_circle(x1, y1, hit_radius) {
                    pm.stroke_path(&path, &red, &line, Transform::identity(), None);
                }
            }
        }
    }

    /// A thin bar along the top edge, as long as the elapsed fraction of the episode.
    fn draw_time_bar(&self, pm: &mut Pixmap, step: usize) {
        let times = &self.trace.times;
        let (Some(&t0), Some(&t1), Some(&now)) = (times.first(), times.last(), times.get(step)) else {
            return;
        };
        if t1 <= t0 || t1.is_nan() || t0.is_nan() {
            return;
        }
        let frac = ((now - t0) / (t1 - t0)).clamp(0.0, 1.0) as f32;
        if let Some(rect) = Rect::from_xywh(0.0, 0.0, self.opts.width as f32 * frac, TIME_BAR_HEIGHT) {
            pm.fill_rect(rect, &paint(TIME_BAR, false), Transform::identity(), None);
        }
    }

    /// Angle of voxel `v` at `step`: the recorded one, or else the mean direction of its top and
    /// bottom edges.
    fn angle(&self, step: usize, v: usize, poly: &[Vec2]) -> f64 {
        let t = self.trace;
        match (t.value(channels::ANGLE.name, step, v), poly) {
            (Some(a), _) if a.is_finite() => a,
            (_, [nw, ne, se, sw]) => {
                let d = (*ne - *nw) + (*se - *sw);
                d.y.atan2(d.x)
            }
            _ => 0.0,
        }
    }
}

/// The closed path through a polygon's corners in pixels (`None` for an empty polygon).
fn closed_path(poly: &[Vec2], px: impl Fn(Vec2) -> (f32, f32)) -> Option<tiny_skia::Path> {
    let (&first, rest) = poly.split_first()?;
    let mut pb = PathBuilder::new();
    let (x, y) = px(first);
    pb.move_to(x, y);
    for &p in rest {
        let (x, y) = px(p);
        pb.line_to(x, y);
    }
    pb.close();
    pb.finish()
}

/// Mean of the polygon's corners.
fn center(poly: &[Vec2]) -> Vec2 {
    poly.iter().fold(Vec2::ZERO, |acc, &p| acc + p) / poly.len().max(1) as f64
}

/// Unsigned (shoelace) area of the polygon.
fn area(poly: &[Vec2]) -> f64 {
    let n = poly.len();
    let mut twice = 0.0;
    for i in 0..n {
        twice += poly[i].cross(poly[(i + 1) % n]);
    }
    (twice / 2.0).abs()
}

/// A pie slice centred on `c` (world), from world angle `a0` to `a1` (counter-clockwise).
fn sector(c: Vec2, radius: f64, a0: f64, a1: f64, px: impl Fn(Vec2) -> (f32, f32)) -> Option<tiny_skia::Path> {
    if radius.is_nan() || radius <= 0.0 {
        return None;
    }
    let segments = ((a1 - a0).abs() / (PI / 24.0)).ceil().max(2.0) as usize;
    let mut pb = PathBuilder::new();
    let (x, y) = px(c);
    pb.move_to(x, y);
    for s in 0..=segments {
        let a = a0 + (a1 - a0) * s as f64 / segments as f64;
        let (x, y) = px(c + Vec2::new(a.cos(), a.sin()) * radius);
        pb.line_to(x, y);
    }
    pb.close();
    pb.finish()
}

/// The part of a polyline (increasing x) spanning [x0, x1], cut by interpolation at both ends.
fn clip_polyline(pts: &[Vec2], x0: f64, x1: f64) -> Vec<Vec2> {
    let lerp_at = |a: Vec2, b: Vec2, x: f64| {
        let t = if b.x != a.x { (x - a.x) / (b.x - a.x) } else { 0.0 };
        Vec2::new(x, a.y + (b.y - a.y) * t)
    };
    let mut out: Vec<Vec2> = Vec::new();
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b.x < x0 || a.x > x1 {
            continue;
        }
        let start = if a.x < x0 { lerp_at(a, b, x0) } else { a };
        let end = if b.x > x1 { lerp_at(a, b, x1) } else { b };
        if out.last() != Some(&start) {
            out.push(start);
        }
        out.push(end);
    }
    out
}

/// Draws step `step` of `trace` (clamped to the last step; an empty trace gives the background
/// only). Sizes outside 1..=[`MAX_SIDE`] are clamped.
pub fn render_frame(trace: &Trace, step: usize, opts: &RenderOptions) -> Pixmap {
    let scene = Scene::new(trace, opts, true);
    let mut pm = scene.new_pixmap();
    scene.draw(step, &mut pm);
    pm
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::*;
    use vsrlab_tasks::Probe;

    fn rgb(pm: &Pixmap, x: u32, y: u32) -> [u8; 3] {
        let c = pm.pixel(x, y).expect("inside");
        assert_eq!(c.alpha(), 255, "frames are opaque");
        [c.red(), c.green(), c.blue()]
    }

    /// Pixel at the world point `p` in the frame drawn at `step`.
    fn at(t: &Trace, step: usize, opts: &RenderOptions, pm: &Pixmap, p: Vec2) -> [u8; 3] {
        let (x, y) = crate::camera_view(t, step, opts).to_pixel(p, opts.width);
        rgb(pm, x as u32, y as u32)
    }

    fn plain() -> RenderOptions {
        RenderOptions {
            draw_sensors: false,
            draw_lidar: false,
            draw_overlay: false,
            draw_ticks: false,
            draw_legend: false,
            ..RenderOptions::default()
        }
    }

    #[test]
    fn area_colors_are_piecewise_linear() {
        assert_eq!(area_color(0.5), RED);
        assert_eq!(area_color(0.75), RED);
        assert_eq!(area_color(1.0), YELLOW);
        assert_eq!(area_color(1.25), GREEN);
        assert_eq!(area_color(2.0), GREEN);
        assert_eq!(area_color(0.875), [255, 128, 0, 128]);
        assert_eq!(area_color(1.125), [128, 255, 0, 128]);
        assert_eq!(area_color(f64::NAN), YELLOW);
    }

    #[test]
    fn a_kind_colours_its_units_with_unit_fill() {
        let opts = plain();
        let mid = Vec2::new(11.5, 6.5);
        let mut t = square_trace(0.75);
        t.fixed(&channels::UNIT_FILL, 1, &[f64::from(0x2060d0)]);
        let pm = render_frame(&t, 0, &opts);
        assert_eq!(
            at(&t, 0, &opts, &pm, mid),
            [0x20, 0x60, 0xd0],
            "the kind's colour, opaque"
        );
        assert_eq!(packed_rgb(f64::NAN), [0, 0, 0, 255]);
        assert_eq!(packed_rgb(1e12), [255, 255, 255, 255]);
    }

    #[test]
    fn fill_follows_area_ratio() {
        let opts = plain();
        let mid = Vec2::new(11.5, 6.5);
        for (ratio, expect) in [(1.0, [255, 255, 128]), (0.75, [255, 128, 128]), (1.25, [128, 255, 128])] {
            let t = square_trace(ratio);
            let pm = render_frame(&t, 0, &opts);
            let c = at(&t, 0, &opts, &pm, mid);
            for i in 0..3 {
                assert!(
                    (i32::from(c[i]) - expect[i]).abs() <= 2,
                    "ratio {ratio}: got {c:?}, want {expect:?}"
                );
            }
        }
    }

    #[test]
    fn broken_voxels_turn_grey_from_the_damage_on() {
        let opts = plain();
        let mut t = moving_square(3, 0.0);
        t.damage = Some(vsrlab_tasks::DamageRecord {
            time: t.times[1],
            broken: vec![true],
        });
        // off the cross (which runs corner to corner), inside the voxel
        let p = Vec2::new(11.5, 5.6);
        let before = at(&t, 0, &opts, &render_frame(&t, 0, &opts), p);
        let after = at(&t, 2, &opts, &render_frame(&t, 2, &opts), p);
        assert!(
            before[0] > 250 && before[1] > 250 && before[2] < 140,
            "intact: the area colour, got {before:?}"
        );
        assert!(
            after[0] == after[1] && after[1] == after[2] && after[0] < 160,
            "broken: grey, got {after:?}"
        );
    }

    #[test]
    fn ground_background_and_outline_are_where_expected() {
        let opts = plain();
        let t = square_trace(1.0);
        let pm = render_frame(&t, 0, &opts);
        // below the terrain line (y = 5): grey ground
        assert_eq!(at(&t, 0, &opts, &pm, Vec2::new(9.0, 4.7)), [180, 180, 180]);
        assert_eq!(at(&t, 0, &opts, &pm, Vec2::new(14.0, 4.4)), [180, 180, 180]);
        // above the ground, away from the robot: background
        assert_eq!(at(&t, 0, &opts, &pm, Vec2::new(8.0, 7.5)), [255, 255, 255]);
        assert_eq!(at(&t, 0, &opts, &pm, Vec2::new(14.5, 8.5)), [255, 255, 255]);
        // the voxel's left edge (x = 10) is blue
        let view = crate::camera_view(&t, 0, &opts);
        let (x, y) = view.to_pixel(Vec2::new(10.0, 7.0), opts.width);
        let near: Vec<[u8; 3]> = (-1..=1).map(|dx| rgb(&pm, (x as i32 + dx) as u32, y as u32)).collect();
        assert!(
            near.iter().any(|c| c[2] > 200 && c[0] < 100 && c[1] < 100),
            "no blue outline near x=10: {near:?}"
        );
        // world y is up: the top of the image is sky, the bottom rows are ground
        assert_eq!(rgb(&pm, 320, 20), [255, 255, 255]);
        assert_eq!(rgb(&pm, 320, 355), [180, 180, 180]);
    }

    #[test]
    fn robot_stays_in_frame_when_far_right() {
        let opts = plain();
        // 10 s at 100 units/s: ends near x = 1000, with 200 units of history in the camera window
        let t = moving_square(601, 100.0);
        let last = t.len() - 1;
        let poly = t.polygons_at(last).first().unwrap().to_vec();
        assert!(poly[0].x > 990.0);
        let pm = render_frame(&t, last, &opts);
        let c = at(&t, last, &opts, &pm, center(&poly));
        assert!(
            c[0] > 200 && c[1] > 200 && c[2] < 180,
            "voxel not drawn where it is: {c:?}"
        );
        assert_eq!(
            at(&t, last, &opts, &pm, center(&poly) - Vec2::new(0.0, 4.0)),
            [180, 180, 180]
        );

        // moves to x = 1000 in 5 s, then stays for 3 s: the camera closes in on it again
        let xs: Vec<f64> = (0..481).map(|k| 10.0 + 200.0 * (k as f64 / 60.0).min(5.0)).collect();
        let t = trace_from_positions(&xs);
        let last = t.len() - 1;
        let pm = render_frame(&t, last, &opts);
        let yellow = pm
            .pixels()
            .iter()
            .filter(|c| c.red() > 240 && c.green() > 240 && c.blue() < 160)
            .count();
        // 3×3 voxel at 80 px per unit: about 240×240 pixels
        assert!(yellow > 40_000, "only {yellow} voxel pixels");
        let mut t2 = t.clone();
        t2.outlines.iter_mut().for_each(|q| q.x -= 500.0);
        let pm2 = render_frame(&t2, last, &opts);
        let worst = pm.data().iter().zip(pm2.data()).map(|(a, b)| a.abs_diff(*b)).max();
        assert!(
            worst <= Some(3),
            "the camera does not follow the robot: pixels differ by {worst:?}"
        );
    }

    #[test]
    fn touching_voxel_gets_dark_outline() {
        let opts = plain();
        let mut t = square_trace(1.0);
        let view = crate::camera_view(&t, 0, &opts);
        let (x, y) = view.to_pixel(Vec2::new(10.0, 7.0), opts.width);
        let pm = render_frame(&t, 0, &opts);
        let before = rgb(&pm, x as u32, y as u32);
        t.values_mut("touch")[0] = 1.0;
        let pm = render_frame(&t, 0, &opts);
        let after = rgb(&pm, x as u32, y as u32);
        assert!(after[2] < before[2], "{before:?} -> {after:?}");
    }

    #[test]
    fn sensor_sectors_darken_the_upper_half_by_value() {
        let mut t = square_trace(1.0);
        t.fixed(&channels::READINGS_PER_UNIT, 1, &[2.0]);
        t.step(&channels::READINGS, &[1.0, 0.0]); // first sector (to the right of up) full, second empty
        let opts = RenderOptions {
            draw_lidar: false,
            ..RenderOptions::default()
        };
        let pm = render_frame(&t, 0, &opts);
        // voxel centre (11.5, 6.5), radius 1.5: the first sector spans angles 0..π/2 (upper right)
        let upper_right = at(&t, 0, &opts, &pm, Vec2::new(12.1, 7.1));
        let upper_left = at(&t, 0, &opts, &pm, Vec2::new(10.9, 7.1));
        let lower_right = at(&t, 0, &opts, &pm, Vec2::new(12.1, 5.9));
        assert!(upper_right[0] < 200, "upper right not darkened: {upper_right:?}");
        assert!(upper_left[0] > 240, "upper left darkened: {upper_left:?}");
        assert!(lower_right[0] > 240, "lower half darkened: {lower_right:?}");
        // turned by the voxel angle: at angle π the half-disk points down
        t.values_mut("angle")[0] = PI;
        let pm = render_frame(&t, 0, &opts);
        let lower_left = at(&t, 0, &opts, &pm, Vec2::new(10.9, 5.9));
        assert!(lower_left[0] < 200, "rotated sector missing: {lower_left:?}");
        assert!(at(&t, 0, &opts, &pm, Vec2::new(12.1, 7.1))[0] > 240);
    }

    #[test]
    fn lidar_ray_stops_at_hit() {
        let mut t = square_trace(1.0);
        // one ray pointing straight down (relative to angle 0), range 10, hit at 1.0
        t.fixed(&channels::RAYS, 3, &[0.0, -PI / 2.0, 10.0]);
        t.step(&channels::LIDAR, &[1.0]);
        let opts = RenderOptions {
            draw_sensors: false,
            ..RenderOptions::default()
        };
        let view = crate::camera_view(&t, 0, &opts);
        let red_near = |pm: &Pixmap, p: Vec2| {
            let (x, y) = view.to_pixel(p, opts.width);
            (-1..=1).any(|dx| {
                let c = rgb(pm, (x as i32 + dx) as u32, y as u32);
                c[0] > 200 && c[1] < 170 && c[2] < 140
            })
        };
        let pm = render_frame(&t, 0, &opts);
        assert!(red_near(&pm, Vec2::new(11.5, 6.0)), "ray missing");
        assert!(red_near(&pm, Vec2::new(11.75, 5.5)), "hit circle missing");
        assert!(!red_near(&pm, Vec2::new(11.5, 5.1)), "ray drawn past the hit");
        assert!(!red_near(&pm, Vec2::new(11.5, 4.5)), "ray drawn past the hit");
        // no hit: the full range is drawn
        t.values_mut("lidar")[0] = 10.0;
        let pm = render_frame(&t, 0, &opts);
        assert!(red_near(&pm, Vec2::new(11.5, 4.5)), "full-range ray missing");
        assert!(!red_near(&pm, Vec2::new(11.75, 5.5)), "hit circle drawn without a hit");
        // lidar off: nothing red
        let pm = render_frame(
            &t,
            0,
            &RenderOptions {
                draw_lidar: false,
                ..opts.clone()
            },
        );
        assert!(!red_near(&pm, Vec2::new(11.5, 6.0)));
    }

    #[test]
    fn clipping_interpolates_at_the_ends() {
        let pts = [
            Vec2::new(0.0, 100.0),
            Vec2::new(10.0, 0.0),
            Vec2::new(1990.0, 0.0),
            Vec2::new(2000.0, 100.0),
        ];
        let c = clip_polyline(&pts, 5.0, 50.0);
        assert_eq!(
            c,
            vec![Vec2::new(5.0, 50.0), Vec2::new(10.0, 0.0), Vec2::new(50.0, 0.0)]
        );
        assert!(clip_polyline(&pts, 3000.0, 3100.0).is_empty());
    }

    #[test]
    fn malformed_traces_do_not_panic() {
        let mut t = square_trace(1.0);
        t.channels.clear();
        t.fixed(&channels::READINGS_PER_UNIT, 1, &[3.0]);
        t.fixed(&channels::RAYS, 3, &[7.0, 0.0, f64::INFINITY]);
        t.fixed(&channels::GRAPH_NEURONS, 2, &[9.0, 1.0]);
        t.fixed(&channels::GRAPH_EDGES, 3, &[0.0, 5.0, 1.0]);
        t.fixed(&channels::ATTENTION_SIDE, 1, &[4.0]);
        t.step(&channels::ATTENTION, &[0.5]);
        t.outlines[2] = Vec2::new(f64::NAN, 1.0);
        // a frame of the asked size comes back, drawn as far as the trace allows
        let pm = render_frame(&t, 10, &RenderOptions::default());
        assert_eq!((pm.width(), pm.height()), (640, 360));
        assert!(pm
            .pixels()
            .iter()
            .any(|p| p.demultiply() != pm.pixels()[0].demultiply()));
        // sizes of 0 are clamped to one pixel rather than failing
        let pm = render_frame(
            &Trace::default(),
            0,
            &RenderOptions {
                width: 0,
                height: 0,
                ..Default::default()
            },
        );
        assert_eq!((pm.width(), pm.height()), (1, 1));
    }
}
