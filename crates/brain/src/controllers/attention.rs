//! Local self-attention controller (thesis §4.2, thesis-code-facts.md §5): the same small network
//! in every voxel, no messages between voxels; each voxel attends over its own readings.
//!
//! # Per voxel, per step
//!
//! With r readings s ∈ ℝʳ (the same r on every voxel), n voxels, d = `d_k` (thesis 8):
//! - Q = s·w_qᵀ + b_q and K = s·w_kᵀ + b_k (r × d; w_q, b_q, w_k, b_k ∈ ℝᵈ): each reading is a
//!   token. This is the thesis' X·W_q with X = s·h_iᵀ and W_q = h_i·w_qᵀ: only the own column
//!   counts.
//! - A = tanh(Q·Kᵀ / √d) (r × r), tanh instead of softmax; the values are the identity.
//! - Y = A·s, placed as block i of a vector of n·r values in reading-major order (entry a·n + i
//!   holds (A·s)_a: the row-major flattening of the r × n matrix A·X), all else 0.
//! - The downstream network, tanh on its inputs and on its single output, no hidden layer:
//!   a = tanh(b + Σ_a w_{a·n+i} · tanh((A·s)_a)).
//!
//! Slow attention (thesis §4.2.5, not in the original code): with `slow = true` two more genes
//! give α = min(|g_α|, 1) and η = min(|g_η|, 1), and the matrix used at step k > 0 is
//! A' = α·A + η·A'_{k−1} (A' = A at the first step).
//!
//! # Parameter layout
//!
//! Homogeneous (thesis): `[w_q (d), b_q (d), w_k (d), b_k (d), (g_α, g_η)]` then the downstream
//! network `[b, n·r weights]`: 4d (+2) + n·r + 1. Biped-4x3 with 4 readings: 32 + 41 = **73**;
//! comb-7x2 (11 voxels): 32 + 45 = 77. The original genotype also carried 88 value genes that were
//! never used; we have none. Heterogeneous: one such block per voxel, in voxel order.
//!
//! With `attention` set (transfer to another body, thesis §4.2.4.1), the attention genes are fixed
//! to those values and the parameters are the downstream network only.
//!
//! The attention matrices are the controller's plastic weights ([`crate::PLASTIC_WEIGHTS`], n·r²
//! values, voxel-major, row-major within a voxel): they can be snapshot and frozen (the
//! frozen-attention ablation), and as channel [`ATTENTION`] they are recorded, drawn in videos and
//! replayed.

use crate::controller::PLASTIC_WEIGHTS;
use crate::controllers::distributed_mlp::common_readings;
use crate::mlp::check_parameter_total;
use crate::short_form::{self, ShortForm};
use crate::validation::{check_count, check_finite, check_units, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller, Layout};
use serde::{Deserialize, Serialize};
use vsrlab_body::{Channel, Probe};
use vsrlab_lanes::fdlibm_tanh;

/// Largest `d_k`.
pub const MAX_D_K: usize = 10_000;

/// Description of a self-attention brain (`{"kind": "attention", …}`), module documentation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AttentionSpec {
    /// Dimension of queries and keys (thesis 8).
    pub d_k: usize,
    /// `homogeneous` (one network for every voxel, the thesis) or `heterogeneous` (one per voxel).
    pub layout: Layout,
    /// Slow attention: two more genes, α and η.
    pub slow: bool,
    /// Fixed attention genes (w_q, b_q, w_k, b_k[, g_α, g_η]), e.g. transferred from another
    /// robot; empty = they are parameters.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub attention: Vec<f64>,
    /// Attention matrices held fixed for the whole episode (n·r² values); empty = computed.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub frozen: Vec<f64>,
    /// The matrices stop changing at this simulated time (s); absent = never.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub freeze_at: Option<f64>,
    /// The genes (layout in the module documentation); default none (a template).
    pub parameters: Vec<f64>,
}

impl Default for AttentionSpec {
    fn default() -> Self {
        AttentionSpec {
            d_k: 8,
            layout: Layout::Homogeneous,
            slow: false,
            attention: Vec::new(),
            frozen: Vec::new(),
            freeze_at: None,
            parameters: Vec::new(),
        }
    }
}

