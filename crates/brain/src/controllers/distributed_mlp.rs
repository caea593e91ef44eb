//! Distributed MLP controller with neighbour signals (2D-VSR-Sim `DistributedSensing` at HEAD,
//! vsr-model.md §4.4, thesis §2.2.2.1): every voxel runs its own MLP on its own readings and on the
//! signals its neighbours sent it at the previous control step.
//!
//! # Wiring
//!
//! Neighbours are those of the body's [`crate::UnitLayout`], D directions per unit. On a 2D grid
//! ([`crate::GridLayout`], D = 4) the directions come in the fixed order N, E, S, W with grid
//! offsets N = (0, −1), E = (+1, 0), S = (0, +1), W = (−1, 0). Since y = 0 is the bottom row, "N"
//! is physically the voxel *below* and "S" the one above; only the index semantics matter. A 3D
//! grid ([`crate::Grid3Layout`]) has D = 6, a ring D = 2; every formula below with 4 reads D there.
//!
//! With `s` signals per direction and `r` readings per voxel (the same on every voxel), on a 2D
//! grid:
//! - inputs (r + 4s) = `[own readings…, s from N, s from E, s from S, s from W]`, where the block
//!   "from d" is the block the neighbour in direction d emitted towards this voxel, i.e. that
//!   neighbour's output block for the opposite direction; a missing neighbour gives zeros;
//! - outputs (1 + 4s) = `[actuation, s towards N, s towards E, s towards S, s towards W]`.
//!
//! Signals have exactly one control step of delay: at each call all voxels first read the signals
//! emitted at the previous call (zeros at the first call and after [`Controller::reset`]), then all
//! emit new ones (synchronous update, HEAD semantics since 2021-10-20).
//!
//! # Parameter layout
//!
//! One network has sizes `[r + 4s, hidden…, 1 + 4s]` and n_w = [`Mlp::parameter_count`] weights
//! (layout in [`crate::mlp`]); with r = 4, s = 1 and no hidden layer: 8 inputs, 5 outputs, 45 weights.
//! - homogeneous: the n_w weights are shared by all voxels (count n_w, whatever the body);
//! - heterogeneous: one block per grid cell, empty cells included (count W·H·n_w); the voxel at
//!   (x, y) uses `weights[(y·W + x)·n_w .. (y·W + x + 1)·n_w]`. 10×10 grid: 4500; 5×5: 1125. In
//!   general one block per slot of the layout ([`crate::UnitLayout::slot`]; W·H·D on a 3D grid).
//!
//! # Positional encoding
//!
//! With `positional = true` (thesis §4.2.3.1, the baselines of the attention chapter) the own
//! readings enter as a one-hot block: voxel i of n sees n·r reading inputs, all 0 but block i,
//! which holds its r readings. The network then has n·r + 4s inputs, so the weights depend on the
//! body's voxel count; with s = 0 and no hidden layer this is the thesis' "MLP" (n·r + 1 weights:
//! 41 on a biped-4x3 with 4 readings), with s = 1 its "MLP-Comm" (5·(n·r + 5) = 225).
//!
//! Short forms: `distributed-mlp[:<signals>]` (homogeneous) and
//! `distributed-mlp-hetero[:<signals>]` (heterogeneous), both without hidden layer, default 1 signal;
//! `local-mlp[:<signals>]`: homogeneous, positional, default 0 signals.

use crate::mlp::{check_at_most, check_parameter_total, Activation, Mlp};
use crate::short_form::{self, ShortForm};
use crate::validation::{check_count, check_units, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};

/// How the voxels' networks get their weights.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Layout {
    /// One weight vector shared by every voxel.
    #[default]
    Homogeneous,
    /// One weight block per grid cell (W·H blocks, empty cells included; a layout's slots).
    Heterogeneous,
}

/// Sizes of one voxel's network with D neighbour directions: `[r + D·s, hidden…, 1 + D·s]`
/// (D = 4 on a 2D grid).
pub fn network_sizes(readings: usize, directions: usize, signals: usize, hidden: &[usize]) -> Vec<usize> {
    let mut sizes = Vec::with_capacity(hidden.len() + 2);
    let all = signals.saturating_mul(directions);
    sizes.push(readings.saturating_add(all));
    sizes.extend_from_slice(hidden);
    sizes.push(all.saturating_add(1));
    sizes
}

/// Most signals per direction.
pub const MAX_SIGNALS: usize = 1_000;

