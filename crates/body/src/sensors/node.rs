//! Running sensors: a tree of [`Node`]s mirroring a [`SensorSpec`], each holding the state it needs
//! (sample windows, noise generators, last lidar distances). Built once per episode by each sensor
//! kind ([`super::kind::SensorKind::build`]); sensing never allocates. `Node` is an enum so that
//! [`Node::sense`], called for every sensor at every step, is dispatched statically.

use super::angle::Angle;
use super::area_ratio::AreaRatio;
use super::average::Average;
use super::constant::ConstantPosition;
use super::cpg::Cpg;
use super::lidar::Lidar;
use super::malfunction::Malfunction;
use super::noise::{NoiseKey, Noisy};
use super::normalization::Normalization;
use super::soft_normalization::SoftNormalization;
use super::spec::SensorSpec;
use super::touch::Touch;
use super::trend::Trend;
use super::velocity::Velocity;
use super::wrapper::Wrapped;
use crate::robot::VoxelState;
use vsrlab_physics::World;

/// What a sensor may read at one step.
pub(crate) struct Frame<'a> {
    /// The world (for ray casts).
    pub world: &'a World,
    /// The sensing voxel's state.
    pub state: &'a VoxelState,
    /// Simulated time (s).
    pub t: f64,
}

/// Where a sensor is being built: fixed facts about its voxel and its place in the suite.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Site {
    /// Relative grid position of the voxel (x, y in [0, 1]).
    pub rel: (f64, f64),
    /// Nominal time between readings (s), to size sample windows.
    pub dt: f64,
    /// Identity of the noise streams of this sensor tree.
    pub noise: NoiseKey,
}

/// A running sensor.
#[derive(Debug, Clone)]
pub(crate) enum Node {
    AreaRatio(AreaRatio),
    Touch(Touch),
    Velocity(Velocity),
    Angle(Angle),
    Lidar(Lidar),
    Cpg(Cpg),
    ConstantPosition(ConstantPosition),
    Malfunction(Malfunction),
    Average(Wrapped<Average>),
    Trend(Wrapped<Trend>),
    Normalization(Wrapped<Normalization>),
    SoftNormalization(Wrapped<SoftNormalization>),
    Noisy(Wrapped<Noisy>),
}

impl Node {
    /// The running form of a (validated) `spec` placed at `site` (built by the spec's kind).
    pub(crate) fn build(spec: &SensorSpec, site: Site) -> Node {
        spec.as_kind().build(site)
    }

    /// Writes this sensor's readings into `out` (exactly its dimension).
    pub(crate) fn sense(&mut self, frame: &Frame, out: &mut [f64]) {
        match self {
            Node::AreaRatio(s) => s.sense(frame, out),
            Node::Touch(s) => s.sense(frame, out),
            Node::Velocity(s) => s.sense(frame, out),
            Node::Angle(s) => s.sense(frame, out),
            Node::Lidar(s) => s.sense(frame, out),
            Node::Cpg(s) => s.sense(frame, out),
            Node::ConstantPosition(s) => s.sense(frame, out),
            Node::Malfunction(s) => s.sense(frame, out),
            Node::Average(s) => s.sense(frame, out),
            Node::Trend(s) => s.sense(frame, out),
            Node::Normalization(s) => s.sense(frame, out),
            Node::SoftNormalization(s) => s.sense(frame, out),
            Node::Noisy(s) => s.sense(frame, out),
        }
    }

    /// Back to the state at construction: empty windows, noise streams at their start.
    pub(crate) fn reset(&mut self) {
        match self {
            Node::Lidar(s) => s.reset(),
            Node::Average(s) => s.reset(),
            Node::Trend(s) => s.reset(),
            Node::Normalization(s) => s.reset(),
            Node::SoftNormalization(s) => s.reset(),
            Node::Noisy(s) => s.reset(),
            Node::AreaRatio(_)
            | Node::Touch(_)
            | Node::Velocity(_)
            | Node::Angle(_)
            | Node::Cpg(_)
            | Node::ConstantPosition(_)
            | Node::Malfunction(_) => {}
        }
    }

    /// Calls `f` on every lidar in this tree, depth first.
    pub(crate) fn for_each_lidar(&self, f: &mut dyn FnMut(&Lidar)) {
        match self {
            Node::Lidar(l) => f(l),
            Node::Average(s) => s.inner().for_each_lidar(f),
            Node::Trend(s) => s.inner().for_each_lidar(f),
            Node::Normalization(s) => s.inner().for_each_lidar(f),
            Node::SoftNormalization(s) => s.inner().for_each_lidar(f),
            Node::Noisy(s) => s.inner().for_each_lidar(f),
            _ => {}
        }
    }
}

/// Helpers for the unit tests of the sensor files.
#[cfg(test)]
pub(crate) mod testing {
    use super::*;
    use vsrlab_physics::{WorldBuilder, WorldSettings};

    /// A world with nothing in it.
    pub(crate) fn empty_world() -> World {
        WorldBuilder::new(WorldSettings::default()).build().unwrap()
    }

    /// A voxel at rest at the origin, upright, not touching anything ([`VoxelState::default`]).
    pub(crate) fn still_state() -> VoxelState {
        VoxelState::default()
    }

    /// One state per item of `items`: a [`still_state`] changed by `set` according to the item.
    pub(crate) fn states_from<T>(
        items: impl IntoIterator<Item = T>,
        set: impl Fn(&mut VoxelState, T),
    ) -> Vec<VoxelState> {
        items
            .into_iter()
            .map(|item| {
                let mut state = still_state();
                set(&mut state, item);
                state
            })
            .collect()
    }

    /// What a sensor sees of `state` in `world` at time `t`.
    pub(crate) fn frame<'a>(world: &'a World, state: &'a VoxelState, t: f64) -> Frame<'a> {
        Frame { world, state, t }
    }

    /// A site at the grid's centre, sampled at 60 Hz, with noise from episode seed 0.
    pub(crate) fn site() -> Site {
        Site {
            rel: (0.5, 0.5),
            dt: 1.0 / 60.0,
            noise: NoiseKey::new(0, 0, 0),
        }
    }

    /// Builds `spec` at [`site`] and reads it once, seeing `state` at time `t` in an empty world
    /// (readings it does not write stay NaN).
    pub(crate) fn read_once(spec: &SensorSpec, state: &VoxelState, t: f64) -> Vec<f64> {
        let mut out = vec![f64::NAN; spec.dimension()];
        Node::build(spec, site()).sense(&frame(&empty_world(), state, t), &mut out);
        out
    }

    /// Builds `spec` and reads it once per state, at times dt, 2dt, …; returns every reading.
    pub(crate) fn run(spec: &SensorSpec, states: &[VoxelState], dt: f64) -> Vec<Vec<f64>> {
        let world = empty_world();
        let mut node = Node::build(spec, Site { dt, ..site() });
        let mut t = 0.0;
        states
            .iter()
            .map(|state| {
                t += dt;
                let mut out = vec![0.0; spec.dimension()];
                node.sense(&frame(&world, state, t), &mut out);
                out
            })
            .collect()
    }
}
