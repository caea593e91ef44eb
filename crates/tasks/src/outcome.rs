//! What an episode returns: the task's metrics and fitness values, and optionally a per-step
//! trace.

use crate::task::Metrics;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
pub use vsrlab_body::probe::ReplayMode;
use vsrlab_body::{Channel, Probe};
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

/// Per-step record of an episode: a small core that every robot kind has (time, centre, outline,
/// damage) plus named channels published by the body, its sensors, its brain and the task
/// ([`vsrlab_body::Probe`]). Arrays indexed `[step][…]` are stored flat, step-major.
///
/// The body's outline is a list of polygons with any number of corners each
/// ([`Trace::outline_corners`], the same at every step). Per-unit channels (area ratio, touch,
/// actuation, …) have one value per outline polygon and step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Trace {
    /// Time step (s).
    pub dt: f64,
    /// Typical size of the body's parts (a voxel's side), for drawing.
    pub side_length: f64,
    /// Terrain polyline.
    pub terrain: Vec<Vec2>,
    /// Time of each recorded step.
    pub times: Vec<f64>,
    /// Robot centre at each step.
    pub centers: Vec<Vec2>,
    /// Corner count of each outline polygon (a voxel: 4, NW, NE, SE, SW).
    pub outline_corners: Vec<usize>,
    /// Outline corners, `[step][polygon][corner]`.
    pub outlines: Vec<Vec2>,
    /// When units broke and which ([`crate::Damage`]); absent without damage.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damage: Option<DamageRecord>,
    /// Everything else, by channel name.
    pub channels: BTreeMap<String, Recorded>,
}

/// One channel of a trace: per-step values (`width` per recorded step) or fixed values
/// (`width` per row, recorded once).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Recorded {
    /// Whether the values hold for the whole episode (recorded once).
    pub fixed: bool,
    /// Values per step (per row, for a fixed channel).
    pub width: usize,
    /// How replays keep it.
    pub replay: ReplayMode,
    /// What replays write for a non-finite value.
    pub fallback: f64,
    /// The values, step-major.
    pub values: Vec<f64>,
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

impl Probe for Trace {
    fn step(&mut self, channel: &Channel, values: &[f64]) {
        self.step_from(channel, &mut values.iter().copied());
    }

    fn step_from(&mut self, channel: &Channel, values: &mut dyn Iterator<Item = f64>) {
        if !channel.traced {
            return;
        }
        let (recorded, first) = match self.channels.get_mut(channel.name) {
            Some(r) => (r, false),
            None => {
                let r = Recorded::new(channel, false, 0);
                (self.channels.entry(channel.name.to_string()).or_insert(r), true)
            }
        };
        let before = recorded.values.len();
        if channel.single {
            recorded.values.extend(values.map(|v| f64::from(v as f32)));
        } else {
            recorded.values.extend(values);
        }
        if first {
            recorded.width = recorded.values.len() - before;
        }
    }

    fn fixed(&mut self, channel: &Channel, width: usize, values: &[f64]) {
        if channel.traced {
            let mut recorded = Recorded::new(channel, true, width);
            recorded.values = values.to_vec();
            self.channels.insert(channel.name.to_string(), recorded);
        }
    }
}

impl Recorded {
    fn new(channel: &Channel, fixed: bool, width: usize) -> Recorded {
        Recorded {
            fixed,
            width,
            replay: channel.replay,
            fallback: channel.fallback,
            values: Vec::new(),
        }
    }

    /// The values of recorded step `step` (of row `step` for a fixed channel), if recorded.
    pub fn row(&self, step: usize) -> Option<&[f64]> {
        self.values.get(step * self.width..(step + 1) * self.width)
    }

    /// The rows of a fixed channel (or the steps of a per-step one), in order.
    pub fn rows(&self) -> impl Iterator<Item = &[f64]> {
        self.values.chunks(self.width.max(1))
    }
}

impl Trace {
    /// The channel called `name`, if recorded.
    pub fn channel(&self, name: &str) -> Option<&Recorded> {
        self.channels.get(name)
    }

    /// Whether a channel called `name` was recorded.
    pub fn has(&self, name: &str) -> bool {
        self.channels.contains_key(name)
    }

    /// The values of per-step channel `name` at recorded step `step`, if recorded.
    pub fn at(&self, name: &str, step: usize) -> Option<&[f64]> {
        self.channel(name)?.row(step)
    }

    /// Value `i` of per-step channel `name` at recorded step `step`, if recorded.
    pub fn value(&self, name: &str, step: usize, i: usize) -> Option<f64> {
        self.at(name, step)?.get(i).copied()
    }

    /// Every value of channel `name`, step-major (empty when not recorded).
    pub fn values(&self, name: &str) -> &[f64] {
        self.channel(name).map_or(&[], |c| &c.values)
    }

    /// Every value of channel `name`, to edit (empty when not recorded): for synthetic traces.
    pub fn values_mut(&mut self, name: &str) -> &mut [f64] {
        self.channels.get_mut(name).map_or(&mut [], |c| &mut c.values)
    }

    /// The values of fixed channel `name` (empty when not recorded).
    pub fn fixed_values(&self, name: &str) -> &[f64] {
        self.values(name)
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
    /// Number of units: the outline's polygons (a voxel each; a PSA's membrane and masses).
    pub fn units(&self) -> usize {
        self.outline_corners.len()
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
    fn channels_are_kept_per_step_or_once_and_untraced_ones_are_not() {
        const A: Channel = Channel::replayed("a", 1e-3);
        const S: Channel = Channel::replayed("s", 1e-3).single();
        const F: Channel = Channel::traced("f");
        const U: Channel = Channel::traced("u").untraced();
        let mut trace = Trace::default();
        trace.fixed(&F, 2, &[1.0, 2.0, 3.0, 4.0]);
        for k in 0..3 {
            let k = k as f64;
            trace.step(&A, &[k, 10.0 * k]);
            trace.step(&S, &[0.1 + k]);
            trace.step(&U, &[k]);
        }
        assert_eq!(trace.at("a", 2), Some(&[2.0, 20.0][..]));
        assert_eq!(trace.value("a", 1, 1), Some(10.0));
        assert_eq!(trace.at("a", 3), None);
        assert_eq!(trace.value("s", 0, 0), Some(f64::from(0.1f32)));
        assert_eq!(trace.fixed_values("f"), [1.0, 2.0, 3.0, 4.0]);
        assert_eq!(trace.channel("f").unwrap().rows().count(), 2);
        assert!(!trace.has("u"));
        assert!(!trace.has("nothing"));
    }

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
