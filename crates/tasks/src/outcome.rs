//! What an episode returns: the task's metrics and fitness values, and optionally a per-step
//! trace.

use crate::task::Metrics;
use serde::{Deserialize, Serialize};
use vsrlab_physics::Vec2;

/// How much of an episode to record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum TraceLevel {
    /// Only the summary figures (fastest; what evolution uses).
    #[default]
    None,
    /// Also the robot's centre at every step.
    Center,
    /// Everything needed to draw or analyse the episode.
    Full,
}

/// The result of one episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Named figures the task measured (locomotion: `distance`, `velocity`, `elapsed`).
    pub metrics: Metrics,
    /// The task's fitness values, one per objective, in order.
    pub fitness: Vec<f64>,
    /// Number of physics steps simulated.
    pub steps: u64,
    /// Number of actuated units of the robot (voxels of a VSR).
    pub units: usize,
    /// Per-step record, when asked for.
    pub trace: Option<Trace>,
}

impl Outcome {
    /// The metric called `name`, or NaN when the task does not report it.
    pub fn metric(&self, name: &str) -> f64 {
        self.metrics.get(name).copied().unwrap_or(f64::NAN)
    }
}

/// A lidar ray of one voxel: direction relative to the voxel angle, and its range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RayInfo {
    /// Index of the voxel (grid order).
    pub voxel: usize,
    /// Direction relative to the voxel's angle (radians).
    pub relative_angle: f64,
    /// Maximum distance.
    pub range: f64,
}

/// Per-step record of an episode. Arrays indexed `[step][unit]` are stored flat, step-major.
///
/// The body's outline is a list of polygons with any number of corners each
/// ([`Trace::outline_corners`], the same at every step); per-unit arrays (area ratios, touch,
/// actuations, readings) have one entry per sensing unit (voxel) and step, and stay empty for
/// bodies that have no such units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Trace {
    /// Time step (s).
    pub dt: f64,
    /// Typical size of the body's parts (a voxel's side), for drawing.
    pub side_length: f64,
    /// Terrain polyline.
    pub terrain: Vec<Vec2>,
    /// Grid cell of each voxel (grid order); empty for bodies that are not grids.
    pub cells: Vec<(usize, usize)>,
    /// Time of each recorded step.
    pub times: Vec<f64>,
    /// Robot centre at each step.
    pub centers: Vec<Vec2>,
    /// Corner count of each outline polygon (a voxel: 4, NW, NE, SE, SW).
    pub outline_corners: Vec<usize>,
    /// Outline corners, `[step][polygon][corner]`.
    pub outlines: Vec<Vec2>,
    /// Area ratios, `[step][unit]`.
    pub area_ratios: Vec<f64>,
    /// Unit angles, `[step][unit]`.
    pub angles: Vec<f64>,
    /// Touch flags, `[step][unit]`.
    pub touching: Vec<bool>,
    /// Actuation applied after sensing, `[step][unit]`.
    pub actuations: Vec<f64>,
    /// Number of sensor readings of each unit.
    pub readings_per_voxel: Vec<usize>,
    /// Sensor readings scaled to [0, 1] by each reading's domain, `[step][reading]`.
    pub readings: Vec<f32>,
    /// The lidar rays, in order.
    pub rays: Vec<RayInfo>,
    /// Lidar distances, `[step][ray]`.
    pub ray_distances: Vec<f32>,
    /// Side r of each unit's attention matrix (attention brains; 0 otherwise).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub attention_side: usize,
    /// Attention matrices, `[step][unit][r][r]` (attention brains; empty otherwise).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attention: Vec<f32>,
    /// A graph brain's neurons: each one's unit and kind (0 sensing, 1 hidden, 2 actuator);
    /// empty for other brains.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub graph_neurons: Vec<(usize, u8)>,
    /// A graph brain's edges: (source, target, weight).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub graph_edges: Vec<(usize, usize, f32)>,
    /// A graph brain's neuron outputs, `[step][neuron]`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub graph_outputs: Vec<f32>,
    /// Static polygons besides the ground (a cage), for drawing.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub obstacles: Vec<Vec<Vec2>>,
    /// Radius of each loose ball of the world.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub object_radii: Vec<f64>,
    /// Each ball's centre and angle, `[step][ball]`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<(Vec2, f64)>,
    /// A pressurised body's pressure over its largest pressure, `[step]` (PSAs; empty otherwise).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pressures: Vec<f32>,
    /// When units broke and which ([`crate::Damage`]); absent without damage.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damage: Option<DamageRecord>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// The damage that happened during an episode: from `time` on, the units marked in `broken` do
