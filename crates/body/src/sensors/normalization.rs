//! Normalization (vsr-model.md §3.2): each inner reading is clipped to its domain [lo, hi], then
//! mapped linearly to [0, 1]. The result's domain is [0, 1].

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};
use super::spec::SensorSpec;
use serde::{Deserialize, Serialize};

/// (v − lo)/(hi − lo), not clipped.
pub(crate) fn linear(v: f64, (lo, hi): (f64, f64)) -> f64 {
    (v - lo) / (hi - lo)
}

/// `v` clipped to [lo, hi] and mapped linearly to [0, 1].
pub(crate) fn normalize(v: f64, domain: (f64, f64)) -> f64 {
    linear(v.clamp(domain.0, domain.1), domain)
}

/// Clip-and-scale of every inner reading.
#[derive(Debug, Clone)]
pub(crate) struct Normalization {
    inner: Box<Node>,
    /// The inner sensor's domain, one per reading.
    domains: Vec<(f64, f64)>,
}

impl Normalization {
    /// Normalises the readings of `inner`, whose domains are `domains`.
    pub(crate) fn new(inner: Box<Node>, domains: Vec<(f64, f64)>) -> Normalization {
        Normalization { inner, domains }
    }

    /// Reads the inner sensor and normalises in place.
    pub(crate) fn sense(&mut self, frame: &Frame, out: &mut [f64]) {
        self.inner.sense(frame, out);
        for (o, d) in out.iter_mut().zip(&self.domains) {
            *o = normalize(*o, *d);
        }
    }

    /// The normalised sensor.
    pub(crate) fn inner(&self) -> &Node {
        &self.inner
    }

    /// The normalised sensor, mutably.
    pub(crate) fn inner_mut(&mut self) -> &mut Node {
        &mut self.inner
    }
}

/// Description of a normalization wrapper (`{"kind": "normalization", "inner": {…}}`): clip to the
/// inner domain, then map linearly to [0, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NormalizationSpec {
    /// The normalised sensor.
    pub inner: Box<SensorSpec>,
}

impl SensorKind for NormalizationSpec {
    fn dimension(&self) -> usize {
        self.inner.dimension()
    }

    fn domains(&self) -> Vec<(f64, f64)> {
        vec![(0.0, 1.0); self.inner.dimension()]
    }

    fn validate(&self, noisy_depth: usize) -> Result<(), String> {
        self.inner.validate_at(noisy_depth)
    }

    fn build(&self, site: Site) -> Node {
        let inner = Box::new(Node::build(&self.inner, site));
        Node::Normalization(Normalization::new(inner, self.inner.domains()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{run, still_state};
    use crate::sensors::spec::SensorSpec;

    #[test]
    fn clips_then_scales() {
        assert_eq!(normalize(0.0, (-1.0, 1.0)), 0.5);
        assert_eq!(normalize(-3.0, (-1.0, 1.0)), 0.0);
        assert_eq!(normalize(7.0, (0.0, 10.0)), 0.7);
        assert_eq!(normalize(12.0, (0.0, 10.0)), 1.0);
    }

    #[test]
    fn normalises_the_area_ratio() {
        let spec = SensorSpec::AreaRatio.normalized();
        let states: Vec<_> = [0.4, 0.75, 1.5, 2.0]
            .iter()
            .map(|&a| {
                let mut s = still_state();
                s.area_ratio = a;
                s
            })
            .collect();
        let r: Vec<f64> = run(&spec, &states, 1.0 / 60.0).into_iter().map(|v| v[0]).collect();
        assert_eq!(r, vec![0.0, 0.25, 1.0, 1.0]);
    }
}
