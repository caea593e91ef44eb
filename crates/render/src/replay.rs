//! Replay files: an episode's [`Trace`] as compact JSON for the browser viewer (docs/viewer.md).
//!
//! JSON, not a binary format, because the page reads it with `JSON.parse` and no decoder, a
//! researcher can open it in any tool, and the compression that matters is done before the text:
//! every per-frame quantity is a [`Channel`] of integers, quantised (positions to a fixed fraction
//! of a voxel side) and delta-coded along time, so a coordinate that moves a little between two
//! frames costs two or three characters. A 30 s biped replay at 30 frames per second is about
//! 0.4 MB.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use vsrlab_physics::Vec2;
use vsrlab_tasks::outcome::ReplayMode;
use vsrlab_tasks::{channels, Trace};

/// The `format` field of every replay file.
pub const FORMAT: &str = "vsrlab-replay";
/// The current version of the replay format.
pub const VERSION: u32 = 1;

/// How a trace becomes a replay.
#[derive(Debug, Clone, PartialEq)]
pub struct ReplayOptions {
    /// Frames per second kept from the trace (steps are picked at a fixed stride; the viewer
    /// interpolates between frames while playing).
    pub fps: f64,
    /// Position resolution as a fraction of the body's part size (a voxel side).
    pub quantum_per_side: f64,
    /// Title shown by the viewer.
    pub title: String,
}

impl Default for ReplayOptions {
    fn default() -> Self {
        ReplayOptions {
            fps: 30.0,
            quantum_per_side: 1.0 / 500.0,
            title: String::new(),
        }
    }
}

/// Errors of replay encoding.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ReplayError {
    /// The trace holds no recorded step.
    #[error("the episode recorded no step (was it simulated with a full trace?)")]
    Empty,
    /// A bad option.
    #[error("{0}")]
    Option(String),
}

/// A replay file's content (docs/viewer.md has the field-by-field description).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Replay {
    /// Always [`FORMAT`].
    pub format: String,
    /// Format version, [`VERSION`].
    pub version: u32,
    /// What is shown (robot file, body, task).
    pub title: String,
    /// Number of frames.
    pub frames: usize,
    /// Simulated time of the first frame (s).
    pub t0: f64,
    /// Simulated time between two frames (s).
    pub frame_dt: f64,
    /// The simulator's time step (s).
    pub step_dt: f64,
    /// Size of the body's parts (a voxel side), world units.
    pub side: f64,
    /// World units per integer of the position channels.
    pub quantum: f64,
    /// The static world.
    pub world: World,
    /// What does not change in the body.
    pub body: Body,
    /// Per-frame quantities by name (see [`Channel`]).
    pub channels: BTreeMap<String, Channel>,
    /// The units that break, and when (damage); absent without damage.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damage: Option<Damage>,
    /// A graph brain's neurons and edges; absent for other brains.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub graph: Option<Graph>,
}

/// The static world: ground, obstacles, the radii of loose balls.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct World {
    /// Terrain polyline, left to right.
    pub terrain: Vec<[f64; 2]>,
    /// Static polygons besides the ground (a cage).
    pub obstacles: Vec<Vec<[f64; 2]>>,
    /// Radius of each loose ball (channels `ball_xy`, `ball_angle`).
    pub balls: Vec<f64>,
    /// Centres (x, y, z; z up) of a 3D world's fixed voxels, each of edge `side` (channels
    /// `voxel_xyz`, `voxel_quat`, `voxel_edge` hold a 3D body).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub fixed_voxels: Vec<[f64; 3]>,
}

/// What does not change in the body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Body {
    /// Grid cell (column, row from the bottom) of each voxel; empty for bodies that are not grids.
    pub cells: Vec<[usize; 2]>,
    /// Corner count of each outline polygon (channel `outline`).
    pub corners: Vec<usize>,
    /// Sensor readings of each voxel (channel `readings`).
    pub readings_per_unit: Vec<usize>,
    /// The lidar rays (channel `lidar`).
    pub rays: Vec<Ray>,
    /// Side of each unit's attention matrix (channel `attention`), 0 without one.
    pub attention_side: usize,
    /// The kind's fill colour of each polygon as `0xRRGGBB` (channel `unit_fill`); empty: coloured
    /// by area ratio.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unit_fill: Vec<u32>,
}