impl AttentionSpec {
    /// Genes of one attention module: 4d, +2 when slow.
    pub fn attention_len(&self) -> usize {
        self.d_k.saturating_mul(4) + if self.slow { 2 } else { 0 }
    }

    /// Genes of one downstream network: n·r + 1.
    fn downstream_len(voxels: usize, readings: usize) -> usize {
        voxels.saturating_mul(readings).saturating_add(1)
    }

    fn check(&self) -> Result<(), BrainError> {
        if self.d_k == 0 || self.d_k > MAX_D_K {
            return Err(BrainError::Invalid {
                field: "d_k",
                msg: format!("must be in 1..={MAX_D_K}, got {}", self.d_k),
            });
        }
        if !self.attention.is_empty() {
            if self.layout == Layout::Heterogeneous {
                return Err(BrainError::Invalid {
                    field: "attention",
                    msg: "fixed attention genes need the homogeneous layout".into(),
                });
            }
            check_count("attention", self.attention_len(), self.attention.len())?;
            check_finite("attention", &self.attention)?;
        }
        check_finite("frozen", &self.frozen)?;
        if let Some(t) = self.freeze_at {
            crate::validation::finite("freeze_at", t)?;
        }
        Ok(())
    }

    /// The attention genes of this brain (fixed or the first block of the parameters), for a
    /// transfer to another body; `None` when the parameters are not filled.
    pub fn attention_genes(&self) -> Option<&[f64]> {
        if !self.attention.is_empty() {
            return Some(&self.attention);
        }
        self.parameters.get(..self.attention_len())
    }
}

impl BrainKind for AttentionSpec {
    fn name(&self) -> &'static str {
        "attention"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        self.check()?;
        check_units(shape)?;
        let r = common_readings(shape)?;
        let n = shape.units();
        let downstream = Self::downstream_len(n, r);
        let count = match (self.layout, self.attention.is_empty()) {
            (Layout::Homogeneous, true) => self.attention_len().saturating_add(downstream),
            (Layout::Homogeneous, false) => downstream,
            (Layout::Heterogeneous, _) => n.saturating_mul(self.attention_len().saturating_add(downstream)),
        };
        check_parameter_total(count)?;
        Ok(count)
    }

    fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("parameters", &mut self.parameters, params)
    }

    fn freeze_with(&mut self, weights: &[f64]) -> Result<(), BrainError> {
        check_finite("frozen", weights)?;
        self.frozen = weights.to_vec();
        Ok(())
    }

    fn stop_learning_at(&mut self, t: f64) -> Result<(), BrainError> {
        crate::validation::finite("freeze_at", t)?;
        self.freeze_at = Some(t);
        Ok(())
    }

    /// Fixes the source's attention genes (it must be an attention brain of the same `d_k` and
    /// `slow`, homogeneous); the parameters become the downstream network only.
    fn transfer_from(&mut self, source: &BrainSpec) -> Result<(), BrainError> {
        let source = source.as_kind().inner().unwrap_or(source);
        let bad = |msg: String| {
            Err(BrainError::Invalid {
                field: "attention",
                msg,
            })
        };
        let BrainSpec::Attention(from) = source else {
            return bad(format!(
                "the source brain is a {} brain, not an attention brain",
                source.kind()
            ));
        };
        if (from.d_k, from.slow, from.layout) != (self.d_k, self.slow, Layout::Homogeneous)
            || from.layout != Layout::Homogeneous
        {
            return bad(format!(
                "the source's attention (d_k {}, slow {}, {:?}) does not fit this brain's (d_k {}, slow {}, homogeneous)",
                from.d_k, from.slow, from.layout, self.d_k, self.slow
            ));
        }
        let Some(genes) = from.attention_genes() else {
            return bad("the source brain has no parameters (a template, not an evolved robot)".into());
        };
        self.attention = genes.to_vec();
        self.parameters.clear();
        Ok(())
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        let expected = self.parameter_count(shape)?;
        check_count("parameters", expected, self.parameters.len())?;
        let r = common_readings(shape)?;
        let n = shape.units();
        if !self.frozen.is_empty() {
            check_count("frozen", n * r * r, self.frozen.len())?;
        }
        let (att, down) = (self.attention_len(), Self::downstream_len(n, r));
        let modules: Vec<(Vec<f64>, Vec<f64>)> = match (self.layout, self.attention.is_empty()) {
            (Layout::Homogeneous, true) => vec![(self.parameters[..att].to_vec(), self.parameters[att..].to_vec())],
            (Layout::Homogeneous, false) => vec![(self.attention.clone(), self.parameters.clone())],
            (Layout::Heterogeneous, _) => self
                .parameters
                .chunks(att + down)
                .map(|block| (block[..att].to_vec(), block[att..].to_vec()))
                .collect(),
        };
        Ok(Box::new(AttentionController::new(
            n,
            r,
            self.d_k,
            self.slow,
            modules,
            self.frozen.clone(),
            self.freeze_at.unwrap_or(f64::INFINITY),
        )))
    }
}

