//! Soft normalization (vsr-model.md §3.2): with v the inner reading mapped linearly to [0, 1],
//! the output is tanh(2(2v − 1))/2 + 1/2, an S-curve through (0.5, 0.5).
//!
//! Two eras differ on clipping. In every thesis-era simulator (2D-VSR-Sim ≤ v1.10) v is **not**
//! clipped, so readings beyond the domain still move the output within (0, 1); from v1.11
//! (2021-12-28) v is first clipped to [0, 1], so the output stays in [0.018, 0.982]. `clip = false`
//! (the default) is the thesis era. Area ratio examples: 0.8 → 0.168, 1.0 → 0.5, 1.2 → 0.832.

use super::kind::SensorKind;
use super::node::{Frame, Node, Site};
use super::normalization::linear;
use super::spec::SensorSpec;
use serde::{Deserialize, Serialize};

/// tanh(2(2v − 1))/2 + 1/2 of `x` mapped linearly from `domain` to v, clipping v to [0, 1] first
/// if `clip`.
pub(crate) fn soft_normalize(x: f64, domain: (f64, f64), clip: bool) -> f64 {
    let mut v = linear(x, domain);
    if clip {
        v = v.clamp(0.0, 1.0);
    }
    (2.0 * (2.0 * v - 1.0)).tanh() / 2.0 + 0.5
}

/// S-curve normalisation of every inner reading.
#[derive(Debug, Clone)]
pub(crate) struct SoftNormalization {
    inner: Box<Node>,
    /// The inner sensor's domain, one per reading.
    domains: Vec<(f64, f64)>,
    clip: bool,
}

impl SoftNormalization {
    /// Soft-normalises the readings of `inner`, whose domains are `domains`.
    pub(crate) fn new(inner: Box<Node>, domains: Vec<(f64, f64)>, clip: bool) -> SoftNormalization {
        SoftNormalization { inner, domains, clip }
    }

    /// Reads the inner sensor and soft-normalises in place.
    pub(crate) fn sense(&mut self, frame: &Frame, out: &mut [f64]) {
        self.inner.sense(frame, out);
        for (o, d) in out.iter_mut().zip(&self.domains) {
            *o = soft_normalize(*o, *d, self.clip);
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

/// Description of a soft normalization wrapper (`{"kind": "soft-normalization", "clip": false,
/// "inner": {…}}`): tanh(2(2v − 1))/2 + 1/2 of the linearly normalised value v; domain [0, 1].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoftNormalizationSpec {
    /// Clip v to [0, 1] first: false (default) as in the thesis era (2D-VSR-Sim ≤ v1.10), true
    /// as in v1.11 and later.
    #[serde(default)]
    pub clip: bool,
    /// The normalised sensor.
    pub inner: Box<SensorSpec>,
}

impl SensorKind for SoftNormalizationSpec {
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
        Node::SoftNormalization(SoftNormalization::new(inner, self.inner.domains(), self.clip))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn area_ratio_matches_the_published_examples() {
        let d = (0.5, 1.5);
        for (area, expected) in [(0.8, 0.168), (1.0, 0.5), (1.2, 0.832)] {
            let v = soft_normalize(area, d, false);
            assert!((v - expected).abs() < 5e-4, "{area} → {v}");
            assert_eq!(
                v,
                soft_normalize(area, d, true),
                "inside the domain clipping changes nothing"
            );
        }
    }

    #[test]
    fn clipping_bounds_the_output() {
        let d = (0.5, 1.5);
        let unclipped = soft_normalize(2.5, d, false);
        let clipped = soft_normalize(2.5, d, true);
        assert!(unclipped > 0.999 && unclipped < 1.0, "{unclipped}");
        assert!((clipped - ((2.0f64).tanh() / 2.0 + 0.5)).abs() < 1e-15, "{clipped}");
        assert!((clipped - 0.982).abs() < 1e-3);
        assert!((soft_normalize(0.0, d, true) - 0.018).abs() < 1e-3);
    }

    #[test]
    fn runs_inside_a_sensor_tree() {
        use crate::sensors::node::testing::{run, still_state};
        use crate::sensors::spec::SensorSpec;
        let spec = SensorSpec::AreaRatio.soft_normalized();
        let mut s = still_state();
        s.area_ratio = 1.2;
        let r = run(&spec, &[s], 1.0 / 60.0);
        assert!((r[0][0] - 0.832).abs() < 5e-4);
    }
}
