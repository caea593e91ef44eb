//! Normalization (vsr-model.md §3.2): each inner reading is clipped to its domain [lo, hi], then
//! mapped linearly to [0, 1]. The result's domain is [0, 1].

use super::node::{Node, Site};
use super::spec::SensorSpec;
use super::wrapper::{Transform, Wrapped, WrapperKind};
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
    /// The inner sensor's domain, one per reading.
    domains: Vec<(f64, f64)>,
}

impl Normalization {
    /// Normalises readings whose domains are `domains`.
    pub(crate) fn new(domains: Vec<(f64, f64)>) -> Normalization {
        Normalization { domains }
    }
}

impl Transform for Normalization {
    /// Normalises in place.
    fn apply(&mut self, _t: f64, out: &mut [f64]) {
        for (o, d) in out.iter_mut().zip(&self.domains) {
            *o = normalize(*o, *d);
        }
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

impl WrapperKind for NormalizationSpec {
    fn inner(&self) -> &SensorSpec {
        &self.inner
    }

    /// [0, 1].
    fn domain(&self, _inner: (f64, f64)) -> (f64, f64) {
        (0.0, 1.0)
    }

    fn wrap(&self, inner: Box<Node>, _site: Site) -> Node {
        Node::Normalization(Wrapped::new(inner, Normalization::new(self.inner.domains())))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::node::testing::{run, states_from};
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
        let states = states_from([0.4, 0.75, 1.5, 2.0], |s, a| s.area_ratio = a);
        let r: Vec<f64> = run(&spec, &states, 1.0 / 60.0).into_iter().map(|v| v[0]).collect();
        assert_eq!(r, vec![0.0, 0.25, 1.0, 1.0]);
    }
}