/// not actuate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DamageRecord {
    /// Simulated time (s) of the first step without their actuation.
    pub time: f64,
    /// One flag per unit (grid order for voxels).
    pub broken: Vec<bool>,
}

impl Trace {
    /// Unit `unit`'s attention matrix at recorded step `step` (r·r values, row-major), if recorded.
    pub fn attention_at(&self, step: usize, unit: usize) -> Option<&[f32]> {
        let r2 = self.attention_side * self.attention_side;
        let start = (step * self.voxels() + unit) * r2;
        (r2 > 0).then(|| self.attention.get(start..start + r2)).flatten()
    }

    /// A graph brain's neuron outputs at recorded step `step`, if recorded.
    pub fn graph_outputs_at(&self, step: usize) -> Option<&[f32]> {
        let n = self.graph_neurons.len();
        (n > 0)
            .then(|| self.graph_outputs.get(step * n..(step + 1) * n))
            .flatten()
    }

    /// Whether unit `unit` is broken at recorded step `step`.
    pub fn is_broken(&self, step: usize, unit: usize) -> bool {
        match (&self.damage, self.times.get(step)) {
            (Some(d), Some(&t)) => t >= d.time && d.broken.get(unit).copied().unwrap_or(false),
            _ => false,
        }
    }
}

/// The outline polygons of one step (see [`Trace::polygons_at`]).
#[derive(Debug, Clone, Copy)]
pub struct Polygons<'a> {
    corners: &'a [usize],
    points: &'a [Vec2],
}

impl<'a> Polygons<'a> {
    /// Number of polygons (zero when the step was not recorded).
    pub fn len(&self) -> usize {
        if self.points.is_empty() {
            0
        } else {
            self.corners.len()
        }
    }
    /// Whether there is no polygon.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The polygons, in order.
    pub fn iter(&self) -> impl Iterator<Item = &'a [Vec2]> + 'a {
        let points = self.points;
        let corners = if points.is_empty() { &[][..] } else { self.corners };
        corners.iter().scan(0usize, move |start, &n| {
            let polygon = &points[*start..*start + n];
            *start += n;
            Some(polygon)
        })
    }
    /// Polygon `i`, if any.
    pub fn get(&self, i: usize) -> Option<&'a [Vec2]> {
        self.iter().nth(i)
    }
    /// The first polygon, if any.
    pub fn first(&self) -> Option<&'a [Vec2]> {
        self.get(0)
    }
    /// Every corner of every polygon.
    pub fn points(&self) -> &'a [Vec2] {
        self.points
    }
}

impl Trace {
    /// Number of recorded steps.
    pub fn len(&self) -> usize {
        self.times.len()
    }
    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }
    /// Number of sensing units (voxels).
    pub fn voxels(&self) -> usize {
        self.cells.len()
    }
    /// Corners per step: the sum of [`Trace::outline_corners`].
    pub fn corners_per_step(&self) -> usize {
        self.outline_corners.iter().sum()
    }
    /// The outline polygons at step `k` (empty when step `k` holds no outline).
    pub fn polygons_at(&self, k: usize) -> Polygons<'_> {
        let n = self.corners_per_step();
        Polygons {
            corners: &self.outline_corners,
            points: self.outlines.get(k * n..(k + 1) * n).unwrap_or(&[]),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygons_of_any_corner_count_are_cut_per_step() {
        let p = |x: f64| Vec2::new(x, 0.0);
        let trace = Trace {
            outline_corners: vec![3, 4],
            outlines: (0..14).map(|i| p(i as f64)).collect(),
            ..Default::default()
        };
        assert_eq!(trace.corners_per_step(), 7);
        let second = trace.polygons_at(1);
        assert_eq!(second.len(), 2);
        assert_eq!(second.first().unwrap(), &[p(7.0), p(8.0), p(9.0)]);
        assert_eq!(second.get(1).unwrap().len(), 4);
        assert_eq!(second.get(1).unwrap()[3], p(13.0));
        assert!(trace.polygons_at(2).is_empty());
        assert_eq!(trace.polygons_at(2).iter().count(), 0);
    }
}