/// A lidar ray: the voxel it starts from, its direction relative to the voxel, its range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Ray {
    /// Voxel index.
    pub unit: usize,
    /// Direction relative to the voxel's angle (radians).
    pub angle: f64,
    /// Maximum distance.
    pub range: f64,
}

/// Units broken from `time` on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Damage {
    /// Simulated time (s).
    pub time: f64,
    /// One flag per unit.
    pub broken: Vec<bool>,
}

/// A graph brain's structure: each neuron's unit and kind (0 sensing, 1 hidden, 2 actuator), and
/// its edges (source, target, weight).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Graph {
    /// `[unit, kind]` of each neuron.
    pub neurons: Vec<[usize; 2]>,
    /// `[source, target, weight]` of each edge.
    pub edges: Vec<(usize, usize, f32)>,
}

/// A quantity with `per_frame` values per frame, stored as integers: value `i` of frame `k` is
/// `scale` times the sum of `data[j·per_frame + i]` for j = 0…k (frame 0 absolute, then
/// differences from the previous frame).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Channel {
    /// Values per frame.
    pub per_frame: usize,
    /// Value of one integer step.
    pub scale: f64,
    /// Delta-coded integers, frame-major.
    pub data: Vec<i64>,
}

impl Channel {
    /// Quantises and delta-codes `values` (frame-major, `per_frame` each); non-finite values
    /// become `fallback`.
    fn encode(values: &[f64], per_frame: usize, scale: f64, fallback: f64) -> Channel {
        let mut data = Vec::with_capacity(values.len());
        let mut previous = vec![0i64; per_frame];
        for (j, &v) in values.iter().enumerate() {
            let v = if v.is_finite() { v } else { fallback };
            let q = (v / scale).round() as i64;
            let slot = &mut previous[j % per_frame];
            data.push(q - *slot);
            *slot = q;
        }
        Channel { per_frame, scale, data }
    }

    /// The decoded values, frame-major (for tests and tools; the page decodes the same way).
    pub fn decode(&self) -> Vec<f64> {
        let mut sums = vec![0i64; self.per_frame.max(1)];
        self.data
            .iter()
            .enumerate()
            .map(|(j, &d)| {
                let slot = &mut sums[j % self.per_frame.max(1)];
                *slot += d;
                *slot as f64 * self.scale
            })
            .collect()
    }
}

/// The recorded steps kept as frames: every `stride`-th.
fn strided_steps(trace: &Trace, fps: f64) -> (Vec<usize>, usize) {
    let dt = if trace.dt > 0.0 { trace.dt } else { 1.0 / 60.0 };
    let stride = ((1.0 / (fps * dt)).round() as usize).max(1);
    ((0..trace.len()).step_by(stride).collect(), stride)
}

/// The channels of a replay being built: each from a step-major trace array, at the kept steps.
struct Channels<'a> {
    steps: &'a [usize],
    map: BTreeMap<String, Channel>,
}

impl Channels<'_> {
    /// Adds channel `name` from `values` (`per_step` entries per recorded step), each entry
    /// giving `W` numbers through `to`; rows the trace lacks become `fallback`. Nothing is added
    /// for an empty array.
    fn add<T: Copy, const W: usize>(
        &mut self,
        name: &str,
        values: &[T],
        per_step: usize,
        (scale, fallback): (f64, f64),
        to: impl Fn(T) -> [f64; W],
    ) {
        let per_frame = per_step * W;
        if per_frame == 0 || values.is_empty() {
            return;
        }
        let mut out = Vec::with_capacity(self.steps.len() * per_frame);
        for &k in self.steps {
            match values.get(k * per_step..(k + 1) * per_step) {
                Some(row) => out.extend(row.iter().flat_map(|&v| to(v))),
                None => out.extend(std::iter::repeat_n(f64::NAN, per_frame)),
            }
        }
        self.map
            .insert(name.to_string(), Channel::encode(&out, per_frame, scale, fallback));
    }
}

fn point(p: Vec2) -> [f64; 2] {
    [p.x, p.y]
}

/// Whole numbers of a fixed channel (counts, indices) as integers.
fn counts(values: &[f64]) -> Vec<usize> {
    values.iter().map(|&v| v as usize).collect()
}