/// One voxel network's genes, unpacked.
#[derive(Debug, Clone)]
struct Module {
    w_q: Vec<f64>,
    b_q: Vec<f64>,
    w_k: Vec<f64>,
    b_k: Vec<f64>,
    alpha: f64,
    eta: f64,
    /// `[b, n·r weights]`.
    downstream: Vec<f64>,
}

impl Module {
    fn new(attention: &[f64], downstream: Vec<f64>, d: usize, slow: bool) -> Module {
        let part = |k: usize| attention[k * d..(k + 1) * d].to_vec();
        let (alpha, eta) = if slow {
            (attention[4 * d].abs().min(1.0), attention[4 * d + 1].abs().min(1.0))
        } else {
            (1.0, 0.0)
        };
        Module {
            w_q: part(0),
            b_q: part(1),
            w_k: part(2),
            b_k: part(3),
            alpha,
            eta,
            downstream,
        }
    }
}

/// The running attention controller: one module (homogeneous) or one per voxel, and every voxel's
/// current attention matrix. [`Controller::control`] allocates nothing.
#[derive(Debug, Clone)]
pub struct AttentionController {
    voxels: usize,
    readings: usize,
    d: usize,
    modules: Vec<Module>,
    /// Per voxel, its r × r matrix (row-major): the one in use (A, or A' when slow).
    attention: Vec<f64>,
    /// Frozen matrices, empty when computed.
    frozen: Vec<f64>,
    freeze_at: f64,
    /// Whether a step has run since the last reset (slow attention starts from A).
    started: bool,
    q: Vec<f64>,
    k: Vec<f64>,
}

impl AttentionController {
    fn new(
        voxels: usize,
        readings: usize,
        d: usize,
        slow: bool,
        modules: Vec<(Vec<f64>, Vec<f64>)>,
        frozen: Vec<f64>,
        freeze_at: f64,
    ) -> Self {
        let modules = modules
            .into_iter()
            .map(|(a, down)| Module::new(&a, down, d, slow))
            .collect();
        let attention = if frozen.is_empty() {
            vec![0.0; voxels * readings * readings]
        } else {
            frozen.clone()
        };
        AttentionController {
            voxels,
            readings,
            d,
            modules,
            attention,
            frozen,
            freeze_at,
            started: false,
            q: vec![0.0; readings * d],
            k: vec![0.0; readings * d],
        }
    }

    /// Computes voxel `v`'s attention matrix from its readings `s` into `self.attention`.
    fn attend(&mut self, v: usize, s: &[f64]) {
        let (r, d) = (self.readings, self.d);
        let m = &self.modules[if self.modules.len() == 1 { 0 } else { v }];
        for (a, &reading) in s.iter().enumerate() {
            for j in 0..d {
                self.q[a * d + j] = reading * m.w_q[j] + m.b_q[j];
                self.k[a * d + j] = reading * m.w_k[j] + m.b_k[j];
            }
        }
        let scale = 1.0 / (d as f64).sqrt();
        let started = self.started;
        let matrix = &mut self.attention[v * r * r..(v + 1) * r * r];
        for a in 0..r {
            for b in 0..r {
                let dot: f64 = (0..d).map(|j| self.q[a * d + j] * self.k[b * d + j]).sum();
                let fresh = fdlibm_tanh(dot * scale);
                let slot = &mut matrix[a * r + b];
                *slot = if started {
                    m.alpha * fresh + m.eta * *slot
                } else {
                    fresh
                };
            }
        }
    }

