//! The affordance study's voxel controller (thesis §5.1.2.3, thesis-code-facts §7.2): the same
//! Elman network in every voxel, with two outputs (actuation and vote) sent to the six face
//! neighbours, which read them at the next step.
//!
//! Per voxel, with r readings, D neighbour directions and m memory units:
//! - inputs x (r + 2D) = `[own readings…, 2 from direction 0, …, 2 from direction D−1]`, the two
//!   values the neighbour in that direction output at the previous step (actuation, vote), zeros
//!   without a neighbour or at the first step; every input passes through tanh;
//! - `u = tanh(W_x tanh(x))` (m units, no bias);
//! - `h = tanh(b_h + u + W_h h_prev)`, `h_prev` the voxel's h of the previous step (0 at the start);
//! - `y = tanh(b_y + W_y h)`: `y[0]` the actuation, `y[1]` the vote (> 0: passable), published on
//!   [`VOTE`] every step.
//!
//! Parameters, in this order (the original genotype's): W_x (m rows of r + 2D, one row per memory
//! unit), then per memory unit its bias and its m recurrent weights, then per output its bias and
//! its m weights: m(r + 2D) + m(m + 1) + 2(m + 1); 158 for the study (r = 5, D = 6, m = 6).
//!
//! Every tanh is vsrlab's own (`vsrlab_lanes::tanh`, within 2 ulp of the platform's): the same
//! bits on every machine, in scalar and lane form (CHANGELOG.md, 2026-12-06).
//!
//! The original never updates `h_prev` (its memory stays 0, thesis-code-facts §7.2); we update it
//! as the thesis describes, and `inert_memory = true` reproduces the original. Short form:
//! `elman[:<memory units>]`.

use crate::short_form::{self, ShortForm};
use crate::validation::{check_count, check_units, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};
use vsrlab_body::{Channel, Probe};
use vsrlab_lanes::{tanh, Lanes};
/// Four voxels' values, one per lane, in an AVX2 register (used only where the CPU has AVX2).
#[cfg(target_arch = "x86_64")]
type Lane4 = vsrlab_lanes::avx::Avx<4>;
/// Eight voxels' values, one per lane, in an AVX-512 register (used only where the CPU has
/// AVX-512F).
#[cfg(target_arch = "x86_64")]
type Lane8 = vsrlab_lanes::avx512::Avx512<8>;

/// Each voxel's vote this step, in [−1, 1] (> 0: "passable").
pub const VOTE: Channel = Channel::replayed("vote", 1e-3);

/// Outputs per voxel: actuation, vote.
pub const OUTPUTS: usize = 2;

/// Most memory units.
pub const MAX_MEMORY: usize = 1_000;

/// Description of an Elman voxel brain (`{"kind": "elman", "memory": 6, …}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ElmanSpec {
    /// Memory (hidden) units per voxel; default 6, the study's.
    pub memory: usize,
    /// Whether the memory stays at 0 (the original's bug); default false.
    pub inert_memory: bool,
    /// The parameters (empty for a template).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub weights: Vec<f64>,
}

impl Default for ElmanSpec {
    fn default() -> Self {
        ElmanSpec {
            memory: 6,
            inert_memory: false,
            weights: Vec::new(),
        }
    }
}

impl ElmanSpec {
    /// Inputs of one voxel's network, refusing bodies whose voxels read different counts.
    fn inputs(shape: &BrainShape) -> Result<usize, BrainError> {
        let readings = shape.readings().first().copied().unwrap_or(0);
        if shape.readings().iter().any(|&r| r != readings) {
            return Err(BrainError::Invalid {
                field: "kind",
                msg: "an Elman voxel brain needs the same readings on every voxel".into(),
            });
        }
        Ok(readings + OUTPUTS * shape.layout().directions())
    }

    /// m(n + m + 1) + 2(m + 1) for n inputs and m memory units.
    fn count(inputs: usize, m: usize) -> usize {
        m * inputs + m * (m + 1) + OUTPUTS * (m + 1)
    }
}