/// Each unit's grid cell, or, for a body that is not a grid, its index along x: the viewer keeps
/// one per outline polygon.
fn cells(trace: &Trace) -> Vec<[usize; 2]> {
    match trace.channel(channels::CELLS.name) {
        Some(cells) => cells.rows().map(|c| [c[0] as usize, c[1] as usize]).collect(),
        None => (0..trace.units()).map(|i| [i, 0]).collect(),
    }
}

/// The lidar rays of the fixed channel `rays`: (unit, relative angle, range) rows.
fn rays(trace: &Trace) -> Vec<Ray> {
    let Some(rays) = trace.channel(channels::RAYS.name) else {
        return Vec::new();
    };
    rays.rows()
        .map(|r| Ray {
            unit: r[0] as usize,
            angle: r[1],
            range: r[2],
        })
        .collect()
}

/// A graph brain's neurons and edges, when the trace has them.
fn graph(trace: &Trace) -> Option<Graph> {
    let neurons = trace.channel(channels::GRAPH_NEURONS.name)?;
    let edges = trace.channel(channels::GRAPH_EDGES.name)?;
    (!neurons.values.is_empty()).then(|| Graph {
        neurons: neurons.rows().map(|n| [n[0] as usize, n[1] as usize]).collect(),
        edges: edges
            .rows()
            .map(|e| (e[0] as usize, e[1] as usize, e[2] as f32))
            .collect(),
    })
}

impl Replay {
    /// The replay of a recorded episode.
    pub fn from_trace(trace: &Trace, options: &ReplayOptions) -> Result<Replay, ReplayError> {
        if !(options.fps.is_finite() && options.fps > 0.0) {
            return Err(ReplayError::Option(format!(
                "replay frame rate must be a positive number, got {}",
                options.fps
            )));
        }
        if !(options.quantum_per_side.is_finite() && options.quantum_per_side > 0.0) {
            return Err(ReplayError::Option(format!(
                "replay resolution must be a positive number, got {}",
                options.quantum_per_side
            )));
        }
        if trace.is_empty() {
            return Err(ReplayError::Empty);
        }
        let (steps, stride) = strided_steps(trace, options.fps);
        let side = crate::camera::side(trace);
        let quantum = side * options.quantum_per_side;
        let mut c = Channels {
            steps: &steps,
            map: BTreeMap::new(),
        };
        let position = (quantum, 0.0);
        c.add("outline", &trace.outlines, trace.corners_per_step(), position, point);
        c.add("center", &trace.centers, 1, position, point);
        for (name, recorded) in trace.channels.iter().filter(|(_, r)| !r.fixed) {
            let scale = match recorded.replay {
                ReplayMode::No => continue,
                ReplayMode::Step(scale) => scale,
                ReplayMode::Position => quantum,
            };
            c.add(
                name,
                &recorded.values,
                recorded.width,
                (scale, recorded.fallback),
                |v| [v],
            );
        }
        let channels = c.map;
        let dt = if trace.dt > 0.0 { trace.dt } else { 1.0 / 60.0 };
        Ok(Replay {
            format: FORMAT.to_string(),
            version: VERSION,
            title: options.title.clone(),
            frames: steps.len(),
            t0: trace.times[0],
            frame_dt: dt * stride as f64,
            step_dt: dt,
            side,
            quantum,
            world: World {
                terrain: trace.terrain.iter().map(|&p| point(p)).collect(),
                obstacles: channels::obstacles(trace)
                    .iter()
                    .map(|o| o.iter().map(|&p| point(p)).collect())
                    .collect(),
                balls: trace.fixed_values(channels::BALL_RADII.name).to_vec(),
                fixed_voxels: trace
                    .fixed_values(channels::FIXED_VOXELS.name)
                    .chunks_exact(3)
                    .map(|c| [c[0], c[1], c[2]])
                    .collect(),
            },
            body: Body {
                cells: cells(trace),
                corners: trace.outline_corners.clone(),
                readings_per_unit: counts(trace.fixed_values(channels::READINGS_PER_UNIT.name)),
                rays: rays(trace),
                attention_side: counts(trace.fixed_values(channels::ATTENTION_SIDE.name))
                    .first()
                    .copied()
                    .unwrap_or(0),
                unit_fill: counts(trace.fixed_values(channels::UNIT_FILL.name))
                    .into_iter()
                    .map(|c| c.min(0xff_ffff) as u32)
                    .collect(),
            },
            channels,
            damage: trace.damage.as_ref().map(|d| Damage {
                time: d.time,
                broken: d.broken.clone(),
            }),
            graph: graph(trace),
        })
    }