/// Refuses more than [`MAX_SIGNALS`] signals, naming `signals`.
fn check_signals(signals: usize) -> Result<(), BrainError> {
    check_at_most("signals", "signals per direction", signals, MAX_SIGNALS)
}

/// [`parameter_count`], checked: shape errors and totals above [`crate::mlp::MAX_PARAMETERS`].
fn checked_parameter_count(
    shape: &BrainShape,
    readings: usize,
    signals: usize,
    hidden: &[usize],
    layout: Layout,
) -> Result<usize, BrainError> {
    check_signals(signals)?;
    Mlp::check_sizes(&network_sizes(readings, shape.layout().directions(), signals, hidden))?;
    let total = parameter_count(shape, readings, signals, hidden, layout);
    check_parameter_total(total)?;
    Ok(total)
}

/// The readings count shared by all voxels, or an error naming `readings_per_voxel`.
pub fn common_readings(shape: &BrainShape) -> Result<usize, BrainError> {
    let readings_per_voxel = shape.readings();
    let Some(&first) = readings_per_voxel.first() else {
        return Err(BrainError::Invalid {
            field: "readings_per_voxel",
            msg: "no voxel: the body is empty".into(),
        });
    };
    if let Some(v) = readings_per_voxel.iter().position(|&r| r != first) {
        let layout = shape.layout();
        let cell = |i: usize| {
            if i < layout.units() {
                layout.cell_text(i)
            } else {
                "?".to_string()
            }
        };
        return Err(BrainError::Invalid {
            field: "readings_per_voxel",
            msg: format!(
                "this brain needs the same number of readings on every voxel, but voxel 0 at {} has {first} \
                 and voxel {v} at {} has {} (check the sensors)",
                cell(0),
                cell(v),
                readings_per_voxel[v]
            ),
        });
    }
    Ok(first)
}

/// Reading inputs of one network: r, or n·r with positional encoding.
fn reading_inputs(readings: usize, voxels: usize, positional: bool) -> usize {
    if positional {
        readings.saturating_mul(voxels)
    } else {
        readings
    }
}

/// Number of weights for a body: n_w (homogeneous) or W·H·n_w (heterogeneous: one block per slot
/// of the layout).
pub fn parameter_count(shape: &BrainShape, readings: usize, signals: usize, hidden: &[usize], layout: Layout) -> usize {
    let sizes = network_sizes(readings, shape.layout().directions(), signals, hidden);
    let per_network = Mlp::parameter_count(&sizes);
    match layout {
        Layout::Homogeneous => per_network,
        Layout::Heterogeneous => shape.layout().slots().saturating_mul(per_network),
    }
}

/// The shape of a distributed controller: everything but the body and the weights.
#[derive(Debug, Clone, PartialEq)]
pub struct DistributedConfig {
    /// Signals per direction (s).
    pub signals: usize,
    /// Hidden layer sizes of each voxel's network.
    pub hidden: Vec<usize>,
    /// Activation of every layer.
    pub activation: Activation,
    /// Whether the activation is applied to the raw inputs first.
    pub input_activation: bool,
    /// Shared or per-cell weights.
    pub layout: Layout,
    /// Own readings as a one-hot block of n·r inputs (module documentation).
    pub positional: bool,
}

/// One MLP per voxel exchanging signals with its neighbours (module documentation).
#[derive(Debug, Clone)]
pub struct DistributedMlpController {
    signals: usize,
    /// Neighbour directions per voxel (D).
    directions: usize,
    /// Per direction: the opposite one.
    opposite: Vec<usize>,
    readings: usize,
    /// Reading inputs of a network: r, or n·r with positional encoding.
    reading_inputs: usize,
    positional: bool,
    n_in: usize,
    n_out: usize,
    /// One network (homogeneous) or one per voxel (heterogeneous).
    networks: Vec<Mlp>,
    /// Per voxel: index into `networks`.
    network_of: Vec<usize>,
    /// Per voxel and direction (voxel-major, D per voxel): the neighbour's voxel index.
    neighbours: Vec<Option<usize>>,
    /// Per voxel: the D·s signals it emitted at the last call (one block per direction).
    emitted: Vec<f64>,
    /// Per voxel: the n_in inputs of the last call.
    inputs: Vec<f64>,
    /// Every voxel's values of one layer (voxel-major), then of the next: the layers of all
    /// networks go through the activation together (in vector lanes).
    current: Vec<f64>,
    next: Vec<f64>,
}

