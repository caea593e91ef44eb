//! Hebbian ABCD controller (thesis §5.3, thesis-code-facts.md §6): a centralized network whose
//! weights change during the episode by evolved local rules, instead of being evolved themselves.
//!
//! # Network
//!
//! Layer sizes `[n_in, hidden…, n_voxels]`, all readings in (voxel order), one actuation per voxel
//! out; by default one hidden layer as wide as the input (the thesis: ratio 1, at least 2
//! neurons). Inputs are used raw (the readings are already normalised to [0, 1]); every other layer
//! is tanh. The weights use the [`Mlp`] layout: layer → destination → `[bias, one
//! weight per source]`, so there are Σ_l n_{l+1}·(n_l + 1) of them. The bias is a synapse from a
//! constant-1 neuron with its own rule (the original overwrote the last sensor reading with 1
//! instead; we keep every reading).
//!
//! # Learning
//!
//! After every forward pass (every control step), each synapse from `pre` to `post` changes by
//! Δw = η·(A·pre·post + B·post + C·pre + D) (thesis-code-facts.md §6.1; pre = 1 for a bias), with
//! `pre`, `post` the activations of this step. Weights start at 0 (or seeded U[−1, 1], or given
//! values) and are restored at every [`Controller::reset`]. With `normalisation = "l2"` every
//! neuron's incoming vector (bias included) is then divided by its Euclidean norm (thesis
//! eq. after Fig. 5.26; skipped while the norm is 0).
//!
//! # Parameter layout (`model`)
//!
//! - `full` (thesis): one rule `[A, B, C, D]` per synapse, in weight order: 4·W parameters.
//! - `incoming`: one rule per non-input neuron, shared by its incoming synapses (layer →
//!   neuron): 4·N parameters, N = Σ_{l≥1} n_l.
//! - `dew` (direct evolution of weights, the thesis' MLP baseline): the W weights themselves, no
//!   learning.
//!
//! With `evolve_eta` every rule has a fifth value, its own η (`[A, B, C, D, η]`).
//!
//! For a biped-4x3 with the `low_biped` apparatus (8 readings): sizes [8, 8, 10], W = 8·9 + 10·9
//! = 162 weights, so `full` has 648 parameters, `incoming` 72 and `dew` 162.

use crate::mlp::{check_parameter_total, Activation};
use crate::short_form::ShortForm;
use crate::validation::{check_count, check_finite, check_units, finite, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller, Mlp};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Which parameters a rule set has (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum HebbianModel {
    /// One ABCD rule per synapse (the thesis).
    #[default]
    Full,
    /// One ABCD rule per non-input neuron, shared by its incoming synapses.
    Incoming,
    /// No rules: the parameters are the weights, fixed during the episode (the MLP baseline).
    Dew,
}

/// What happens to the weights after each update.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Normalisation {
    /// Unbounded weights (the thesis' main model).
    #[default]
    None,
    /// Each neuron's incoming weights divided by their Euclidean norm (the thesis' ablation).
    L2,
}

/// The weights at the start of every episode.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", deny_unknown_fields)]
pub enum WeightInit {
    /// All zero (the thesis).
    #[default]
    Zero,
    /// Uniform in [−1, 1] from a ChaCha8 generator with this seed.
    Uniform(u64),
    /// These values ([`crate::mlp`] layout), e.g. a snapshot taken during another episode.
    Weights(Vec<f64>),
}

/// Description of a Hebbian brain (`{"kind": "hebbian", …}`), module documentation. Every field
/// has a default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct HebbianSpec {
    /// Hidden layer sizes; absent = one layer as wide as the input (at least 2), `[]` = none.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hidden: Option<Vec<usize>>,
    /// Rule per synapse (`full`), per neuron (`incoming`) or no learning (`dew`).
    pub model: HebbianModel,
    /// Learning rate of every rule (thesis 0.01); the initial one when `evolve_eta`.
    pub eta: f64,
    /// Each rule carries its own η as a fifth parameter.
    pub evolve_eta: bool,
    /// Weight normalisation after each update.
    pub normalisation: Normalisation,
    /// Weights at the start of every episode.
    pub init: WeightInit,
    /// False freezes the weights for the whole episode (they stay at `init`).
    pub learning: bool,
    /// Learning stops at this simulated time (s); absent = never.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub freeze_at: Option<f64>,
    /// The rules (or, for `dew`, the weights), layout in the module documentation; default none
    /// (a template).
    pub parameters: Vec<f64>,
}