impl BrainKind for ElmanSpec {
    fn name(&self) -> &'static str {
        "elman"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_units(shape)?;
        if self.memory == 0 || self.memory > MAX_MEMORY {
            return Err(BrainError::Invalid {
                field: "memory",
                msg: format!("must be 1 to {MAX_MEMORY}, got {}", self.memory),
            });
        }
        Ok(ElmanSpec::count(ElmanSpec::inputs(shape)?, self.memory))
    }

    fn parameters(&self) -> &[f64] {
        &self.weights
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("weights", &mut self.weights, params)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        check_count("weights", self.parameter_count(shape)?, self.weights.len())?;
        Ok(Box::new(ElmanController::new(self, shape)?))
    }
}

/// The running brain: per-voxel memory and last outputs.
#[derive(Debug, Clone)]
pub struct ElmanController {
    m: usize,
    inputs: usize,
    readings: usize,
    inert_memory: bool,
    /// W_x rows, then [b_h, W_h row] per unit, then [b_y, W_y row] per output.
    weights: Vec<f64>,
    /// Per unit and direction, the neighbour's unit.
    neighbours: Vec<Option<usize>>,
    directions: usize,
    memory: Vec<f64>,
    outputs: Vec<f64>,
    /// tanh of every unit's outputs of the previous step: the squashed signals its neighbours
    /// read (computed once per unit, not once per neighbour).
    previous: Vec<f64>,
    x: Vec<f64>,
    u: Vec<f64>,
    h: Vec<f64>,
    votes: Vec<f64>,
    /// Four voxels' networks at a time in AVX2 lanes, where the CPU has AVX2 (`think_lanes`,
    /// the same bits).
    #[cfg(target_arch = "x86_64")]
    fours: Option<NetLanes<Lane4>>,
    /// Eight at a time in AVX-512 lanes, where the CPU has AVX-512F (before the fours).
    #[cfg(target_arch = "x86_64")]
    eights: Option<NetLanes<Lane8>>,
}

/// The inputs, units and memories of as many voxels as `L` has lanes, one voxel per lane.
#[derive(Debug, Clone, Default)]
struct NetLanes<L> {
    xs: Vec<L>,
    us: Vec<L>,
    hs: Vec<L>,
    memories: Vec<L>,
}

impl<L: Lanes> NetLanes<L> {
    /// Buffers for `inputs` inputs and `m` memory units, if `available` (the CPU can run `L`).
    fn new(available: bool, inputs: usize, m: usize) -> Option<NetLanes<L>> {
        available.then(|| NetLanes {
            xs: vec![L::splat(0.0); inputs],
            us: vec![L::splat(0.0); m],
            hs: vec![L::splat(0.0); m],
            memories: vec![L::splat(0.0); m],
        })
    }
}

/// `Σ w·x` over the pairs in order, from −0 as `Iterator::sum` of f64 adds them.
#[inline(always)]
fn dot(weights: &[f64], values: &[f64]) -> f64 {
    weights.iter().zip(values).fold(-0.0, |sum, (w, x)| sum + w * x)
}

/// [`dot`] in every lane: each lane the bits of `dot` on its own values.
#[inline(always)]
fn dot_lanes<L: Lanes>(weights: &[f64], values: &[L]) -> L {
    weights
        .iter()
        .zip(values)
        .fold(L::splat(-0.0), |sum, (&w, &x)| sum + L::splat(w) * x)
}

impl ElmanController {
    fn new(spec: &ElmanSpec, shape: &BrainShape) -> Result<ElmanController, BrainError> {
        let layout = shape.layout();
        let (units, directions, m) = (layout.units(), layout.directions(), spec.memory);
        let inputs = ElmanSpec::inputs(shape)?;
        let neighbours = (0..units)
            .flat_map(|u| (0..directions).map(move |d| (u, d)))
            .map(|(u, d)| layout.neighbour(u, d))
            .collect();
        Ok(ElmanController {
            m,
            inputs,
            readings: inputs - OUTPUTS * directions,
            inert_memory: spec.inert_memory,
            weights: spec.weights.clone(),
            neighbours,
            directions,
            memory: vec![0.0; units * m],
            outputs: vec![0.0; units * OUTPUTS],
            previous: vec![0.0; units * OUTPUTS],
            x: vec![0.0; inputs],
            u: vec![0.0; m],
            h: vec![0.0; m],
            votes: vec![0.0; units],
            #[cfg(target_arch = "x86_64")]
            fours: NetLanes::new(vsrlab_lanes::avx::available(), inputs, m),
            #[cfg(target_arch = "x86_64")]
            eights: NetLanes::new(vsrlab_lanes::avx512::available(), inputs, m),
        })
    }