impl DistributedMlpController {
    /// Builds the controller; `weights` must have [`parameter_count`] entries for this body.
    pub fn new(shape: &BrainShape, config: &DistributedConfig, weights: &[f64]) -> Result<Self, BrainError> {
        let DistributedConfig {
            signals,
            ref hidden,
            activation,
            input_activation,
            layout,
            positional,
        } = *config;
        check_units(shape)?;
        let readings = common_readings(shape)?;
        let units = shape.units();
        let reading_inputs = reading_inputs(readings, units, positional);
        let expected = checked_parameter_count(shape, reading_inputs, signals, hidden, layout)?;
        let grid = shape.layout();
        let directions = grid.directions();
        let sizes = network_sizes(reading_inputs, directions, signals, hidden);
        check_count("weights", expected, weights.len())?;
        let n_w = Mlp::parameter_count(&sizes);
        let neighbours = (0..units)
            .flat_map(|v| (0..directions).map(move |d| grid.neighbour(v, d)))
            .collect();
        let block = |slot: usize| weights[slot * n_w..(slot + 1) * n_w].to_vec();
        let (networks, network_of) = match layout {
            Layout::Homogeneous => (
                vec![Mlp::new(sizes.clone(), activation, input_activation, block(0))?],
                vec![0; units],
            ),
            Layout::Heterogeneous => (
                (0..units)
                    .map(|v| Mlp::new(sizes.clone(), activation, input_activation, block(grid.slot(v))))
                    .collect::<Result<Vec<_>, _>>()?,
                (0..units).collect(),
            ),
        };
        let (n_in, n_out) = (sizes[0], sizes[sizes.len() - 1]);
        let layer_values = units * networks[0].scratch_len() / 2;
        Ok(DistributedMlpController {
            signals,
            directions,
            opposite: (0..directions).map(|d| grid.opposite(d)).collect(),
            readings,
            reading_inputs,
            positional,
            n_in,
            n_out,
            networks,
            network_of,
            neighbours,
            emitted: vec![0.0; units * directions * signals],
            inputs: vec![0.0; units * n_in],
            current: vec![0.0; layer_values],
            next: vec![0.0; layer_values],
        })
    }

    /// Signals per direction (s).
    pub fn signals(&self) -> usize {
        self.signals
    }

    /// Neighbour directions per voxel (D: 4 on a 2D grid, 6 on a 3D grid).
    pub fn directions(&self) -> usize {
        self.directions
    }

    /// The voxel's neighbours in the layout's directions (on a 2D grid N, E, S, W; voxel
    /// indices, `None` where no voxel).
    pub fn neighbours(&self, voxel: usize) -> &[Option<usize>] {
        &self.neighbours[voxel * self.directions..(voxel + 1) * self.directions]
    }

    /// The D·s signals the voxel received at the last call, one block per direction in the
    /// layout's order (zeros before the first call).
    pub fn incoming(&self, voxel: usize) -> &[f64] {
        &self.inputs[voxel * self.n_in + self.reading_inputs..(voxel + 1) * self.n_in]
    }

    /// The D·s signals the voxel emitted at the last call, one block towards each direction.
    pub fn emitted(&self, voxel: usize) -> &[f64] {
        let all = self.directions * self.signals;
        &self.emitted[voxel * all..(voxel + 1) * all]
    }
}

impl DistributedMlpController {
    /// Every voxel's network on its inputs, layer by layer, into `current` (voxel-major, n_out
    /// per voxel): the bits of each network's [`Mlp::apply`], with each layer's activation applied
    /// to all voxels' neurons at once.
    fn forward_all(&mut self) {
        let units = self.network_of.len();
        let first = &self.networks[0];
        let (sizes, act) = (first.sizes(), first.activation());
        let values = units * self.n_in;
        self.current[..values].copy_from_slice(&self.inputs);
        if first.input_activation() {
            act.apply_in_place(&mut self.current[..values]);
        }
        for layer in 0..sizes.len() - 1 {
            let (n_src, n_dst) = (sizes[layer], sizes[layer + 1]);
            for (v, &network) in self.network_of.iter().enumerate() {
                let src = &self.current[v * n_src..(v + 1) * n_src];
                self.networks[network].layer_sums(layer, src, &mut self.next[v * n_dst..(v + 1) * n_dst]);
            }
            act.apply_in_place(&mut self.next[..units * n_dst]);
            std::mem::swap(&mut self.current, &mut self.next);
        }
    }
}

impl Controller for DistributedMlpController {
    fn reset(&mut self) {
        self.emitted.fill(0.0);
        self.inputs.fill(0.0);
    }