impl Default for HebbianSpec {
    fn default() -> Self {
        HebbianSpec {
            hidden: None,
            model: HebbianModel::Full,
            eta: 0.01,
            evolve_eta: false,
            normalisation: Normalisation::None,
            init: WeightInit::Zero,
            learning: true,
            freeze_at: None,
            parameters: Vec::new(),
        }
    }
}

impl HebbianSpec {
    /// Layer sizes for a body: `[n_inputs, hidden…, n_voxels]`.
    pub fn sizes(&self, shape: &BrainShape) -> Vec<usize> {
        let n_in: usize = shape.readings().iter().sum();
        let mut sizes = vec![n_in];
        match &self.hidden {
            Some(h) => sizes.extend_from_slice(h),
            None => sizes.push(n_in.max(2)),
        }
        sizes.push(shape.units());
        sizes
    }

    /// Values per rule: 4, or 5 with `evolve_eta`.
    fn rule_len(&self) -> usize {
        if self.evolve_eta {
            5
        } else {
            4
        }
    }

    /// Parameter count for these layer sizes (module documentation).
    fn count_for(&self, sizes: &[usize]) -> usize {
        let weights = Mlp::parameter_count(sizes);
        match self.model {
            HebbianModel::Full => weights.saturating_mul(self.rule_len()),
            HebbianModel::Incoming => sizes[1..].iter().sum::<usize>().saturating_mul(self.rule_len()),
            HebbianModel::Dew => weights,
        }
    }

    /// Errors for `dew`, whose weights never change.
    fn check_plastic(&self) -> Result<(), BrainError> {
        if self.model == HebbianModel::Dew {
            return Err(BrainError::Invalid {
                field: "model",
                msg: "a dew brain has no plastic weights to freeze (its weights are evolved and fixed)".into(),
            });
        }
        Ok(())
    }

    fn validate(&self) -> Result<(), BrainError> {
        finite("eta", self.eta)?;
        if self.evolve_eta && self.model == HebbianModel::Dew {
            return Err(BrainError::Invalid {
                field: "evolve_eta",
                msg: "a dew brain has no rules, so no η to evolve".into(),
            });
        }
        if let Some(t) = self.freeze_at {
            finite("freeze_at", t)?;
        }
        if let WeightInit::Weights(w) = &self.init {
            check_finite("init", w)?;
        }
        Ok(())
    }
}

impl BrainKind for HebbianSpec {
    fn name(&self) -> &'static str {
        "hebbian"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        check_units(shape)?;
        let sizes = self.sizes(shape);
        Mlp::check_sizes(&sizes)?;
        let count = self.count_for(&sizes);
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
        self.check_plastic()?;
        check_finite("init", weights)?;
        self.init = WeightInit::Weights(weights.to_vec());
        self.learning = false;
        Ok(())
    }

    fn stop_learning_at(&mut self, t: f64) -> Result<(), BrainError> {
        self.check_plastic()?;
        finite("freeze_at", t)?;
        self.freeze_at = Some(t);
        Ok(())
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        self.validate()?;
        let expected = self.parameter_count(shape)?;
        check_count("parameters", expected, self.parameters.len())?;
        let sizes = self.sizes(shape);
        let weights = Mlp::parameter_count(&sizes);
        let initial = match (&self.init, self.model) {
            (_, HebbianModel::Dew) => self.parameters.clone(),
            (WeightInit::Zero, _) => vec![0.0; weights],
            (WeightInit::Uniform(seed), _) => {
                let mut rng = ChaCha8Rng::seed_from_u64(*seed);
                (0..weights).map(|_| rng.random_range(-1.0..=1.0)).collect()
            }
            (WeightInit::Weights(w), _) => {
                check_count("init", weights, w.len())?;
                w.clone()
            }
        };
        let rules = match self.model {
            HebbianModel::Dew => Rules::None,
            HebbianModel::Full => Rules::PerSynapse(self.parameters.clone()),
            HebbianModel::Incoming => Rules::PerNeuron(self.parameters.clone()),
        };
        Ok(Box::new(HebbianController::new(
            sizes,
            initial,
            rules,
            Learning {
                eta: self.eta,
                evolve_eta: self.evolve_eta,
                normalisation: self.normalisation,
                enabled: self.learning && self.model != HebbianModel::Dew,
                freeze_at: self.freeze_at.unwrap_or(f64::INFINITY),
            },
        )))
    }
}