    /// The inputs of `unit` (before tanh) into `self.x`.
    fn gather(&mut self, unit: usize, readings: &[f64]) {
        let r = self.readings;
        self.x[..r].copy_from_slice(&readings[unit * r..(unit + 1) * r]);
        for d in 0..self.directions {
            let slot = &mut self.x[r + OUTPUTS * d..r + OUTPUTS * (d + 1)];
            match self.neighbours[unit * self.directions + d] {
                Some(n) => slot.copy_from_slice(&self.previous[n * OUTPUTS..(n + 1) * OUTPUTS]),
                None => slot.fill(0.0),
            }
        }
    }

    /// One voxel's network on `self.x`: its new memory and two outputs.
    fn think(&mut self, unit: usize) {
        let (m, n) = (self.m, self.inputs);
        // the sensor readings pass through tanh here; the neighbours' signals already did
        // (`previous` holds them squashed; tanh(0) = 0 for a missing neighbour)
        self.x[..self.readings].iter_mut().for_each(|v| *v = tanh(*v));
        let (wx, rest) = self.weights.split_at(m * n);
        let (wh, wy) = rest.split_at(m * (m + 1));
        for (i, u) in self.u.iter_mut().enumerate() {
            *u = tanh(dot(&wx[i * n..(i + 1) * n], &self.x));
        }
        let memory = &mut self.memory[unit * m..(unit + 1) * m];
        for i in 0..m {
            let row = &wh[i * (m + 1)..(i + 1) * (m + 1)];
            self.h[i] = tanh(row[0] + self.u[i] + dot(&row[1..], memory));
        }
        if !self.inert_memory {
            memory.copy_from_slice(&self.h);
        }
        for o in 0..OUTPUTS {
            let row = &wy[o * (m + 1)..(o + 1) * (m + 1)];
            self.outputs[unit * OUTPUTS + o] = tanh(row[0] + dot(&row[1..], &self.h));
        }
    }

    /// [`ElmanController::think`] for the `L::LANES` voxels from `first`, each in its own lane
    /// of `net`, the same operations in the same order (so each voxel gets its scalar bits).
    #[inline(always)]
    fn think_lanes<L: Lanes>(&mut self, net: &mut NetLanes<L>, first: usize, readings: &[f64]) {
        let (m, n, r) = (self.m, self.inputs, self.readings);
        // the inputs of `gather` and the memories, input by input (each lane its voxel's)
        for (i, x) in net.xs[..r].iter_mut().enumerate() {
            *x = L::splat(0.0);
            for lane in 0..L::LANES {
                x.set(lane, readings[(first + lane) * r + i]);
            }
        }
        for d in 0..self.directions {
            for o in 0..OUTPUTS {
                let x = &mut net.xs[r + OUTPUTS * d + o];
                *x = L::splat(0.0);
                for lane in 0..L::LANES {
                    if let Some(k) = self.neighbours[(first + lane) * self.directions + d] {
                        x.set(lane, self.previous[k * OUTPUTS + o]);
                    }
                }
            }
        }
        for (i, h) in net.memories.iter_mut().enumerate() {
            for lane in 0..L::LANES {
                h.set(lane, self.memory[(first + lane) * m + i]);
            }
        }
        for x in &mut net.xs[..self.readings] {
            *x = x.tanh();
        }
        let (wx, rest) = self.weights.split_at(m * n);
        let (wh, wy) = rest.split_at(m * (m + 1));
        for i in 0..m {
            net.us[i] = dot_lanes(&wx[i * n..(i + 1) * n], &net.xs).tanh();
        }
        for i in 0..m {
            let row = &wh[i * (m + 1)..(i + 1) * (m + 1)];
            net.hs[i] = (L::splat(row[0]) + net.us[i] + dot_lanes(&row[1..], &net.memories)).tanh();
        }
        if !self.inert_memory {
            for lane in 0..L::LANES {
                let unit = first + lane;
                for (v, h) in self.memory[unit * m..(unit + 1) * m].iter_mut().zip(&net.hs) {
                    *v = h.get(lane);
                }
            }
        }
        for o in 0..OUTPUTS {
            let row = &wy[o * (m + 1)..(o + 1) * (m + 1)];
            let out = (L::splat(row[0]) + dot_lanes(&row[1..], &net.hs)).tanh();
            for lane in 0..L::LANES {
                self.outputs[(first + lane) * OUTPUTS + o] = out.get(lane);
            }
        }
    }