    /// Voxel `v`'s actuation from its readings and its current attention matrix.
    fn act(&self, v: usize, s: &[f64]) -> f64 {
        let (r, n) = (self.readings, self.voxels);
        let m = &self.modules[if self.modules.len() == 1 { 0 } else { v }];
        let matrix = &self.attention[v * r * r..(v + 1) * r * r];
        let mut sum = m.downstream[0];
        for a in 0..r {
            let y: f64 = (0..r).map(|b| matrix[a * r + b] * s[b]).sum();
            sum += m.downstream[1 + a * n + v] * fdlibm_tanh(y);
        }
        fdlibm_tanh(sum)
    }
}

impl Controller for AttentionController {
    fn reset(&mut self) {
        if self.frozen.is_empty() {
            self.attention.fill(0.0);
        } else {
            self.attention.copy_from_slice(&self.frozen);
        }
        self.started = false;
    }

    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]) {
        let r = self.readings;
        let update = self.frozen.is_empty() && t < self.freeze_at;
        for (v, a) in actuations.iter_mut().enumerate() {
            let s = &readings[v * r..(v + 1) * r];
            if update {
                self.attend(v, s);
            }
            *a = self.act(v, s).clamp(-1.0, 1.0);
        }
        self.started = true;
    }

    fn describe(&self, probe: &mut dyn Probe) {
        probe.fixed(&ATTENTION_SIDE, 1, &[self.readings as f64]);
    }

    fn publish(&self, probe: &mut dyn Probe) {
        probe.step(&ATTENTION, &self.attention);
        probe.step(&PLASTIC_WEIGHTS, &self.attention);
    }
}

/// Every voxel's attention matrix, r·r values each (voxel-major, row-major within a voxel), for
/// drawing and replays.
pub const ATTENTION: Channel = Channel::replayed("attention", 1e-2).single();

/// The side r of each voxel's attention matrix (its readings count).
pub const ATTENTION_SIDE: Channel = Channel::traced("attention_side");

/// The side r and the matrices (n·r² values) a brain publishes on [`ATTENTION_SIDE`] and
/// [`ATTENTION`], if it is an attention brain (wrapped or not).
pub fn attention_matrices(brain: &dyn Controller) -> Option<(usize, Vec<f64>)> {
    let mut capture = vsrlab_body::Capture::new();
    brain.describe(&mut capture);
    brain.publish(&mut capture);
    let side = capture.get(ATTENTION_SIDE.name)?.first().copied()? as usize;
    Some((side, capture.get(ATTENTION.name)?.to_vec()))
}

