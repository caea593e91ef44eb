//! Probes and channels: how bodies, sensors, brains and tasks publish what they want recorded.
//!
//! A producer names each quantity with a [`Channel`] (a constant beside the code that makes it)
//! and hands its values to a [`Probe`]; whoever listens decides what to keep: the episode's trace
//! keeps every channel marked [`Channel::traced`], a weight-snapshot observer keeps only the
//! plastic weights. So a new kind of brain or body records, draws and replays its own quantities
//! without a field on any shared type, and every consumer iterates channels by name.

use std::collections::BTreeMap;

/// How a replay file keeps a per-step channel.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ReplayMode {
    /// Not in replays (kept in traces only).
    No,
    /// Quantised to this value per stored integer.
    Step(f64),
    /// Positions (x, y pairs): quantised to the replay's position resolution.
    Position,
}

/// A named quantity: its name and how traces and replays keep it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Channel {
    /// The name, unique across producers (`area_ratio`, `attention`, `graph_outputs`, …).
    pub name: &'static str,
    /// Whether full traces keep it (false for bulky quantities read by observers only).
    pub traced: bool,
    /// How replays keep it.
    pub replay: ReplayMode,
    /// The value replays write in place of a non-finite one.
    pub fallback: f64,
    /// Whether traces keep it in single precision (values rounded to `f32`: enough for drawing).
    pub single: bool,
}

impl Channel {
    /// A channel kept by traces and by replays at `resolution`, non-finite values written as 0.
    pub const fn replayed(name: &'static str, resolution: f64) -> Channel {
        Channel {
            name,
            traced: true,
            replay: ReplayMode::Step(resolution),
            fallback: 0.0,
            single: false,
        }
    }

    /// A channel kept by traces but not by replays (or a fixed one, recorded once).
    pub const fn traced(name: &'static str) -> Channel {
        Channel {
            name,
            traced: true,
            replay: ReplayMode::No,
            fallback: 0.0,
            single: false,
        }
    }

    /// The same channel, kept in single precision by traces.
    pub const fn single(self) -> Channel {
        Channel { single: true, ..self }
    }

    /// The same channel, not kept by traces (observers only).
    pub const fn untraced(self) -> Channel {
        Channel { traced: false, ..self }
    }

    /// The same channel, with `fallback` written by replays for non-finite values.
    pub const fn fallback(self, fallback: f64) -> Channel {
        Channel { fallback, ..self }
    }

    /// The same channel, replayed as positions.
    pub const fn positions(self) -> Channel {
        Channel {
            replay: ReplayMode::Position,
            ..self
        }
    }
}

/// Where producers publish: per-step values, and fixed values that do not change in an episode.
pub trait Probe {
    /// This step's values of `channel` (the same count at every step).
    fn step(&mut self, channel: &Channel, values: &[f64]);
    /// [`Probe::step`] with the values from an iterator (no buffer needed at the producer).
    /// Default: collects them, then calls [`Probe::step`].
    fn step_from(&mut self, channel: &Channel, values: &mut dyn Iterator<Item = f64>) {
        let values: Vec<f64> = values.collect();
        self.step(channel, &values);
    }
    /// Values of `channel` that hold for the whole episode (a graph's edges, lidar directions),
    /// `width` numbers per row.
    fn fixed(&mut self, channel: &Channel, width: usize, values: &[f64]);
}

/// A [`Probe`] that keeps the last values of every channel it is given, by name: for tests and
/// observers that look at one quantity during an episode.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Capture {
    values: BTreeMap<&'static str, Vec<f64>>,
}

impl Capture {
    /// An empty capture.
    pub fn new() -> Capture {
        Capture::default()
    }

    /// The last values published on the channel called `name`, if any.
    pub fn get(&self, name: &str) -> Option<&[f64]> {
        self.values.get(name).map(Vec::as_slice)
    }

    /// Names of the channels seen, in order.
    pub fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.values.keys().copied()
    }

    fn keep(&mut self, channel: &Channel, values: &[f64]) {
        let slot = self.values.entry(channel.name).or_default();
        slot.clear();
        slot.extend_from_slice(values);
    }
}

impl Probe for Capture {
    fn step(&mut self, channel: &Channel, values: &[f64]) {
        self.keep(channel, values);
    }

    fn fixed(&mut self, channel: &Channel, _width: usize, values: &[f64]) {
        self.keep(channel, values);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capture_keeps_the_last_values_of_each_channel() {
        const A: Channel = Channel::replayed("a", 1e-3);
        const B: Channel = Channel::traced("b");
        let mut c = Capture::new();
        c.step(&A, &[1.0, 2.0]);
        c.step(&A, &[3.0, 4.0]);
        c.fixed(&B, 1, &[5.0]);
        assert_eq!(c.get("a"), Some(&[3.0, 4.0][..]));
        assert_eq!(c.get("b"), Some(&[5.0][..]));
        assert_eq!(c.get("c"), None);
        assert_eq!(c.names().collect::<Vec<_>>(), ["a", "b"]);
    }
}