    /// Every voxel's network: eight at a time in AVX-512 lanes where the CPU has AVX-512F, then
    /// four at a time in AVX2 lanes where it has AVX2, the rest alone.
    fn think_all(&mut self, units: usize, readings: &[f64]) {
        #[allow(unused_mut)]
        let mut done = 0;
        #[cfg(target_arch = "x86_64")]
        {
            if let Some(mut net) = self.eights.take() {
                let end = units / 8 * 8;
                // SAFETY: `eights` is made only where the CPU has AVX-512F
                unsafe { self.think_lanes_avx512(&mut net, done, end, readings) };
                self.eights = Some(net);
                done = end;
            }
            if let Some(mut net) = self.fours.take() {
                let end = done + (units - done) / 4 * 4;
                // SAFETY: `fours` is made only where the CPU has AVX2
                unsafe { self.think_lanes_avx2(&mut net, done, end, readings) };
                self.fours = Some(net);
                done = end;
            }
        }
        for unit in done..units {
            self.gather(unit, readings);
            self.think(unit);
        }
    }

    /// tanh of every output into `previous`: eight at a time in AVX-512 lanes, then four in
    /// AVX2 lanes, where the CPU has them, the rest alone.
    fn squash_outputs(&mut self) {
        #[allow(unused_mut)]
        let mut done = 0;
        #[cfg(target_arch = "x86_64")]
        {
            let total = self.outputs.len();
            if self.eights.is_some() {
                let end = total / 8 * 8;
                // SAFETY: `eights` is made only where the CPU has AVX-512F
                unsafe { self.squash_lanes_avx512(done, end) };
                done = end;
            }
            if self.fours.is_some() {
                let end = done + (total - done) / 4 * 4;
                // SAFETY: `fours` is made only where the CPU has AVX2
                unsafe { self.squash_lanes_avx2(done, end) };
                done = end;
            }
        }
        for (p, o) in self.previous[done..].iter_mut().zip(&self.outputs[done..]) {
            *p = tanh(*o);
        }
    }

    /// tanh of outputs `start..end` into `previous`, `L::LANES` at a time (`end − start` a
    /// multiple of it).
    #[inline(always)]
    fn squash_lanes<L: Lanes>(&mut self, start: usize, end: usize) {
        let outputs = self.outputs[start..end].chunks_exact(L::LANES);
        for (p, o) in self.previous[start..end].chunks_exact_mut(L::LANES).zip(outputs) {
            let mut x = L::splat(0.0);
            for (lane, &v) in o.iter().enumerate() {
                x.set(lane, v);
            }
            let y = x.tanh();
            for (lane, p) in p.iter_mut().enumerate() {
                *p = y.get(lane);
            }
        }
    }

    /// [`ElmanController::squash_lanes`] in AVX2 lanes of four.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn squash_lanes_avx2(&mut self, start: usize, end: usize) {
        self.squash_lanes::<Lane4>(start, end)
    }

    /// [`ElmanController::squash_lanes`] in AVX-512 lanes of eight.
    ///
    /// # Safety
    /// The CPU must support AVX-512F.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn squash_lanes_avx512(&mut self, start: usize, end: usize) {
        self.squash_lanes::<Lane8>(start, end)
    }

    /// The laned networks of voxels `start..end` in AVX2 lanes of four.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn think_lanes_avx2(&mut self, net: &mut NetLanes<Lane4>, start: usize, end: usize, readings: &[f64]) {
        for first in (start..end).step_by(4) {
            self.think_lanes(net, first, readings);
        }
    }

    /// The laned networks of voxels `start..end` in AVX-512 lanes of eight.
    ///
    /// # Safety
    /// The CPU must support AVX-512F.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn think_lanes_avx512(&mut self, net: &mut NetLanes<Lane8>, start: usize, end: usize, readings: &[f64]) {
        for first in (start..end).step_by(8) {
            self.think_lanes(net, first, readings);
        }
    }
}