/// `attention` (homogeneous, d_k = 8), `attention:hetero`, `attention:slow`.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "attention",
    usage: "attention[:hetero|slow]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let mut spec = AttentionSpec::default();
    match argument.map(str::trim) {
        None => {}
        Some("hetero") => spec.layout = Layout::Heterogeneous,
        Some("slow") => spec.slow = true,
        Some(other) => spec.d_k = short_form::count(other).filter(|&d| d > 0)?,
    }
    Some(BrainSpec::Attention(spec))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped};
    use vsrlab_body::Morphology;

    fn filled(spec: &str, seed: u64) -> BrainSpec {
        let (m, rpv) = biped();
        BrainSpec::parse(spec)
            .unwrap()
            .with_random_parameters(seed, &BrainShape::grid(&m, &rpv))
            .unwrap()
    }

    #[test]
    fn the_thesis_parameter_counts() {
        let (m, rpv) = biped();
        let count = |s: &str| {
            BrainSpec::parse(s)
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv))
                .unwrap()
        };
        assert_eq!(count("attention"), 73);
        assert_eq!(count("attention:slow"), 75);
        assert_eq!(count("attention:hetero"), 10 * 73);
        let comb = Morphology::named("comb-7x2").unwrap();
        let spec = BrainSpec::parse("attention").unwrap();
        assert_eq!(spec.parameter_count(&BrainShape::grid(&comb, &[4; 11])).unwrap(), 77);
        // the baselines: per-voxel MLP on the one-hot readings, with and without signals
        assert_eq!(count("local-mlp"), 41);
        assert_eq!(count("local-mlp:1"), 5 * 45);
        // larger bodies: biped-6x4 has 18 voxels, comb-14x2 21
        let big = Morphology::named("biped-6x4").unwrap();
        assert_eq!(big.voxel_count(), 18);
        assert_eq!(
            spec.parameter_count(&BrainShape::grid(&big, &[4; 18])).unwrap(),
            32 + 18 * 4 + 1
        );
    }

    #[test]
    fn one_voxel_follows_the_formula() {
        // worm-1x1, 2 readings, d = 1: Q = s·w_q + b_q, K = s·w_k + b_k, A = tanh(Q Kᵀ)
        let m = Morphology::named("worm-1x1").unwrap();
        let params = vec![0.5, 0.1, -0.3, 0.2, /* downstream */ 0.05, 0.7, -0.4];
        let spec = BrainSpec::Attention(AttentionSpec {
            d_k: 1,
            parameters: params,
            ..AttentionSpec::default()
        });
        let mut c = spec.build(&BrainShape::grid(&m, &[2])).unwrap();
        let s = [0.6, 0.2];
        let mut a = [0.0];
        c.control(0.0, &s, &mut a);
        let q: [f64; 2] = [0.6 * 0.5 + 0.1, 0.2 * 0.5 + 0.1];
        let k: [f64; 2] = [0.6 * -0.3 + 0.2, 0.2 * -0.3 + 0.2];
        let att = |i: usize, j: usize| (q[i] * k[j]).tanh();
        let y0 = att(0, 0) * s[0] + att(0, 1) * s[1];
        let y1 = att(1, 0) * s[0] + att(1, 1) * s[1];
        let expected = (0.05 + 0.7 * y0.tanh() - 0.4 * y1.tanh()).tanh();
        assert!((a[0] - expected).abs() < 1e-15, "{} vs {expected}", a[0]);
        let (side, matrix) = attention_matrices(&c).unwrap();
        assert_eq!(side, 2);
        assert!((matrix[1] - att(0, 1)).abs() < 1e-15);
    }

    #[test]
    fn no_voxel_reads_another_voxels_state() {
        let (m, rpv) = biped();
        for form in ["attention", "attention:hetero", "attention:slow", "local-mlp"] {
            let spec = filled(form, 5);
            let base: Vec<f64> = (0..40).map(|i| (i as f64 * 0.31).sin().abs()).collect();
            let run = |readings: &[f64]| {
                let mut c = spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
                let mut a = vec![0.0; 10];
                // two steps, so that slow attention's memory is involved too
                c.control(0.0, &base, &mut a);
                c.control(1.0 / 60.0, readings, &mut a);
                a
            };
            let reference = run(&base);
            for v in 0..10 {
                let mut perturbed = base.clone();
                for x in &mut perturbed[v * 4..(v + 1) * 4] {
                    *x = 1.0 - *x;
                }
                let out = run(&perturbed);
                for u in 0..10 {
                    if u == v {
                        assert_ne!(out[u], reference[u], "{form}: voxel {v} ignores its own readings");
                    } else {
                        assert_eq!(out[u], reference[u], "{form}: voxel {u} reads voxel {v}");
                    }
                }
            }
        }
    }

    #[test]
    fn slow_attention_mixes_the_previous_matrix() {
        let m = Morphology::named("worm-1x1").unwrap();
        // d = 1, α gene −0.5 → α = 0.5, η gene 3 → η = 1 (clipped)
        let spec = BrainSpec::Attention(AttentionSpec {
            d_k: 1,
            slow: true,
            parameters: vec![1.0, 0.0, 1.0, 0.0, -0.5, 3.0, 0.0, 1.0],
            ..AttentionSpec::default()
        });
        let mut c = spec.build(&BrainShape::grid(&m, &[1])).unwrap();
        let mut a = [0.0];
        c.control(0.0, &[0.5], &mut a);
        let first = attention_matrices(&c).unwrap().1[0];
        assert!((first - 0.25f64.tanh()).abs() < 1e-15);
        c.control(1.0 / 60.0, &[0.8], &mut a);
        let second = attention_matrices(&c).unwrap().1[0];
        assert!((second - (0.5 * 0.64f64.tanh() + first)).abs() < 1e-15);
        c.reset();
        c.control(0.0, &[0.5], &mut a);
        assert_eq!(attention_matrices(&c).unwrap().1[0], first, "reset forgets");
    }

    #[test]
    fn frozen_matrices_replace_the_computed_ones() {
        let (m, rpv) = biped();
        let spec = filled("attention", 2);
        let readings: Vec<f64> = (0..40).map(|i| (i as f64 * 0.17).cos().abs()).collect();
        let mut live = spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mut a = vec![0.0; 10];
        live.control(0.0, &readings, &mut a);
        let snapshot = crate::plastic_weights(&live).unwrap().to_vec();
        assert_eq!(snapshot.len(), 10 * 16);
        let mut frozen = spec.clone();
        frozen.as_kind_mut().freeze_with(&snapshot).unwrap();
        let mut c = frozen.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mut b = vec![0.0; 10];
        let other: Vec<f64> = readings.iter().map(|x| 1.0 - x).collect();
        c.control(0.0, &other, &mut b);
        assert_eq!(
            crate::plastic_weights(&c).unwrap(),
            &snapshot[..],
            "frozen matrices never change"
        );
        c.control(0.0, &readings, &mut b);
        assert_eq!(a, b, "the same matrices and readings give the same actuations");
        let mut wrong = spec.clone();
        wrong.as_kind_mut().freeze_with(&[0.0; 3]).unwrap();
        assert_invalid(&wrong.build(&BrainShape::grid(&m, &rpv)).err().unwrap(), "frozen");
    }

    #[test]
    fn fixed_attention_genes_leave_the_downstream_as_parameters() {
        let (m, rpv) = biped();
        let source = filled("attention", 4);
        let BrainSpec::Attention(source_spec) = &source else {
            unreachable!()
        };
        let genes = source_spec.attention_genes().unwrap().to_vec();
        assert_eq!(genes, source.parameters()[..32]);
        let transfer = BrainSpec::Attention(AttentionSpec {
            attention: genes,
            ..AttentionSpec::default()
        });
        assert_eq!(transfer.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap(), 41);
        let rebuilt = transfer.with_parameters(&source.parameters()[32..]).unwrap();
        let readings = vec![0.4; 40];
        let (mut a, mut b) = (vec![0.0; 10], vec![0.0; 10]);
        source
            .build(&BrainShape::grid(&m, &rpv))
            .unwrap()
            .control(0.0, &readings, &mut a);
        rebuilt
            .build(&BrainShape::grid(&m, &rpv))
            .unwrap()
            .control(0.0, &readings, &mut b);
        assert_eq!(a, b);
        let bad = BrainSpec::Attention(AttentionSpec {
            attention: vec![0.0; 31],
            ..AttentionSpec::default()
        });
        assert_invalid(
            &bad.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap_err(),
            "attention",
        );
        // the same through transfer_from, wrappers included
        let mut target = BrainSpec::parse("step:0.33:attention").unwrap();
        let wrapped_source = BrainSpec::Step(crate::StepSpec {
            period: 0.33,
            inner: Box::new(source.clone()),
        });
        target.as_kind_mut().transfer_from(&wrapped_source).unwrap();
        assert_eq!(target.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap(), 41);
        let mut slow = BrainSpec::parse("attention:slow").unwrap();
        assert_invalid(&slow.as_kind_mut().transfer_from(&source).unwrap_err(), "attention");
        let mut mlp = BrainSpec::parse("mlp").unwrap();
        assert_invalid(&mlp.as_kind_mut().transfer_from(&source).unwrap_err(), "kind");
        let bad = BrainSpec::parse("attention:0");
        assert!(bad.is_err());
        let err = serde_json::from_str::<BrainSpec>(r#"{"kind": "attention", "d_k": 0}"#)
            .unwrap()
            .parameter_count(&BrainShape::grid(&m, &rpv))
            .unwrap_err();
        assert_invalid(&err, "d_k");
    }
}