/// The rules of a controller, by model.
#[derive(Debug, Clone, PartialEq)]
pub enum Rules {
    /// No learning (`dew`).
    None,
    /// One rule per synapse, in weight order.
    PerSynapse(Vec<f64>),
    /// One rule per non-input neuron, layer → neuron.
    PerNeuron(Vec<f64>),
}

/// How a controller learns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Learning {
    /// Learning rate of every rule (unless `evolve_eta`).
    pub eta: f64,
    /// Every rule's fifth value is its η.
    pub evolve_eta: bool,
    /// Normalisation after each update.
    pub normalisation: Normalisation,
    /// Whether the weights change at all.
    pub enabled: bool,
    /// Learning stops at this time (s); infinity = never.
    pub freeze_at: f64,
}

/// The running Hebbian network: weights, the activations of every layer and the rules.
/// [`Controller::control`] allocates nothing.
#[derive(Debug, Clone)]
pub struct HebbianController {
    sizes: Vec<usize>,
    initial: Vec<f64>,
    weights: Vec<f64>,
    rules: Rules,
    learning: Learning,
    /// Activations of every layer, concatenated (layer 0 = the inputs).
    activations: Vec<f64>,
    /// Start of each layer in `activations`.
    offsets: Vec<usize>,
}

impl HebbianController {
    /// A network with these layer sizes, initial weights ([`crate::mlp`] layout) and rules.
    pub fn new(sizes: Vec<usize>, initial: Vec<f64>, rules: Rules, learning: Learning) -> Self {
        let mut offsets = Vec::with_capacity(sizes.len());
        let mut total = 0;
        for &n in &sizes {
            offsets.push(total);
            total += n;
        }
        HebbianController {
            weights: initial.clone(),
            initial,
            sizes,
            rules,
            learning,
            activations: vec![0.0; total],
            offsets,
        }
    }

    /// The current weights ([`crate::mlp`] layout).
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    fn forward(&mut self, readings: &[f64]) {
        self.activations[..self.sizes[0]].copy_from_slice(readings);
        let mut w = 0;
        for l in 0..self.sizes.len() - 1 {
            let (n_src, n_dst) = (self.sizes[l], self.sizes[l + 1]);
            let (src_at, dst_at) = (self.offsets[l], self.offsets[l + 1]);
            for o in 0..n_dst {
                let row = &self.weights[w..w + n_src + 1];
                let src = &self.activations[src_at..src_at + n_src];
                let sum = row[0] + row[1..].iter().zip(src).map(|(w, a)| w * a).sum::<f64>();
                self.activations[dst_at + o] = Activation::Tanh.apply(sum);
                w += n_src + 1;
            }
        }
    }

    /// One Hebbian update of every synapse from this step's activations, then the normalisation.
    fn learn(&mut self) {
        let Self {
            sizes,
            weights,
            rules,
            learning,
            activations,
            offsets,
            ..
        } = self;
        let (rules, per_synapse) = match rules {
            Rules::None => return,
            Rules::PerSynapse(r) => (&r[..], true),
            Rules::PerNeuron(r) => (&r[..], false),
        };
        let len = if learning.evolve_eta { 5 } else { 4 };
        let mut w = 0;
        let mut neuron = 0;
        for l in 0..sizes.len() - 1 {
            let (n_src, n_dst) = (sizes[l], sizes[l + 1]);
            let src = &activations[offsets[l]..offsets[l] + n_src];
            for o in 0..n_dst {
                let post = activations[offsets[l + 1] + o];
                let row = &mut weights[w..w + n_src + 1];
                for (i, weight) in row.iter_mut().enumerate() {
                    let pre = if i == 0 { 1.0 } else { src[i - 1] };
                    let at = if per_synapse { (w + i) * len } else { neuron * len };
                    let rule = &rules[at..at + len];
                    let eta = if len == 5 { rule[4] } else { learning.eta };
                    *weight += eta * (rule[0] * pre * post + rule[1] * post + rule[2] * pre + rule[3]);
                }
                if learning.normalisation == Normalisation::L2 {
                    normalise(row);
                }
                w += n_src + 1;
                neuron += 1;
            }
        }
    }
}