    fn control(&mut self, _t: f64, readings: &[f64], actuations: &mut [f64]) {
        let (r, s, n_in, ri) = (self.readings, self.signals, self.n_in, self.reading_inputs);
        let directions = self.directions;
        let all = directions * s;
        let units = self.network_of.len();
        debug_assert_eq!(readings.len(), r * units);
        debug_assert_eq!(actuations.len(), units);
        // Gather every voxel's inputs from the previous step's signals before anyone emits.
        for v in 0..units {
            let input = &mut self.inputs[v * n_in..(v + 1) * n_in];
            // positional: block v of the n·r reading inputs; the others stay 0
            let own = if self.positional { v * r } else { 0 };
            input[own..own + r].copy_from_slice(&readings[v * r..(v + 1) * r]);
            let neighbours = &self.neighbours[v * directions..(v + 1) * directions];
            for (d, neighbour) in neighbours.iter().enumerate() {
                let slot = &mut input[ri + d * s..ri + (d + 1) * s];
                match neighbour {
                    Some(n) => {
                        let from = n * all + self.opposite[d] * s;
                        slot.copy_from_slice(&self.emitted[from..from + s]);
                    }
                    None => slot.fill(0.0),
                }
            }
        }
        self.forward_all();
        let n_out = self.n_out;
        for (v, a) in actuations.iter_mut().enumerate() {
            let outputs = &self.current[v * n_out..(v + 1) * n_out];
            *a = outputs[0].clamp(-1.0, 1.0);
            self.emitted[v * all..(v + 1) * all].copy_from_slice(&outputs[1..]);
        }
    }
}

/// Description of a distributed MLP brain (`{"kind": "distributed-mlp", …}`): one MLP per voxel with
/// neighbour signals (module documentation). Every field has a default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct DistributedMlpSpec {
    /// Signals per direction s (default 1).
    pub signals: usize,
    /// Hidden layer sizes of each voxel's network (default none).
    pub hidden: Vec<usize>,
    /// Activation of every layer (default tanh).
    pub activation: Activation,
    /// Apply the activation to the raw inputs first (2D-VSR-Sim ≥ v1.9.1; default true).
    pub input_activation: bool,
    /// `homogeneous` (one shared weight vector, default) or `heterogeneous` (one per grid cell).
    pub layout: Layout,
    /// Own readings as a one-hot block of n·r inputs (default false; module documentation).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub positional: bool,
    /// The weights: n_w (homogeneous) or W·H·n_w (heterogeneous); default none (a template).
    pub weights: Vec<f64>,
}

impl Default for DistributedMlpSpec {
    fn default() -> Self {
        DistributedMlpSpec {
            signals: 1,
            hidden: Vec::new(),
            activation: Activation::Tanh,
            input_activation: true,
            layout: Layout::Homogeneous,
            positional: false,
            weights: Vec::new(),
        }
    }
}

impl BrainKind for DistributedMlpSpec {
    fn name(&self) -> &'static str {
        "distributed-mlp"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_units(shape)?;
        let readings = common_readings(shape)?;
        let inputs = reading_inputs(readings, shape.units(), self.positional);
        checked_parameter_count(shape, inputs, self.signals, &self.hidden, self.layout)
    }

    fn parameters(&self) -> &[f64] {
        &self.weights
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("weights", &mut self.weights, params)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        let config = DistributedConfig {
            signals: self.signals,
            hidden: self.hidden.clone(),
            activation: self.activation,
            input_activation: self.input_activation,
            layout: self.layout,
            positional: self.positional,
        };
        Ok(Box::new(DistributedMlpController::new(shape, &config, &self.weights)?))
    }
}

/// `distributed-mlp[:<signals>]`: homogeneous, no hidden layer.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "distributed-mlp",
    usage: "distributed-mlp[:<signals>]",
    parse: parse_homogeneous,
};

/// `distributed-mlp-hetero[:<signals>]`: heterogeneous, no hidden layer.
pub const HETEROGENEOUS_SHORT_FORM: ShortForm = ShortForm {
    name: "distributed-mlp-hetero",
    usage: "distributed-mlp-hetero[:<signals>]",
    parse: parse_heterogeneous,
};

fn parse_homogeneous(argument: Option<&str>) -> Option<BrainSpec> {
    parse_short_form(argument, Layout::Homogeneous)
}

fn parse_heterogeneous(argument: Option<&str>) -> Option<BrainSpec> {
    parse_short_form(argument, Layout::Heterogeneous)
}

