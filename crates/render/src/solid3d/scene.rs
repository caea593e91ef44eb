//! A 3D episode ready to draw: what does not change between frames (colours, fixed voxels,
//! framing), and the drawing of one step.

use super::camera::Camera;
use super::cube::Cube;
use super::floor::Floor;
use super::painter::{self, Face};
use super::quat::Quat;
use super::shading::{self, FIXED_VOXEL, TOUCH_BORDER, VOTE_IMPASSABLE, VOTE_PASSABLE};
use super::vec3::Vec3;
use crate::draw::{packed_rgb, Rgba};
use crate::RenderOptions;
use tiny_skia::Pixmap;
use vsrlab_tasks::{channels, Trace};

/// Everything about a 3D trace that does not change from frame to frame.
pub(crate) struct SolidScene<'a> {
    trace: &'a Trace,
    width: u32,
    height: u32,
    anti_alias: bool,
    /// The lattice's voxel edge (m).
    side: f64,
    /// Number of moving voxels.
    voxels: usize,
    /// Each voxel's fill (channel `unit_fill`), where given.
    fills: Vec<Rgba>,
    /// Whether voxels are coloured by their votes (channel `vote`).
    votes: bool,
    /// Whether voxels that touch another are bordered (channel `touch`).
    touch: bool,
    /// Whether to write the votes' count at the top right.
    legend: bool,
    /// Centres of the voxels that never move.
    fixed: Vec<Vec3>,
    /// How far the camera stays from the body's centre.
    distance: f64,
    /// Height the camera looks at: half the body's height above the floor.
    target_z: f64,
    floor: Floor,
}

/// Whether `trace` is a 3D one (it records voxel centres in 3D).
pub(crate) fn is_solid(trace: &Trace) -> bool {
    trace.has(channels::VOXEL_XYZ.name)
}

/// Whether a 3D trace has the centres of at least one voxel at every step.
pub(crate) fn has_every_step(trace: &Trace) -> bool {
    trace
        .channel(channels::VOXEL_XYZ.name)
        .is_some_and(|c| !c.fixed && c.width >= 3 && c.values.len() >= c.width * trace.len())
}

/// The edge of a trace's lattice, or 1 when it does not say.
fn lattice_side(trace: &Trace) -> f64 {
    if trace.side_length.is_finite() && trace.side_length > 0.0 {
        trace.side_length
    } else {
        1.0
    }
}

/// Finite x, y, z triples of `values`, in order (the others skipped).
fn points(values: &[f64]) -> impl Iterator<Item = Vec3> + '_ {
    values
        .chunks_exact(3)
        .map(|p| Vec3::new(p[0], p[1], p[2]))
        .filter(|p| p.is_finite())
}

/// Smallest box holding `pts`, as (min, max), or `None` without points.
fn bounds(pts: impl Iterator<Item = Vec3>) -> Option<(Vec3, Vec3)> {
    pts.fold(None, |acc, p| {
        let (lo, hi) = acc.unwrap_or((p, p));
        Some((
            Vec3::new(lo.x.min(p.x), lo.y.min(p.y), lo.z.min(p.z)),
            Vec3::new(hi.x.max(p.x), hi.y.max(p.y), hi.z.max(p.z)),
        ))
    })
}

impl<'a> SolidScene<'a> {
    /// Prepares to draw frames of `trace` with `opts` (sizes already clamped), or `None` when
    /// `trace` is not a 3D one.
    pub fn of(trace: &'a Trace, opts: &RenderOptions, anti_alias: bool) -> Option<SolidScene<'a>> {
        if !is_solid(trace) {
            return None;
        }
        let side = lattice_side(trace);
        let floor_z = -side / 2.0;
        let (radius, height) = Self::body_size(trace, side, floor_z);
        let distance = Camera::framing_distance(radius);
        let square = side * (radius / side).round().max(1.0);
        Some(SolidScene {
            trace,
            width: opts.width,
            height: opts.height,
            anti_alias,
            side,
            voxels: trace.channel(channels::VOXEL_XYZ.name).map_or(0, |c| c.width / 3),
            fills: trace
                .fixed_values(channels::UNIT_FILL.name)
                .iter()
                .map(|&c| packed_rgb(c))
                .collect(),
            votes: opts.draw_votes && trace.has(channels::VOTE.name),
            touch: opts.draw_sensors && trace.has(channels::TOUCH.name),
            legend: opts.draw_legend,
            fixed: points(trace.fixed_values(channels::FIXED_VOXELS.name)).collect(),
            distance,
            target_z: floor_z + height / 2.0,
            floor: Floor { z: floor_z, square },
        })
    }

    /// The body's size over the episode: the largest radius of the sphere around its bounding box
    /// (of whole cubes) at any step, and its greatest height above the floor (at least a voxel each).
    fn body_size(trace: &Trace, side: f64, floor_z: f64) -> (f64, f64) {
        let (mut radius, mut height) = (side, side);
        for step in 0..trace.len() {
            let row = trace.at(channels::VOXEL_XYZ.name, step).unwrap_or(&[]);
            if let Some((lo, hi)) = bounds(points(row)) {
                let cube = Vec3::new(side, side, side);
                radius = radius.max((hi - lo + cube).length() / 2.0);
                height = height.max(hi.z + side / 2.0 - floor_z);
            }
        }
        (radius, height)
    }

    /// Centre of the body at `step`: the mean of its voxel centres, else the trace's centre.
    fn body_centre(&self, step: usize) -> Vec3 {
        let row = self.trace.at(channels::VOXEL_XYZ.name, step).unwrap_or(&[]);
        let (sum, n) = points(row).fold((Vec3::default(), 0usize), |(s, n), p| (s + p, n + 1));
        if n > 0 {
            return sum * (1.0 / n as f64);
        }
        match self.trace.centers.get(step) {
            Some(c) if c.x.is_finite() && c.y.is_finite() => Vec3::new(c.x, c.y, self.target_z),
            _ => Vec3::new(0.0, 0.0, self.target_z),
        }
    }

    /// The point the camera looks at during `step`: above the body's centre, at half its height.
    fn target(&self, step: usize) -> Vec3 {
        let c = self.body_centre(step);
        Vec3::new(c.x, c.y, self.target_z)
    }

    /// The camera of `step`, following the body's centre.
    pub fn camera_at(&self, step: usize) -> Camera {
        Camera::looking_at(self.target(step), self.distance, self.width, self.height)
    }

    /// A per-voxel channel's values at `step`, when it has one per voxel.
    fn per_voxel(&self, name: &str, step: usize) -> Option<&'a [f64]> {
        self.trace.at(name, step).filter(|a| a.len() == self.voxels)
    }