/// Divides `v` by its Euclidean norm, unless the norm is 0 or not finite.
fn normalise(v: &mut [f64]) {
    let norm = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    if norm > 0.0 && norm.is_finite() {
        for x in v {
            *x /= norm;
        }
    }
}

impl Controller for HebbianController {
    fn reset(&mut self) {
        self.weights.copy_from_slice(&self.initial);
        self.activations.fill(0.0);
    }

    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]) {
        debug_assert_eq!(readings.len(), self.sizes[0]);
        self.forward(readings);
        let out = *self.offsets.last().expect("at least two layers");
        for (a, y) in actuations.iter_mut().zip(&self.activations[out..]) {
            *a = y.clamp(-1.0, 1.0);
        }
        if self.learning.enabled && t < self.learning.freeze_at {
            self.learn();
        }
    }

    /// The weights, unless they cannot change (`dew`).
    fn publish(&self, probe: &mut dyn vsrlab_body::Probe) {
        if self.rules != Rules::None {
            probe.step(&crate::controller::PLASTIC_WEIGHTS, &self.weights);
        }
    }
}

/// `hebbian` (per-synapse rules), `hebbian:incoming`, `hebbian:dew`, or `hebbian:l2` (per-synapse
/// rules, normalised weights).
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "hebbian",
    usage: "hebbian[:full|incoming|dew|l2]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let mut spec = HebbianSpec::default();
    match argument.map(str::trim) {
        None | Some("full") => {}
        Some("incoming") => spec.model = HebbianModel::Incoming,
        Some("dew") => spec.model = HebbianModel::Dew,
        Some("l2") => spec.normalisation = Normalisation::L2,
        Some(_) => return None,
    }
    Some(BrainSpec::Hebbian(spec))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped};
    use vsrlab_body::Morphology;

    /// A 1 → 1 network (one synapse and one bias) with the rule [A, B, C, D] on both.
    fn two_neurons(rule: [f64; 4], initial: [f64; 2]) -> HebbianController {
        let mut rules = rule.to_vec();
        rules.extend_from_slice(&rule);
        HebbianController::new(
            vec![1, 1],
            initial.to_vec(),
            Rules::PerSynapse(rules),
            Learning {
                eta: 0.1,
                evolve_eta: false,
                normalisation: Normalisation::None,
                enabled: true,
                freeze_at: f64::INFINITY,
            },
        )
    }

    /// Weights after one step with input `x`, checked against the hand-computed rule.
    fn one_step(rule: [f64; 4], initial: [f64; 2], x: f64) -> ([f64; 2], f64) {
        let mut c = two_neurons(rule, initial);
        let mut a = [0.0];
        c.control(0.0, &[x], &mut a);
        ([c.weights()[0], c.weights()[1]], a[0])
    }

    #[test]
    fn each_coefficient_alone_follows_the_abcd_rule() {
        let (b0, w0, x): (f64, f64, f64) = (0.2, 0.5, 0.8);
        let post = (b0 + w0 * x).tanh();
        let eta = 0.1;
        // A: Δw = η·A·pre·post (pre = 1 for the bias)
        let (w, a) = one_step([2.0, 0.0, 0.0, 0.0], [b0, w0], x);
        assert_eq!(a, post);
        assert!((w[0] - (b0 + eta * 2.0 * post)).abs() < 1e-15);
        assert!((w[1] - (w0 + eta * 2.0 * x * post)).abs() < 1e-15);
        // B: Δw = η·B·post
        let (w, _) = one_step([0.0, -3.0, 0.0, 0.0], [b0, w0], x);
        assert!((w[0] - (b0 - eta * 3.0 * post)).abs() < 1e-15);
        assert!((w[1] - (w0 - eta * 3.0 * post)).abs() < 1e-15);
        // C: Δw = η·C·pre
        let (w, _) = one_step([0.0, 0.0, 1.5, 0.0], [b0, w0], x);
        assert!((w[0] - (b0 + eta * 1.5)).abs() < 1e-15);
        assert!((w[1] - (w0 + eta * 1.5 * x)).abs() < 1e-15);
        // D: Δw = η·D
        let (w, _) = one_step([0.0, 0.0, 0.0, 0.7], [b0, w0], x);
        assert!((w[0] - (b0 + eta * 0.7)).abs() < 1e-15);
        assert!((w[1] - (w0 + eta * 0.7)).abs() < 1e-15);
    }

    #[test]
    fn the_update_uses_this_steps_activations_and_the_next_step_sees_it() {
        // zero start: the first output is tanh(0) = 0; D moves both weights, the second output
        // then reads them
        let mut c = two_neurons([0.0, 0.0, 0.0, 1.0], [0.0, 0.0]);
        let mut a = [9.0];
        c.control(0.0, &[0.5], &mut a);
        assert_eq!(a, [0.0]);
        c.control(1.0 / 60.0, &[0.5], &mut a);
        assert!((a[0] - (0.1 + 0.1 * 0.5f64).tanh()).abs() < 1e-15);
    }

    #[test]
    fn reset_restores_the_initial_weights() {
        let mut c = two_neurons([1.0, 1.0, 1.0, 1.0], [0.3, -0.2]);
        let mut a = [0.0];
        for k in 0..10 {
            c.control(k as f64 / 60.0, &[0.4], &mut a);
        }
        assert_ne!(c.weights(), &[0.3, -0.2]);
        c.reset();
        assert_eq!(c.weights(), &[0.3, -0.2]);
        let mut again = two_neurons([1.0, 1.0, 1.0, 1.0], [0.3, -0.2]);
        let mut b = [0.0];
        c.control(0.0, &[0.4], &mut a);
        again.control(0.0, &[0.4], &mut b);
        assert_eq!(a, b);
        assert_eq!(c.weights(), again.weights());
    }

    #[test]
    fn freezing_stops_the_weights_at_the_given_time() {
        let mut c = two_neurons([0.0, 0.0, 0.0, 1.0], [0.0, 0.0]);
        c.learning.freeze_at = 0.05;
        let mut a = [0.0];
        for k in 0..6 {
            c.control(k as f64 / 60.0, &[0.5], &mut a);
        }
        // steps at t = 0, 1/60, 2/60 learn (t < 0.05); 3/60 onwards do not
        assert!((c.weights()[0] - 0.3).abs() < 1e-12, "{:?}", c.weights());
    }

    #[test]
    fn l2_normalisation_gives_unit_incoming_vectors() {
        let mut c = two_neurons([0.0, 0.0, 0.0, 1.0], [3.0, 4.0]);
        c.learning.normalisation = Normalisation::L2;
        let mut a = [0.0];
        c.control(0.0, &[0.5], &mut a);
        let (b, w): (f64, f64) = (3.1, 4.1);
        let n = (b * b + w * w).sqrt();
        assert!((c.weights()[0] - b / n).abs() < 1e-12);
        assert!((c.weights()[1] - w / n).abs() < 1e-12);
    }

    #[test]
    fn parameter_counts_of_every_model() {
        // biped-4x3, 8 readings on the top two rows (low_biped): sizes [8, 8, 10], W = 162
        let m = Morphology::named("biped-4x3").unwrap();
        let rpv = [0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1];
        let rpv = &rpv[2..];
        let count = |s: &str| {
            BrainSpec::parse(s)
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, rpv))
                .unwrap()
        };
        assert_eq!(count("hebbian"), 4 * 162);
        assert_eq!(count("hebbian:l2"), 4 * 162);
        assert_eq!(count("hebbian:incoming"), 4 * (8 + 10));
        assert_eq!(count("hebbian:dew"), 162);
        let eta = HebbianSpec {
            evolve_eta: true,
            ..HebbianSpec::default()
        };
        assert_eq!(eta.parameter_count(&BrainShape::grid(&m, rpv)).unwrap(), 5 * 162);
        // 4 readings per voxel: 40 inputs, hidden 40, 10 outputs: 40·41 + 10·41 = 2050
        let (m, rpv) = biped();
        assert_eq!(
            BrainSpec::parse("hebbian")
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv))
                .unwrap(),
            4 * 2050
        );
    }

    #[test]
    fn dew_is_a_fixed_tanh_network() {
        let m = Morphology::named("worm-2x1").unwrap();
        let spec = BrainSpec::parse("hebbian:dew").unwrap();
        let rpv = [1, 1];
        let n = spec.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap();
        let spec = spec.with_random_parameters(3, &BrainShape::grid(&m, &rpv)).unwrap();
        let mut c = spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mlp = Mlp::new(vec![2, 2, 2], Activation::Tanh, false, spec.parameters().to_vec()).unwrap();
        assert_eq!(n, Mlp::parameter_count(&[2, 2, 2]));
        let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
        let mut scratch = vec![0.0; mlp.scratch_len()];
        for k in 0..5 {
            c.control(k as f64, &[0.3, 0.9], &mut a);
            mlp.apply(&[0.3, 0.9], &mut b, &mut scratch);
            assert_eq!(a, b);
        }
        assert_eq!(crate::plastic_weights(&c), None, "fixed weights are not plastic");
        let mut dew = spec.clone();
        assert!(dew.as_kind_mut().freeze_with(&[0.0; 12]).is_err());
    }

    #[test]
    fn bad_fields_are_named() {
        let (m, rpv) = biped();
        let spec = |f: fn(&mut HebbianSpec)| {
            let mut s = HebbianSpec::default();
            f(&mut s);
            let n = s.parameter_count(&BrainShape::grid(&m, &rpv)).unwrap_or(0);
            s.parameters = vec![0.0; n];
            s.build(&BrainShape::grid(&m, &rpv)).err().expect("invalid")
        };
        assert_invalid(&spec(|s| s.eta = f64::NAN), "eta");
        assert_invalid(
            &spec(|s| {
                s.model = HebbianModel::Dew;
                s.evolve_eta = true
            }),
            "evolve_eta",
        );
        assert_invalid(&spec(|s| s.init = WeightInit::Weights(vec![0.0; 3])), "init");
        assert_invalid(&spec(|s| s.freeze_at = Some(f64::INFINITY)), "freeze_at");
        let empty = HebbianSpec::default().build(&BrainShape::grid(&m, &rpv)).err().unwrap();
        assert_invalid(&empty, "parameters");
        let err = serde_json::from_str::<BrainSpec>(r#"{"kind": "hebbian", "model": "fast"}"#).unwrap_err();
        assert!(err.to_string().contains("model"), "{err}");
    }

    #[test]
    fn freezing_with_a_snapshot_replays_those_weights() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("hebbian")
            .unwrap()
            .with_random_parameters(1, &BrainShape::grid(&m, &rpv))
            .unwrap();
        let readings: Vec<f64> = (0..40).map(|i| (i as f64 * 0.37).sin().abs()).collect();
        let mut live = spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mut a = vec![0.0; 10];
        for k in 0..30 {
            live.control(k as f64 / 60.0, &readings, &mut a);
        }
        let snapshot = crate::plastic_weights(&live).unwrap().to_vec();
        let mut frozen_spec = spec.clone();
        frozen_spec.as_kind_mut().freeze_with(&snapshot).unwrap();
        let mut frozen = frozen_spec.build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mut b = vec![0.0; 10];
        for k in 0..5 {
            frozen.control(k as f64 / 60.0, &readings, &mut b);
        }
        assert_eq!(crate::plastic_weights(&frozen).unwrap(), &snapshot[..]);
        let mut wrapped = BrainSpec::parse("step:0.5:phase").unwrap();
        assert!(wrapped.as_kind_mut().freeze_with(&snapshot).is_err());
        // wrappers pass the weights and the freezing through
        let mut stepped = BrainSpec::parse("step:0.33:hebbian")
            .unwrap()
            .with_random_parameters(1, &BrainShape::grid(&m, &rpv))
            .unwrap();
        let c = stepped.build(&BrainShape::grid(&m, &rpv)).unwrap();
        assert_eq!(crate::plastic_weights(&c).map(|w| w.len()), Some(snapshot.len()));
        stepped.as_kind_mut().freeze_with(&snapshot).unwrap();
        let c = stepped.build(&BrainShape::grid(&m, &rpv)).unwrap();
        assert_eq!(crate::plastic_weights(&c).unwrap(), &snapshot[..]);
    }
}
