//! Soft normalization (vsr-model.md §3.2): with v the inner reading mapped linearly to [0, 1],
//! the output is tanh(2(2v − 1))/2 + 1/2, an S-curve through (0.5, 0.5).
//!
//! Two eras differ on clipping. In every thesis-era simulator (2D-VSR-Sim ≤ v1.10) v is **not**
//! clipped, so readings beyond the domain still move the output within (0, 1); from v1.11
//! (2021-12-28) v is first clipped to [0, 1], so the output stays in [0.018, 0.982]. `clip = false`
//! (the default) is the thesis era. Area ratio examples: 0.8 → 0.168, 1.0 → 0.5, 1.2 → 0.832.

use super::node::{Node, Site};
use super::normalization::linear;
use super::spec::SensorSpec;
use super::wrapper::{Transform, Wrapped, WrapperKind};
use serde::{Deserialize, Serialize};
use vsrlab_lanes::fdlibm_tanh;

/// tanh(2(2v − 1))/2 + 1/2 of `x` mapped linearly from `domain` to v, clipping v to [0, 1] first
/// if `clip`.
pub(crate) fn soft_normalize(x: f64, domain: (f64, f64), clip: bool) -> f64 {
    let mut v = linear(x, domain);
    if clip {
        v = v.clamp(0.0, 1.0);
    }
    fdlibm_tanh(2.0 * (2.0 * v - 1.0)) / 2.0 + 0.5
}

/// S-curve normalisation of every inner reading.
#[derive(Debug, Clone)]
pub(crate) struct SoftNormalization {
    /// The inner sensor's domain, one per reading.
    domains: Vec<(f64, f64)>,
    clip: bool,
}

impl SoftNormalization {
    /// Soft-normalises readings whose domains are `domains`.
    pub(crate) fn new(domains: Vec<(f64, f64)>, clip: bool) -> SoftNormalization {
        SoftNormalization { domains, clip }
    }
}

impl Transform for SoftNormalization {
    /// Soft-normalises in place.
    fn apply(&mut self, _t: f64, out: &mut [f64]) {
        for (o, d) in out.iter_mut().zip(&self.domains) {
            *o = soft_normalize(*o, *d, self.clip);
        }
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

impl WrapperKind for SoftNormalizationSpec {
    fn inner(&self) -> &SensorSpec {
        &self.inner
    }

    /// [0, 1].
    fn domain(&self, _inner: (f64, f64)) -> (f64, f64) {
        (0.0, 1.0)
    }

    fn wrap(&self, inner: Box<Node>, _site: Site) -> Node {
        let soft = SoftNormalization::new(self.inner.domains(), self.clip);
        Node::SoftNormalization(Wrapped::new(inner, soft))
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