    /// The replay as compact JSON text.
    pub fn to_json(&self) -> String {
        serde_json::to_string(self).expect("replays serialise")
    }
}

/// Why a replay could not be saved.
#[derive(Debug, thiserror::Error)]
pub enum SaveReplayError {
    /// The trace could not be encoded.
    #[error(transparent)]
    Encode(#[from] ReplayError),
    /// The file could not be written.
    #[error("{}: {source}", path.display())]
    Write {
        /// The replay file.
        path: std::path::PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

/// Writes the replay of `trace` to `path` atomically (temporary file, then rename); returns its
/// size in bytes.
pub fn save_replay(trace: &Trace, options: &ReplayOptions, path: &std::path::Path) -> Result<u64, SaveReplayError> {
    let replay = Replay::from_trace(trace, options)?;
    let text = replay.to_json();
    vsrlab_tasks::files::write_atomic(path, text.as_bytes()).map_err(|source| SaveReplayError::Write {
        path: path.to_path_buf(),
        source,
    })?;
    Ok(text.len() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::moving_square;

    #[test]
    fn channels_decode_to_the_quantised_values() {
        let values = [0.0, 1.0, 0.5, 1.25, 0.75, f64::NAN];
        let c = Channel::encode(&values, 2, 0.25, 9.0);
        assert_eq!(c.data, vec![0, 4, 2, 1, 1, 31]);
        assert_eq!(c.decode(), vec![0.0, 1.0, 0.5, 1.25, 0.75, 9.0]);
    }

    #[test]
    fn a_moving_square_keeps_its_positions_within_the_quantum() {
        let trace = moving_square(61, 3.0);
        let options = ReplayOptions {
            fps: 60.0,
            ..ReplayOptions::default()
        };
        let replay = Replay::from_trace(&trace, &options).unwrap();
        assert_eq!(replay.frames, trace.len());
        let outline = replay.channels["outline"].decode();
        let corners = trace.corners_per_step();
        for k in 0..trace.len() {
            for (i, p) in trace.outlines[k * corners..(k + 1) * corners].iter().enumerate() {
                let j = (k * corners + i) * 2;
                assert!((outline[j] - p.x).abs() <= replay.quantum / 2.0 + 1e-12);
                assert!((outline[j + 1] - p.y).abs() <= replay.quantum / 2.0 + 1e-12);
            }
        }
    }

    #[test]
    fn unit_fill_travels_only_when_the_kind_gives_it() {
        use vsrlab_tasks::Probe;
        let mut trace = moving_square(5, 1.0);
        let plain = Replay::from_trace(&trace, &ReplayOptions::default()).unwrap();
        assert!(
            !plain.to_json().contains("unit_fill"),
            "replays without it are unchanged"
        );
        trace.fixed(&channels::UNIT_FILL, 1, &[f64::from(0x2060d0)]);
        let coloured = Replay::from_trace(&trace, &ReplayOptions::default()).unwrap();
        assert_eq!(coloured.body.unit_fill, vec![0x2060d0]);
        let back: Replay = serde_json::from_str(&coloured.to_json()).unwrap();
        assert_eq!(back.body.unit_fill, vec![0x2060d0]);
    }

    #[test]
    fn frames_are_picked_at_the_requested_rate() {
        let trace = moving_square(61, 3.0);
        let replay = Replay::from_trace(&trace, &ReplayOptions::default()).unwrap();
        assert!((replay.frame_dt - 2.0 * trace.dt).abs() < 1e-12, "{}", replay.frame_dt);
        assert_eq!(replay.frames, trace.len().div_ceil(2));
        let text = replay.to_json();
        let back: Replay = serde_json::from_str(&text).unwrap();
        assert_eq!(back, replay);
    }

    #[test]
    fn empty_traces_and_bad_options_are_refused() {
        assert_eq!(
            Replay::from_trace(&Trace::default(), &ReplayOptions::default()),
            Err(ReplayError::Empty)
        );
        let bad = ReplayOptions {
            fps: 0.0,
            ..ReplayOptions::default()
        };
        let trace = moving_square(61, 3.0);
        assert!(Replay::from_trace(&trace, &bad)
            .unwrap_err()
            .to_string()
            .contains("frame rate"));
    }
}