/// `local-mlp[:<signals>]`: homogeneous, positional encoding, default 0 signals (the attention
/// chapter's MLP; `local-mlp:1` is its MLP-Comm).
pub const LOCAL_SHORT_FORM: ShortForm = ShortForm {
    name: "local-mlp",
    usage: "local-mlp[:<signals>]",
    parse: parse_local,
};

fn parse_local(argument: Option<&str>) -> Option<BrainSpec> {
    let signals = match argument {
        None => 0,
        Some(signals) => short_form::count(signals)?,
    };
    Some(BrainSpec::DistributedMlp(DistributedMlpSpec {
        signals,
        positional: true,
        ..DistributedMlpSpec::default()
    }))
}

/// `[<signals>]`: signals per direction, default 1; no hidden layer.
fn parse_short_form(argument: Option<&str>, layout: Layout) -> Option<BrainSpec> {
    let signals = match argument {
        None => 1,
        Some(signals) => short_form::count(signals)?,
    };
    Some(BrainSpec::DistributedMlp(DistributedMlpSpec {
        signals,
        layout,
        ..DistributedMlpSpec::default()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped, build_error};
    use vsrlab_body::Morphology;

    fn config(
        signals: usize,
        hidden: &[usize],
        activation: Activation,
        input_activation: bool,
        layout: Layout,
    ) -> DistributedConfig {
        DistributedConfig {
            signals,
            hidden: hidden.to_vec(),
            activation,
            input_activation,
            layout,
            positional: false,
        }
    }

    /// Weights of one network with `r` readings, `s` signals, no hidden layer, identity activation:
    /// each output neuron's bias and source weights given by `f(output, source)`, bias = source None.
    fn weights(r: usize, s: usize, f: impl Fn(usize, Option<usize>) -> f64) -> Vec<f64> {
        let (n_in, n_out) = (r + 4 * s, 1 + 4 * s);
        let mut w = Vec::new();
        for o in 0..n_out {
            w.push(f(o, None));
            for i in 0..n_in {
                w.push(f(o, Some(i)));
            }
        }
        w
    }

    #[test]
    fn parameter_counts_match_the_thesis() {
        let sizes = network_sizes(4, 4, 1, &[]);
        assert_eq!(sizes, vec![8, 5]);
        assert_eq!(Mlp::parameter_count(&sizes), 45);
        let m10 = Morphology::named("box-10x10").unwrap();
        let m5 = Morphology::named("box-5x5").unwrap();
        let single = Morphology::from_fn(10, 10, |x, y| x == 3 && y == 4).unwrap();
        assert_eq!(
            parameter_count(&BrainShape::grid(&m10, &[]), 4, 1, &[], Layout::Homogeneous),
            45
        );
        assert_eq!(
            parameter_count(&BrainShape::grid(&m10, &[]), 4, 1, &[], Layout::Heterogeneous),
            4500
        );
        assert_eq!(
            parameter_count(&BrainShape::grid(&single, &[]), 4, 1, &[], Layout::Heterogeneous),
            4500
        );
        assert_eq!(
            parameter_count(&BrainShape::grid(&m5, &[]), 4, 1, &[], Layout::Heterogeneous),
            1125
        );
        // s = 2, hidden 6: sizes [12, 6, 9] → 6·13 + 9·7 = 141
        assert_eq!(
            parameter_count(&BrainShape::grid(&m5, &[]), 4, 2, &[6], Layout::Homogeneous),
            141
        );
    }

    /// Each voxel emits, in every direction, its own first reading (1 reading, s = 1, identity);
    /// so a single voxel with a nonzero reading is the only emitter. The actuation reports nothing.
    fn relay(m: &Morphology) -> DistributedMlpController {
        let w = weights(1, 1, |o, i| if o >= 1 && i == Some(0) { 1.0 } else { 0.0 });
        let rpv = vec![1; m.voxel_count()];
        DistributedMlpController::new(
            &BrainShape::grid(m, &rpv),
            &config(1, &[], Activation::Identity, false, Layout::Homogeneous),
            &w,
        )
        .unwrap()
    }

    #[test]
    fn a_signal_reaches_exactly_the_neighbours_one_step_later_on_the_right_slot() {
        // a plus shape with a hole: centre (1, 1) has neighbours N = (1, 0), E = (2, 1), W = (0, 1);
        // (1, 2) is empty, so the centre has no S neighbour
        let m = Morphology::from_rows(&["#.#", "###", ".#."]).unwrap();
        let cells: Vec<(usize, usize)> = m.voxels().collect();
        let index = |x: usize, y: usize| cells.iter().position(|&c| c == (x, y)).unwrap();
        let centre = index(1, 1);
        let mut c = relay(&m);
        assert_eq!(
            c.neighbours(centre),
            [Some(index(1, 0)), Some(index(2, 1)), None, Some(index(0, 1))]
        );
        let n = m.voxel_count();
        let mut readings = vec![0.0; n];
        readings[centre] = 0.75;
        let mut a = vec![0.0; n];

        c.control(1.0 / 60.0, &readings, &mut a);
        // step 1: nobody has received anything yet; only the centre emitted
        for v in 0..n {
            assert_eq!(c.incoming(v), &[0.0; 4], "voxel {v} at step 1");
            let expected = if v == centre { [0.75; 4] } else { [0.0; 4] };
            assert_eq!(c.emitted(v), &expected, "voxel {v} emitted at step 1");
        }

        readings[centre] = 0.0;
        c.control(2.0 / 60.0, &readings, &mut a);
        // step 2: the centre's neighbour below (its N) receives it from its S, and so on
        let expected_incoming = |v: usize| -> [f64; 4] {
            let mut e = [0.0; 4];
            if v == index(1, 0) {
                e[2] = 0.75; // the centre is this voxel's S neighbour
            } else if v == index(2, 1) {
                e[3] = 0.75; // … its W neighbour
            } else if v == index(0, 1) {
                e[1] = 0.75; // … its E neighbour
            }
            e
        };
        for (v, cell) in cells.iter().enumerate() {
            assert_eq!(c.incoming(v), &expected_incoming(v), "voxel {v} at {cell:?}, step 2");
        }
        // the voxels above the centre's row are not its neighbours and got nothing
        assert_eq!(c.incoming(index(0, 2)), &[0.0; 4]);
        assert_eq!(c.incoming(index(2, 2)), &[0.0; 4]);

        // step 3: the wave has moved on: the centre gets nothing back (its neighbours emitted 0)
        c.control(3.0 / 60.0, &readings, &mut a);
        assert_eq!(c.incoming(centre), &[0.0; 4]);
    }

    #[test]
    fn a_direction_specific_signal_reaches_only_the_neighbour_it_was_sent_to() {
        // s = 2; emitter sends its reading only on the second signal towards E; actuation = input
        // "second signal from W" (input index r + 3·2 + 1 = 8)
        let (r, s) = (1, 2);
        let w = weights(r, s, |o, i| match (o, i) {
            (0, Some(8)) => 1.0, // actuation ← from W, signal 1
            (4, Some(0)) => 1.0, // output 4 = towards E (block 1), signal 1
            _ => 0.0,
        });
        let m = Morphology::named("box-3x2").unwrap();
        let rpv = vec![r; 6];
        let mut c = DistributedMlpController::new(
            &BrainShape::grid(&m, &rpv),
            &config(s, &[], Activation::Identity, true, Layout::Homogeneous),
            &w,
        )
        .unwrap();
        let mut readings = vec![0.0; 6];
        readings[0] = 0.5; // voxel 0 = (0, 0); its E neighbour is voxel 1 = (1, 0)
        let mut a = vec![0.0; 6];
        c.control(1.0 / 60.0, &readings, &mut a);
        assert_eq!(a, vec![0.0; 6], "no signal at the first step");
        c.control(2.0 / 60.0, &readings, &mut a);
        // only voxel 1 received it, in the second slot of its W block (identity everywhere)
        assert_eq!(a, vec![0.0, 0.5, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(c.incoming(1), &[0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.5]);
        for v in [0, 2, 3, 4, 5] {
            assert_eq!(c.incoming(v), &[0.0; 8], "voxel {v}");
        }
    }

    #[test]
    fn absent_neighbours_give_zero_even_when_everyone_emits() {
        // every voxel emits a constant 1 in every direction (bias); incoming counts neighbours
        let w = weights(0, 1, |o, i| if o >= 1 && i.is_none() { 1.0 } else { 0.0 });
        let m = Morphology::named("biped-4x3").unwrap();
        let rpv = vec![0; m.voxel_count()];
        let mut c = DistributedMlpController::new(
            &BrainShape::grid(&m, &rpv),
            &config(1, &[], Activation::Identity, false, Layout::Homogeneous),
            &w,
        )
        .unwrap();
        let mut a = vec![0.0; m.voxel_count()];
        c.control(1.0 / 60.0, &[], &mut a);
        c.control(2.0 / 60.0, &[], &mut a);
        for (v, (x, y)) in m.voxels().enumerate() {
            for (d, (dx, dy)) in crate::layout::grid::DIRECTION_OFFSETS.iter().enumerate() {
                let (nx, ny) = (x as isize + dx, y as isize + dy);
                let present = nx >= 0 && ny >= 0 && m.has(nx as usize, ny as usize);
                let expected = if present { 1.0 } else { 0.0 };
                assert_eq!(c.incoming(v)[d], expected, "voxel ({x}, {y}) direction {d}");
            }
        }
        c.reset();
        assert!((0..m.voxel_count()).all(|v| c.incoming(v) == [0.0; 4] && c.emitted(v) == [0.0; 4]));
    }

    #[test]
    fn heterogeneous_with_equal_blocks_equals_homogeneous() {
        let m = Morphology::named("comb-5x3").unwrap();
        let (r, s, hidden) = (3, 2, [5]);
        let n_w = Mlp::parameter_count(&network_sizes(r, 4, s, &hidden));
        let block: Vec<f64> = (0..n_w).map(|i| ((i * 37 % 23) as f64 / 11.5) - 1.0).collect();
        let all: Vec<f64> = (0..15).flat_map(|_| block.iter().copied()).collect();
        let rpv = vec![r; m.voxel_count()];
        let [mut ho, mut he] = [(Layout::Homogeneous, &block), (Layout::Heterogeneous, &all)].map(|(layout, w)| {
            DistributedMlpController::new(
                &BrainShape::grid(&m, &rpv),
                &config(s, &hidden, Activation::Tanh, true, layout),
                w,
            )
            .unwrap()
        });
        let n = m.voxel_count();
        let (mut a1, mut a2) = (vec![0.0; n], vec![0.0; n]);
        for k in 1..=50 {
            let t = k as f64 / 60.0;
            let readings: Vec<f64> = (0..n * r).map(|i| (t * (i + 1) as f64).sin()).collect();
            ho.control(t, &readings, &mut a1);
            he.control(t, &readings, &mut a2);
            assert_eq!(a1, a2, "step {k}");
            assert!(a1.iter().all(|a| (-1.0..=1.0).contains(a)));
        }
    }

    #[test]
    fn all_voxels_at_once_give_each_network_s_own_bits() {
        // 15 voxels with their own weights and a hidden layer: each layer's tanh runs over every
        // voxel's neurons together, and must give what each voxel's network gives alone
        let m = Morphology::named("comb-5x3").unwrap();
        let (r, s, hidden) = (3, 2, [7]);
        let sizes = network_sizes(r, 4, s, &hidden);
        let n_w = Mlp::parameter_count(&sizes);
        let n = m.voxel_count();
        let rpv = vec![r; n];
        let shape = BrainShape::grid(&m, &rpv);
        let grid = shape.layout();
        let all: Vec<f64> = (0..grid.slots() * n_w)
            .map(|i| ((i * 7919 % 1013) as f64 / 250.0) - 2.0)
            .collect();
        let mut c = DistributedMlpController::new(
            &BrainShape::grid(&m, &rpv),
            &config(s, &hidden, Activation::Tanh, true, Layout::Heterogeneous),
            &all,
        )
        .unwrap();
        let mut actuations = vec![0.0; n];
        let mut scratch = vec![0.0; 64];
        for k in 1..=20 {
            let t = k as f64 / 60.0;
            let readings: Vec<f64> = (0..n * r).map(|i| 3.0 * (t * (i + 1) as f64).sin()).collect();
            c.control(t, &readings, &mut actuations);
            for v in 0..n {
                let block = &all[grid.slot(v) * n_w..(grid.slot(v) + 1) * n_w];
                let alone = Mlp::new(sizes.clone(), Activation::Tanh, true, block.to_vec()).unwrap();
                let inputs: Vec<f64> = readings[v * r..(v + 1) * r]
                    .iter()
                    .chain(c.incoming(v))
                    .copied()
                    .collect();
                let mut out = vec![0.0; 1 + 4 * s];
                alone.apply(&inputs, &mut out, &mut scratch);
                assert_eq!(
                    actuations[v].to_bits(),
                    out[0].clamp(-1.0, 1.0).to_bits(),
                    "step {k}, voxel {v}"
                );
                assert_eq!(c.emitted(v), &out[1..], "step {k}, voxel {v}");
            }
        }
    }

    #[test]
    fn heterogeneous_blocks_are_indexed_by_grid_cell() {
        // 2×2 grid with (1, 0) empty; each cell's block has actuation bias = its cell index
        let m = Morphology::from_rows(&["##", "#."]).unwrap();
        let n_w = Mlp::parameter_count(&network_sizes(0, 4, 1, &[]));
        let mut w = vec![0.0; 4 * n_w];
        for cell in 0..4 {
            w[cell * n_w] = cell as f64 / 10.0;
        }
        let mut c = DistributedMlpController::new(
            &BrainShape::grid(&m, &[0, 0, 0]),
            &config(1, &[], Activation::Identity, false, Layout::Heterogeneous),
            &w,
        )
        .unwrap();
        let mut a = vec![0.0; 3];
        c.control(1.0 / 60.0, &[], &mut a);
        // voxels in grid order: (0, 0) → cell 0, (0, 1) → cell 2, (1, 1) → cell 3
        assert_eq!(a, vec![0.0, 0.2, 0.3]);
    }

    #[test]
    fn unequal_readings_and_wrong_weight_counts_are_errors() {
        let m = Morphology::named("worm-3x1").unwrap();
        let err = DistributedMlpController::new(
            &BrainShape::grid(&m, &[4, 4, 5]),
            &config(1, &[], Activation::Tanh, true, Layout::Homogeneous),
            &[],
        )
        .unwrap_err();
        assert_invalid(&err, "readings_per_voxel");
        assert!(
            err.to_string()
                .contains("voxel 0 at (0, 0) has 4 and voxel 2 at (2, 0) has 5"),
            "{err}"
        );
        let err = DistributedMlpController::new(
            &BrainShape::grid(&m, &[4, 4, 4]),
            &config(1, &[], Activation::Tanh, true, Layout::Heterogeneous),
            &[0.0; 45],
        )
        .unwrap_err();
        assert_eq!(
            err,
            BrainError::Invalid {
                field: "weights",
                msg: "expected 135 for this body and sensors, got 45".into()
            }
        );
    }

    fn homogeneous() -> BrainSpec {
        BrainSpec::parse("distributed-mlp").unwrap()
    }

    #[test]
    fn the_spec_counts_the_thesis_values() {
        let m10 = Morphology::named("box-10x10").unwrap();
        let m5 = Morphology::named("box-5x5").unwrap();
        let hetero = BrainSpec::parse("distributed-mlp-hetero").unwrap();
        assert_eq!(
            homogeneous().parameter_count(&BrainShape::grid(&m10, &[4; 100])),
            Ok(45)
        );
        assert_eq!(hetero.parameter_count(&BrainShape::grid(&m10, &[4; 100])), Ok(4500));
        assert_eq!(hetero.parameter_count(&BrainShape::grid(&m5, &[4; 25])), Ok(1125));
        let single = Morphology::from_fn(5, 5, |x, y| (x, y) == (2, 2)).unwrap();
        assert_eq!(hetero.parameter_count(&BrainShape::grid(&single, &[4])), Ok(1125));
    }

    #[test]
    fn the_spec_rejects_wrong_and_non_finite_weights_and_unequal_readings() {
        let (_, rpv) = biped();
        let err = build_error(&homogeneous().with_parameters(&[0.1; 44]).unwrap(), &rpv);
        assert_eq!(
            err.to_string(),
            "brain.weights: expected 45 for this body and sensors, got 44"
        );

        let mut w = vec![0.0; 45];
        w[3] = f64::INFINITY;
        let with_inf = BrainSpec::DistributedMlp(DistributedMlpSpec {
            weights: w,
            ..DistributedMlpSpec::default()
        });
        let err = build_error(&with_inf, &rpv);
        assert_invalid(&err, "weights");
        assert!(err.to_string().contains("value 3 is inf"), "{err}");

        let err = build_error(&homogeneous(), &[4, 4, 4, 4, 4, 4, 4, 4, 4, 3]);
        assert_invalid(&err, "readings_per_voxel");
    }

    #[test]
    fn a_built_distributed_brain_is_deterministic_across_reset() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("distributed-mlp-hetero:2")
            .unwrap()
            .with_random_parameters(3, &BrainShape::grid(&m, &rpv))
            .unwrap();
        let mut c = spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let run = |c: &mut Box<dyn Controller>| {
            let mut a = vec![0.0; 10];
            let mut all = Vec::new();
            for k in 1..=30 {
                let readings: Vec<f64> = (0..40).map(|i| ((k * 7 + i) as f64).cos()).collect();
                c.control(k as f64 / 60.0, &readings, &mut a);
                all.extend_from_slice(&a);
            }
            all
        };
        let first = run(&mut c);
        c.reset();
        assert_eq!(run(&mut c), first);
    }
}