impl Controller for ElmanController {
    fn reset(&mut self) {
        self.memory.fill(0.0);
        self.outputs.fill(0.0);
        self.previous.fill(0.0);
        self.votes.fill(0.0);
    }

    fn control(&mut self, _t: f64, readings: &[f64], actuations: &mut [f64]) {
        self.think_all(actuations.len(), readings);
        self.squash_outputs();
        for (unit, a) in actuations.iter_mut().enumerate() {
            *a = self.outputs[unit * OUTPUTS];
            self.votes[unit] = self.outputs[unit * OUTPUTS + 1];
        }
    }

    fn publish(&self, probe: &mut dyn Probe) {
        probe.step(&VOTE, &self.votes);
    }
}

/// `elman` (6 memory units) or `elman:<memory units>`.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "elman",
    usage: "elman[:<memory units>]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let memory = match argument {
        None => 6,
        Some(k) => short_form::count(k)?,
    };
    Some(BrainSpec::Elman(ElmanSpec {
        memory,
        ..ElmanSpec::default()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Grid3Layout, UnitSet};
    use vsrlab_body::Capture;

    fn shape(extent: [usize; 3], readings: usize) -> BrainShape {
        let layout = Grid3Layout::from_fn(extent, |_, _, _| true);
        let units = extent.iter().product();
        BrainShape::new(layout, vec![readings; units])
    }

    /// A 5 × 3 × 1 body (15 voxels: a batch of eight, one of four and three alone where the CPU
    /// has AVX-512; three of four and three alone with AVX2 only) with random weights and
    /// readings, memory on and inert: the laned networks give every voxel the actuation and vote
    /// of the one-by-one networks, bit for bit, step after step.
    #[test]
    fn voxels_in_lanes_give_the_bits_of_voxels_one_by_one() {
        const N: usize = 15;
        let sh = shape([5, 3, 1], 5);
        let mut state = 0xE1_u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        for inert_memory in [false, true] {
            let mut spec = ElmanSpec {
                inert_memory,
                ..ElmanSpec::default()
            };
            let count = spec.parameter_count(&sh).unwrap();
            spec.weights = (0..count).map(|_| 2.0 * next()).collect();
            let laned = ElmanController::new(&spec, &sh).unwrap();
            #[allow(unused_mut)]
            let (mut fours, mut alone) = (laned.clone(), laned.clone());
            #[cfg(target_arch = "x86_64")]
            {
                fours.eights = None;
                (alone.eights, alone.fours) = (None, None);
            }
            let mut forms = [laned, fours];
            let mut b = [0.0; N];
            for step in 0..40 {
                let readings: Vec<f64> = (0..N * 5).map(|_| 3.0 * next()).collect();
                alone.control(0.0, &readings, &mut b);
                for (f, form) in forms.iter_mut().enumerate() {
                    let mut a = [0.0; N];
                    form.control(0.0, &readings, &mut a);
                    assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "form {f}, step {step}");
                    assert_eq!(
                        form.votes.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                        alone.votes.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
                    );
                }
            }
            // the memory moved (not zeros compared with zeros)
            assert_eq!(forms[0].memory.iter().any(|&h| h != 0.0), !inert_memory);
        }
    }

    #[test]
    fn the_studys_network_has_158_parameters() {
        let spec = ElmanSpec::default();
        assert_eq!(spec.parameter_count(&shape([3, 3, 1], 5)).unwrap(), 158);
        assert_eq!(
            spec.parameter_count(&shape([1, 1, 1], 5)).unwrap(),
            158,
            "the body does not matter"
        );
        let small = ElmanSpec {
            memory: 2,
            ..ElmanSpec::default()
        };
        // 2·17 + 2·3 + 2·3
        assert_eq!(small.parameter_count(&shape([2, 1, 1], 5)).unwrap(), 46);
        let e = ElmanSpec {
            memory: 0,
            ..ElmanSpec::default()
        }
        .parameter_count(&shape([1, 1, 1], 5));
        assert!(e.unwrap_err().to_string().contains("memory"));
    }

    /// One voxel, memory 1, weights chosen by hand: every formula of the module doc.
    #[test]
    fn one_voxel_computes_the_documented_network_and_remembers() {
        let sh = BrainShape::new(UnitSet::new(1), vec![1]);
        // UnitSet has no directions: inputs = 1 reading
        let (wx, bh, wh, by0, wy0, by1, wy1) = (0.5, 0.1, 0.8, -0.2, 1.5, 0.3, -1.0);
        let spec = ElmanSpec {
            memory: 1,
            inert_memory: false,
            weights: vec![wx, bh, wh, by0, wy0, by1, wy1],
        };
        let mut brain = spec.build(&sh).unwrap();
        let mut a = [0.0];
        let reading = 0.7f64;
        let mut h = 0.0f64;
        for step in 0..3 {
            brain.control(0.0, &[reading], &mut a);
            let u = (wx * reading.tanh()).tanh();
            h = (bh + u + wh * h).tanh();
            let expected = (by0 + wy0 * h).tanh();
            assert!((a[0] - expected).abs() < 1e-15, "step {step}: {} vs {expected}", a[0]);
            let mut capture = Capture::new();
            brain.publish(&mut capture);
            let vote = capture.get(VOTE.name).unwrap()[0];
            assert!((vote - (by1 + wy1 * h).tanh()).abs() < 1e-15);
        }
        // the original's inert memory: every step is the first
        let inert = ElmanSpec {
            inert_memory: true,
            ..spec.clone()
        };
        let mut brain = inert.build(&sh).unwrap();
        let first = (by0 + wy0 * (bh + (wx * reading.tanh()).tanh()).tanh()).tanh();
        for _ in 0..3 {
            brain.control(0.0, &[reading], &mut a);
            assert!((a[0] - first).abs() < 1e-15);
        }
    }

    /// Two voxels side by side: each reads the other's outputs of the previous step in the slot
    /// of the direction it lies in, zeros elsewhere and at the first step.
    #[test]
    fn neighbours_read_each_others_previous_outputs() {
        let sh = shape([2, 1, 1], 0);
        let n = 12; // 0 readings + 2 × 6 directions
        let m = 1;
        let mut weights = vec![0.0; ElmanSpec::count(n, m)];
        // u = tanh(tanh(input from E, actuation slot)) for the left voxel (E = direction 1)
        weights[OUTPUTS] = 1.0;
        // h = tanh(0.5 + u); actuation = tanh(h); vote = tanh(-h)
        weights[m * n] = 0.5;
        let y = m * n + m * (m + 1);
        weights[y + 1] = 1.0;
        weights[y + m + 2] = -1.0;
        let spec = ElmanSpec {
            memory: 1,
            inert_memory: true,
            weights,
        };
        let mut brain = spec.build(&sh).unwrap();
        let mut a = [0.0; 2];
        brain.control(0.0, &[], &mut a);
        let first = 0.5f64.tanh().tanh();
        assert!((a[0] - first).abs() < 1e-15 && (a[1] - first).abs() < 1e-15, "{a:?}");
        brain.control(0.0, &[], &mut a);
        // the left voxel read the right one's actuation (first) through its E slot
        let left = (0.5 + first.tanh().tanh()).tanh().tanh();
        assert!((a[0] - left).abs() < 1e-15, "{a:?}");
        // the right voxel's E slot is empty (no neighbour): unchanged
        assert!((a[1] - first).abs() < 1e-15, "{a:?}");
        brain.reset();
        brain.control(0.0, &[], &mut a);
        assert!((a[0] - first).abs() < 1e-15, "reset clears the signals");
    }
}
