//! The trace of a 3D episode, at a fixed frame rate (an episode has some 20,000 engine steps per
//! second): times and the centre's x, y at every level but `None`; with `Full`, each voxel's
//! centre, orientation, edge, actuation and touch (1 when it touches another voxel), and the
//! obstacles' cells once (the channels [`VOXEL_XYZ`], [`VOXEL_QUAT`], [`VOXEL_EDGE`],
//! [`ACTUATION`], [`TOUCH`], [`FIXED_VOXELS`]).

use super::physics::Built;
use super::task::centre;
use crate::channels::{ACTUATION, FIXED_VOXELS, TOUCH, VOXEL_EDGE, VOXEL_QUAT, VOXEL_XYZ};
use crate::outcome::{Trace, TraceLevel};
use vsrlab_body::Probe;
use vsrlab_physics::Vec2;
use vsrlab_physics3d::{VoxelId, World};

/// Records frames of a 3D episode.
pub(crate) struct Recorder {
    level: TraceLevel,
    trace: Trace,
    /// Time of the next frame (s).
    next: f64,
    period: f64,
    /// Whether the last call to [`Recorder::record`] recorded a full frame.
    framed: bool,
    /// Buffers for one frame's rows.
    xyz: Vec<f64>,
    quat: Vec<f64>,
    edge: Vec<f64>,
    touch: Vec<f64>,
}

impl Recorder {
    pub fn new(level: TraceLevel, built: &Built, frame_rate: f64) -> Recorder {
        let period = 1.0 / frame_rate;
        let mut trace = Trace {
            dt: period,
            side_length: built.world.settings().voxel_size,
            ..Default::default()
        };
        if level == TraceLevel::Full {
            let cells: Vec<f64> = built
                .obstacles
                .iter()
                .flat_map(|&v| built.world.position(v).to_array())
                .collect();
            trace.fixed(&FIXED_VOXELS, 3, &cells);
        }
        Recorder {
            level,
            trace,
            next: 0.0,
            period,
            framed: false,
            xyz: Vec::new(),
            quat: Vec::new(),
            edge: Vec::new(),
            touch: Vec::new(),
        }
    }

    /// Records the state at time `t` when a frame is due.
    pub fn record(&mut self, world: &World, body: &[VoxelId], actuation: &[f64], t: f64) {
        self.framed = false;
        if self.level == TraceLevel::None || t + 1e-12 < self.next {
            return;
        }
        self.next += self.period * ((t - self.next) / self.period + 1e-9).floor().max(0.0) + self.period;
        let c = centre(world, body, 0);
        self.trace.times.push(t);
        self.trace.centers.push(Vec2::new(c.x, c.y));
        if self.level != TraceLevel::Full {
            return;
        }
        self.xyz.clear();
        self.quat.clear();
        self.edge.clear();
        self.touch.clear();
        for &v in body {
            self.xyz.extend(world.position(v).to_array());
            let q = world.orientation(v);
            self.quat.extend([q.w, q.x, q.y, q.z]);
            self.edge.push(world.edge(v));
            self.touch.push(f64::from(u8::from(world.touches_voxel(v))));
        }
        self.trace.step(&VOXEL_XYZ, &self.xyz);
        self.trace.step(&VOXEL_QUAT, &self.quat);
        self.trace.step(&VOXEL_EDGE, &self.edge);
        self.trace.step(&ACTUATION, actuation);
        self.trace.step(&TOUCH, &self.touch);
        self.framed = true;
    }

    /// Adds a channel's values to the frame just recorded, if one was (a brain's votes).
    pub fn record_channel(&mut self, channel: &vsrlab_body::Channel, values: &[f64]) {
        if self.framed {
            self.trace.step(channel, values);
        }
    }

    pub fn finish(self) -> Option<crate::outcome::Trace> {
        (self.level != TraceLevel::None).then_some(self.trace)
    }
}