    /// The moving voxels at `step` as cubes with their base colours and borders (unusable ones
    /// skipped).
    fn voxel_cubes(&self, step: usize) -> Vec<(Cube, Rgba, Option<Rgba>)> {
        let t = self.trace;
        let xyz = t.at(channels::VOXEL_XYZ.name, step).unwrap_or(&[]);
        let quats = t.at(channels::VOXEL_QUAT.name, step).unwrap_or(&[]);
        let edges = t.at(channels::VOXEL_EDGE.name, step).unwrap_or(&[]);
        let actuation = self.per_voxel(channels::ACTUATION.name, step);
        let votes = self.per_voxel(channels::VOTE.name, step).filter(|_| self.votes);
        let touch = self.per_voxel(channels::TOUCH.name, step).filter(|_| self.touch);
        (0..self.voxels)
            .filter_map(|v| {
                let p = xyz.get(3 * v..3 * v + 3)?;
                let centre = Vec3::new(p[0], p[1], p[2]);
                if !centre.is_finite() {
                    return None;
                }
                let edge = edges.get(v).copied().filter(|e| e.is_finite() && *e > 0.0);
                let cube = Cube {
                    centre,
                    orientation: Quat::from_slice(quats.get(4 * v..4 * v + 4)),
                    edge: edge.unwrap_or(self.side),
                };
                let color = match votes {
                    Some(votes) => shading::vote_color(votes[v]),
                    None => shading::voxel_color(self.fills.get(v).copied(), actuation.map(|a| a[v])),
                };
                let border = touch.filter(|t| t[v] > 0.5).map(|_| TOUCH_BORDER);
                Some((cube, color, border))
            })
            .collect()
    }

    /// The votes of `step` at the top right: how many voxels vote "passable" and "impassable",
    /// and the collective decision (passable on a tie, as the affordance study counts).
    fn draw_votes_legend(&self, step: usize, pm: &mut Pixmap) {
        let Some(votes) = self.per_voxel(channels::VOTE.name, step) else {
            return;
        };
        let yes = votes.iter().filter(|&&v| v > 0.0).count();
        let no = votes.len() - yes;
        let decision = if yes >= no { "passable" } else { "impassable" };
        let size = crate::overlay::text_size(pm.height()) * 0.85;
        let lines = [
            (format!("{yes} vote passable"), VOTE_PASSABLE),
            (format!("{no} vote impassable"), VOTE_IMPASSABLE),
            (format!("decision: {decision}"), [40, 40, 40, 255]),
        ];
        let widest = lines
            .iter()
            .map(|(l, _)| crate::text::width(l, size))
            .fold(0.0, f32::max);
        let x = pm.width() as f32 - widest - 8.0;
        for (i, (line, [r, g, b, _])) in lines.iter().enumerate() {
            crate::text::draw(pm, line, x, 8.0 + i as f32 * size * 1.3, size, [*r, *g, *b]);
        }
    }

    /// Draws step `step` (clamped to the last one) into `pm`, which must have the frame size:
    /// sky and floor, then every visible face of every cube far to near.
    pub fn draw(&self, step: usize, pm: &mut Pixmap) {
        let step = step.min(self.trace.len().saturating_sub(1));
        let target = self.target(step);
        let camera = self.camera_at(step);
        self.floor.draw(pm, &camera, target, self.distance, self.anti_alias);
        let fixed = self.fixed.iter().map(|&centre| {
            let cube = Cube {
                centre,
                orientation: Quat::IDENTITY,
                edge: self.side,
            };
            (cube, FIXED_VOXEL)
        });
        let mut faces: Vec<Face> = self
            .voxel_cubes(step)
            .into_iter()
            .chain(fixed.map(|(cube, color)| (cube, color, None)))
            .flat_map(|(cube, color, border)| painter::visible_faces(&cube, color, border, &camera))
            .collect();
        painter::paint_faces(pm, &camera, &mut faces, self.anti_alias);
        if self.votes && self.legend {
            self.draw_votes_legend(step, pm);
        }
    }
}
