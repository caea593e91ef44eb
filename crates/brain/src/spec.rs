//! [`BrainSpec`]: the serialisable description of a brain, its parameters and its builder.

use crate::controllers::centralized_mlp::{default_hidden, CentralizedMlpController};
use crate::controllers::distributed_mlp::{self, DistributedConfig, DistributedMlpController, Layout};
use crate::controllers::phase_grid::{self, PhaseGridController, PhaseLayout};
use crate::controllers::smoothed::SmoothedController;
use crate::controllers::step::StepController;
use crate::mlp::{check_finite, Activation, Mlp};
use crate::{BrainError, ConstantController, Controller, PhaseController, RandomController};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vsrlab_body::Morphology;

/// Description of a brain, as written in configs and robot files (JSON or TOML, tagged by `kind`).
///
/// Parameterised kinds (`mlp`, `distributed-mlp`, `phase-grid`) carry their parameter vector
/// (`weights` or `parameters`); it may be left empty in a *template* (an experiment's brain whose
/// parameters come from the genotype, see [`BrainSpec::with_parameters`]), but building a brain
/// needs the exact count for the body and sensors ([`BrainSpec::parameter_count`]).
///
/// JSON forms (fields with defaults may be omitted):
/// ```json
/// {"kind": "phase", "frequency": 1.0, "amplitude": 1.0, "phase_x": 1.0, "phase_y": 0.0}
/// {"kind": "constant", "value": 0.0}
/// {"kind": "random", "period": 0.0, "seed": 0}
/// {"kind": "phase-grid", "frequency": 1.0, "amplitude": 1.0, "evolve_frequency": false,
///  "layout": "grid", "parameters": [...]}
/// {"kind": "mlp", "hidden": [26], "activation": "tanh", "input_activation": true, "weights": [...]}
/// {"kind": "distributed-mlp", "signals": 1, "hidden": [], "activation": "tanh",
///  "input_activation": true, "layout": "homogeneous", "weights": [...]}
/// {"kind": "step", "period": 0.33, "inner": {"kind": "distributed-mlp", ...}}
/// {"kind": "smoothed", "speed": 5.0, "inner": {"kind": "mlp", ...}}
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum BrainSpec {
    /// Open-loop a = A·sin(2πft + φ(x, y)) with φ = phase_x·π·x/W + phase_y·π·y/H.
    Phase {
        /// Frequency f (Hz).
        #[serde(default = "one")]
        frequency: f64,
        /// Amplitude A.
        #[serde(default = "one")]
        amplitude: f64,
        /// Phase shift across the width, in units of π.
        #[serde(default = "one")]
        phase_x: f64,
        /// Phase shift across the height, in units of π.
        #[serde(default)]
        phase_y: f64,
    },
    /// The same constant actuation on every voxel (calibration, passive bodies).
    Constant {
        /// Actuation in [-1, 1] (positive contracts).
        value: f64,
    },
    /// Independent uniform random actuations in [-1, 1], redrawn every `period` seconds
    /// (a baseline, and a stress test for the physics).
    Random {
        /// Seconds between redraws (0 = every step).
        #[serde(default)]
        period: f64,
        /// Seed of the generator.
        #[serde(default)]
        seed: u64,
    },
    /// Open-loop a_v = clamp(A·sin(2π·f_v·t + φ_v), −1, 1) with evolvable per-voxel phases and
    /// optionally frequencies ([`crate::controllers::phase_grid`]: φ_v = π·p_φ, f_v = f₀ + p_f).
    PhaseGrid {
        /// Base frequency f₀ (Hz).
        #[serde(default = "one")]
        frequency: f64,
        /// Amplitude A.
        #[serde(default = "one")]
        amplitude: f64,
        /// Whether each voxel also has a frequency parameter.
        #[serde(default)]
        evolve_frequency: bool,
        /// One block per grid cell (`grid`, default) or per voxel (`voxels`).
        #[serde(default)]
        layout: PhaseLayout,
        /// The parameters: units × (1 + evolve_frequency) values.
        #[serde(default)]
        parameters: Vec<f64>,
    },
    /// Centralized MLP: all readings in, one actuation per voxel out
    /// ([`crate::controllers::centralized_mlp`]).
    Mlp {
        /// Hidden layer sizes; absent = one layer of max(2, round(0.65·n_inputs)) neurons
        /// (2D-VSR-Sim's default), `[]` = no hidden layer.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        hidden: Option<Vec<usize>>,
        /// Activation of every layer (default tanh).
        #[serde(default)]
        activation: Activation,
        /// Apply the activation to the raw inputs first (2D-VSR-Sim ≥ v1.9.1; default true).
        #[serde(default = "yes")]
        input_activation: bool,
        /// The weights ([`crate::mlp`] layout), sizes `[n_inputs, hidden…, n_voxels]`.
        #[serde(default)]
        weights: Vec<f64>,
    },
    /// One MLP per voxel with neighbour signals ([`crate::controllers::distributed_mlp`]).
    DistributedMlp {
        /// Signals per direction s (default 1).
        #[serde(default = "one_signal")]
        signals: usize,
        /// Hidden layer sizes of each voxel's network (default none).
        #[serde(default)]
        hidden: Vec<usize>,
        /// Activation of every layer (default tanh).
        #[serde(default)]
        activation: Activation,
        /// Apply the activation to the raw inputs first (2D-VSR-Sim ≥ v1.9.1; default true).
        #[serde(default = "yes")]
        input_activation: bool,
        /// `homogeneous` (one shared weight vector, default) or `heterogeneous` (one per grid cell).
        #[serde(default)]
        layout: Layout,
        /// The weights: n_w (homogeneous) or W·H·n_w (heterogeneous).
        #[serde(default)]
        weights: Vec<f64>,
    },
    /// Holds the inner brain's output for `period` seconds ([`crate::controllers::step`]).
    Step {
        /// Seconds between refreshes of the applied actuations (0 = every step).
        period: f64,
        /// The wrapped brain.
        inner: Box<BrainSpec>,
    },
    /// Rate-limits the inner brain's output ([`crate::controllers::smoothed`]).
    Smoothed {
        /// Largest change of an actuation per second.
        speed: f64,
        /// The wrapped brain.
        inner: Box<BrainSpec>,
    },
}

fn one() -> f64 {
    1.0
}

fn one_signal() -> usize {
    1
}

fn yes() -> bool {
    true
}

impl Default for BrainSpec {
    fn default() -> Self {
        BrainSpec::Phase {
            frequency: 1.0,
            amplitude: 1.0,
            phase_x: 1.0,
            phase_y: 0.0,
        }
    }
}

fn finite(field: &'static str, v: f64) -> Result<(), BrainError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("must be a finite number, got {v}"),
        })
    }
}

fn non_negative(field: &'static str, v: f64, unit: &str) -> Result<(), BrainError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("must be ≥ 0{unit}, got {v}"),
        })
    }
}

fn check_count(field: &'static str, expected: usize, got: usize) -> Result<(), BrainError> {
    if expected == got {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field,
            msg: format!("expected {expected} for this body and sensors, got {got}"),
        })
    }
}

fn check_voxels(morphology: &Morphology, readings_per_voxel: &[usize]) -> Result<(), BrainError> {
    if readings_per_voxel.len() == morphology.voxel_count() {
        Ok(())
    } else {
        Err(BrainError::Invalid {
            field: "readings_per_voxel",
            msg: format!(
                "{} entries for a body of {} voxels",
                readings_per_voxel.len(),
                morphology.voxel_count()
            ),
        })
    }
}

/// Layer sizes of a centralized MLP for a body.
fn centralized_sizes(hidden: &Option<Vec<usize>>, morphology: &Morphology, readings_per_voxel: &[usize]) -> Vec<usize> {
    let n_in: usize = readings_per_voxel.iter().sum();
    let mut sizes = vec![n_in];
    match hidden {
        Some(h) => sizes.extend_from_slice(h),
        None => sizes.extend(default_hidden(n_in)),
    }
    sizes.push(morphology.voxel_count());
    sizes
}

impl BrainSpec {
    /// The `kind` tag, as in configs.
    pub fn kind(&self) -> &'static str {
        match self {
            BrainSpec::Phase { .. } => "phase",
            BrainSpec::Constant { .. } => "constant",
            BrainSpec::Random { .. } => "random",
            BrainSpec::PhaseGrid { .. } => "phase-grid",
            BrainSpec::Mlp { .. } => "mlp",
            BrainSpec::DistributedMlp { .. } => "distributed-mlp",
            BrainSpec::Step { .. } => "step",
            BrainSpec::Smoothed { .. } => "smoothed",
        }
    }

    /// Parses a short name from the command line:
    /// - `phase`, `constant:<value>`, `random[:<period s>]`;
    /// - `phase-grid` (per-cell phases) or `phase-grid:freq` (per-cell phases and frequencies);
    /// - `mlp` (default hidden layer), `mlp:<sizes>` (e.g. `mlp:26` or `mlp:16,8`), `mlp:none`
    ///   (no hidden layer);
    /// - `distributed-mlp[:<signals>]` (homogeneous), `distributed-mlp-hetero[:<signals>]`
    ///   (heterogeneous), both without hidden layer, default 1 signal;
    /// - `step:<period s>:<brain>`, `smoothed:<speed>:<brain>` wrapping any of these.
    ///
    /// Parameterised brains come with no parameters: fill them with [`BrainSpec::with_parameters`]
    /// or [`BrainSpec::with_random_parameters`] before building.
    pub fn parse(s: &str) -> Result<BrainSpec, BrainError> {
        let unknown = || BrainError::Unknown(s.to_string());
        let (name, arg) = s.split_once(':').map_or((s, None), |(a, b)| (a, Some(b)));
        let number = |a: &str| a.trim().parse::<f64>().map_err(|_| unknown());
        let count = |a: &str| a.trim().parse::<usize>().map_err(|_| unknown());
        let wrapped = |a: &str| -> Result<(f64, Box<BrainSpec>), BrainError> {
            let (value, inner) = a.split_once(':').ok_or_else(unknown)?;
            let inner = BrainSpec::parse(inner).map_err(|e| match e {
                BrainError::Unknown(_) => unknown(),
                other => other,
            })?;
            Ok((number(value)?, Box::new(inner)))
        };
        let distributed = |arg: Option<&str>, layout: Layout| -> Result<BrainSpec, BrainError> {
            Ok(BrainSpec::DistributedMlp {
                signals: arg.map(count).transpose()?.unwrap_or(1),
                hidden: Vec::new(),
                activation: Activation::Tanh,
                input_activation: true,
                layout,
                weights: Vec::new(),
            })
        };
        match (name, arg) {
            ("phase", None) => Ok(BrainSpec::default()),
            ("constant", Some(v)) => Ok(BrainSpec::Constant { value: number(v)? }),
            ("random", None) => Ok(BrainSpec::Random { period: 0.0, seed: 0 }),
            ("random", Some(p)) => Ok(BrainSpec::Random {
                period: number(p)?,
                seed: 0,
            }),
            ("phase-grid", None | Some("freq")) => Ok(BrainSpec::PhaseGrid {
                frequency: 1.0,
                amplitude: 1.0,
                evolve_frequency: arg.is_some(),
                layout: PhaseLayout::Grid,
                parameters: Vec::new(),
            }),
            ("mlp", _) => {
                let hidden = match arg.map(str::trim) {
                    None => None,
                    Some("none") => Some(Vec::new()),
                    Some(list) => Some(list.split(',').map(count).collect::<Result<Vec<_>, _>>()?),
                };
                Ok(BrainSpec::Mlp {
                    hidden,
                    activation: Activation::Tanh,
                    input_activation: true,
                    weights: Vec::new(),
                })
            }
            ("distributed-mlp", _) => distributed(arg, Layout::Homogeneous),
            ("distributed-mlp-hetero", _) => distributed(arg, Layout::Heterogeneous),
            ("step", Some(a)) => {
                let (period, inner) = wrapped(a)?;
                Ok(BrainSpec::Step { period, inner })
            }
            ("smoothed", Some(a)) => {
                let (speed, inner) = wrapped(a)?;
                Ok(BrainSpec::Smoothed { speed, inner })
            }
            _ => Err(unknown()),
        }
    }

    /// Number of parameters this brain needs for a body whose voxels (voxel order) have these
    /// readings counts: 0 for parameterless brains (`phase`, `constant`, `random`); wrappers
    /// delegate to their inner brain. Errors when the shape does not fit the body (for example
    /// unequal readings counts for a distributed MLP).
    pub fn parameter_count(&self, morphology: &Morphology, readings_per_voxel: &[usize]) -> Result<usize, BrainError> {
        match self {
            BrainSpec::Phase { .. } | BrainSpec::Constant { .. } | BrainSpec::Random { .. } => Ok(0),
            BrainSpec::PhaseGrid {
                evolve_frequency,
                layout,
                ..
            } => Ok(phase_grid::parameter_count(morphology, *layout, *evolve_frequency)),
            BrainSpec::Mlp { hidden, .. } => {
                check_voxels(morphology, readings_per_voxel)?;
                let sizes = centralized_sizes(hidden, morphology, readings_per_voxel);
                Mlp::check_sizes(&sizes)?;
                Ok(Mlp::parameter_count(&sizes))
            }
            BrainSpec::DistributedMlp {
                signals,
                hidden,
                layout,
                ..
            } => {
                check_voxels(morphology, readings_per_voxel)?;
                let readings = distributed_mlp::common_readings(morphology, readings_per_voxel)?;
                Mlp::check_sizes(&distributed_mlp::network_sizes(readings, *signals, hidden))?;
                Ok(distributed_mlp::parameter_count(
                    morphology, readings, *signals, hidden, *layout,
                ))
            }
            BrainSpec::Step { inner, .. } | BrainSpec::Smoothed { inner, .. } => {
                inner.parameter_count(morphology, readings_per_voxel)
            }
        }
    }

    /// The parameter vector (empty for parameterless brains and unfilled templates); wrappers give
    /// their inner brain's.
    pub fn parameters(&self) -> &[f64] {
        match self {
            BrainSpec::Phase { .. } | BrainSpec::Constant { .. } | BrainSpec::Random { .. } => &[],
            BrainSpec::PhaseGrid { parameters, .. } => parameters,
            BrainSpec::Mlp { weights, .. } | BrainSpec::DistributedMlp { weights, .. } => weights,
            BrainSpec::Step { inner, .. } | BrainSpec::Smoothed { inner, .. } => inner.parameters(),
        }
    }

    /// The same brain with this parameter vector (weights of an MLP, parameters of a phase grid;
    /// wrappers pass it to their inner brain).
    ///
    /// Errors when a parameterless brain gets a non-empty vector (field `parameters`, naming both
    /// counts) or a value is not finite. The count for a body is checked by [`BrainSpec::build`],
    /// or here already with [`BrainSpec::with_parameters_for`].
    pub fn with_parameters(&self, params: &[f64]) -> Result<BrainSpec, BrainError> {
        let mut spec = self.clone();
        spec.set_parameters(params)?;
        Ok(spec)
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        let kind = self.kind();
        match self {
            BrainSpec::Phase { .. } | BrainSpec::Constant { .. } | BrainSpec::Random { .. } => {
                if !params.is_empty() {
                    return Err(BrainError::Invalid {
                        field: "parameters",
                        msg: format!("expected 0 for a {kind} brain (it has none), got {}", params.len()),
                    });
                }
            }
            BrainSpec::PhaseGrid { parameters, .. } => {
                check_finite("parameters", params)?;
                *parameters = params.to_vec();
            }
            BrainSpec::Mlp { weights, .. } | BrainSpec::DistributedMlp { weights, .. } => {
                check_finite("weights", params)?;
                *weights = params.to_vec();
            }
            BrainSpec::Step { inner, .. } | BrainSpec::Smoothed { inner, .. } => inner.set_parameters(params)?,
        }
        Ok(())
    }

    /// [`BrainSpec::with_parameters`], first checking the count against
    /// [`BrainSpec::parameter_count`] for this body: a mismatch is an error on field `parameters`,
    /// "expected N for this body and sensors, got M".
    pub fn with_parameters_for(
        &self,
        params: &[f64],
        morphology: &Morphology,
        readings_per_voxel: &[usize],
    ) -> Result<BrainSpec, BrainError> {
        let expected = self.parameter_count(morphology, readings_per_voxel)?;
        check_count("parameters", expected, params.len())?;
        self.with_parameters(params)
    }

    /// The same brain with [`BrainSpec::parameter_count`] parameters drawn uniformly in [−1, 1]
    /// from a ChaCha8 generator seeded with `seed` (reproducible: a random brain for the command
    /// line or a benchmark). Parameterless brains come back unchanged.
    pub fn with_random_parameters(
        &self,
        seed: u64,
        morphology: &Morphology,
        readings_per_voxel: &[usize],
    ) -> Result<BrainSpec, BrainError> {
        let n = self.parameter_count(morphology, readings_per_voxel)?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let params: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..=1.0)).collect();
        self.with_parameters(&params)
    }

    /// Builds the controller for a body whose voxels (voxel order) have these readings counts.
    ///
    /// Validates every field; a parameter vector of the wrong length is an error on `weights`
    /// (MLPs) or `parameters` (phase grid): "expected N for this body and sensors, got M" (an
    /// unfilled template has M = 0).
    pub fn build(
        &self,
        morphology: &Morphology,
        readings_per_voxel: &[usize],
    ) -> Result<Box<dyn Controller>, BrainError> {
        match self {
            &BrainSpec::Phase {
                frequency,
                amplitude,
                phase_x,
                phase_y,
            } => {
                for (field, v) in [
                    ("frequency", frequency),
                    ("amplitude", amplitude),
                    ("phase_x", phase_x),
                    ("phase_y", phase_y),
                ] {
                    finite(field, v)?;
                }
                Ok(Box::new(PhaseController::for_morphology(
                    morphology, frequency, amplitude, phase_x, phase_y,
                )))
            }
            &BrainSpec::Constant { value } => {
                finite("value", value)?;
                Ok(Box::new(ConstantController { value }))
            }
            &BrainSpec::Random { period, seed } => {
                non_negative("period", period, " seconds")?;
                Ok(Box::new(RandomController::new(period, seed)))
            }
            BrainSpec::PhaseGrid {
                frequency,
                amplitude,
                evolve_frequency,
                layout,
                parameters,
            } => {
                finite("frequency", *frequency)?;
                finite("amplitude", *amplitude)?;
                let expected = phase_grid::parameter_count(morphology, *layout, *evolve_frequency);
                check_count("parameters", expected, parameters.len())?;
                check_finite("parameters", parameters)?;
                Ok(Box::new(PhaseGridController::new(
                    morphology,
                    *amplitude,
                    *frequency,
                    *layout,
                    *evolve_frequency,
                    parameters,
                )))
            }
            BrainSpec::Mlp {
                hidden,
                activation,
                input_activation,
                weights,
            } => {
                let expected = self.parameter_count(morphology, readings_per_voxel)?;
                check_count("weights", expected, weights.len())?;
                let sizes = centralized_sizes(hidden, morphology, readings_per_voxel);
                let mlp = Mlp::new(sizes, *activation, *input_activation, weights.clone())?;
                Ok(Box::new(CentralizedMlpController::new(mlp)))
            }
            BrainSpec::DistributedMlp {
                signals,
                hidden,
                activation,
                input_activation,
                layout,
                weights,
            } => {
                let config = DistributedConfig {
                    signals: *signals,
                    hidden: hidden.clone(),
                    activation: *activation,
                    input_activation: *input_activation,
                    layout: *layout,
                };
                Ok(Box::new(DistributedMlpController::new(
                    morphology,
                    readings_per_voxel,
                    &config,
                    weights,
                )?))
            }
            BrainSpec::Step { period, inner } => {
                non_negative("period", *period, " seconds")?;
                let inner = inner.build(morphology, readings_per_voxel)?;
                Ok(Box::new(StepController::new(inner, *period, morphology.voxel_count())))
            }
            BrainSpec::Smoothed { speed, inner } => {
                non_negative("speed", *speed, " per second")?;
                let inner = inner.build(morphology, readings_per_voxel)?;
                Ok(Box::new(SmoothedController::new(
                    inner,
                    *speed,
                    morphology.voxel_count(),
                )))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn biped() -> (Morphology, Vec<usize>) {
        (Morphology::named("biped-4x3").unwrap(), vec![4; 10])
    }

    fn homogeneous() -> BrainSpec {
        BrainSpec::parse("distributed-mlp").unwrap()
    }

    /// One spec of every kind, parameters filled for the biped with 4 readings per voxel.
    fn every_kind() -> Vec<BrainSpec> {
        let (m, rpv) = biped();
        let templates = [
            "phase",
            "constant:0.25",
            "random:0.2",
            "phase-grid",
            "phase-grid:freq",
            "mlp",
            "mlp:5,3",
            "mlp:none",
            "distributed-mlp",
            "distributed-mlp-hetero:2",
            "step:0.33:distributed-mlp",
            "smoothed:4:mlp",
            "step:0.5:smoothed:2:phase-grid",
        ];
        let mut specs: Vec<BrainSpec> = templates
            .iter()
            .enumerate()
            .map(|(k, s)| {
                BrainSpec::parse(s)
                    .unwrap()
                    .with_random_parameters(k as u64, &m, &rpv)
                    .unwrap()
            })
            .collect();
        specs.push(
            BrainSpec::DistributedMlp {
                signals: 2,
                hidden: vec![6, 4],
                activation: Activation::Sin,
                input_activation: false,
                layout: Layout::Heterogeneous,
                weights: Vec::new(),
            }
            .with_random_parameters(99, &m, &rpv)
            .unwrap(),
        );
        specs.push(
            BrainSpec::PhaseGrid {
                frequency: 0.5,
                amplitude: 0.8,
                evolve_frequency: true,
                layout: PhaseLayout::Voxels,
                parameters: Vec::new(),
            }
            .with_random_parameters(100, &m, &rpv)
            .unwrap(),
        );
        specs.push(
            BrainSpec::Mlp {
                hidden: Some(vec![7]),
                activation: Activation::Relu,
                input_activation: false,
                weights: Vec::new(),
            }
            .with_random_parameters(101, &m, &rpv)
            .unwrap(),
        );
        specs
    }

    #[test]
    fn parameter_counts_match_the_check_values() {
        let (m, rpv) = biped();
        assert_eq!(BrainSpec::parse("mlp").unwrap().parameter_count(&m, &rpv), Ok(1336));
        let m10 = Morphology::named("box-10x10").unwrap();
        let m5 = Morphology::named("box-5x5").unwrap();
        let hetero = BrainSpec::parse("distributed-mlp-hetero").unwrap();
        assert_eq!(homogeneous().parameter_count(&m10, &[4; 100]), Ok(45));
        assert_eq!(hetero.parameter_count(&m10, &[4; 100]), Ok(4500));
        assert_eq!(hetero.parameter_count(&m5, &[4; 25]), Ok(1125));
        let single = Morphology::from_fn(5, 5, |x, y| (x, y) == (2, 2)).unwrap();
        assert_eq!(hetero.parameter_count(&single, &[4]), Ok(1125));
        for s in ["phase", "constant:0", "random", "step:1:phase"] {
            assert_eq!(BrainSpec::parse(s).unwrap().parameter_count(&m, &rpv), Ok(0), "{s}");
        }
        assert_eq!(
            BrainSpec::parse("step:0.33:mlp").unwrap().parameter_count(&m, &rpv),
            Ok(1336)
        );
        assert_eq!(
            BrainSpec::parse("smoothed:2:distributed-mlp-hetero")
                .unwrap()
                .parameter_count(&m, &rpv),
            Ok(12 * 45)
        );
        assert_eq!(
            BrainSpec::parse("mlp:none").unwrap().parameter_count(&m, &rpv),
            Ok(10 * 41)
        );
        assert_eq!(
            BrainSpec::parse("phase-grid:freq").unwrap().parameter_count(&m, &rpv),
            Ok(24)
        );
    }

    #[test]
    fn parse_accepts_every_short_form_and_rejects_the_rest() {
        assert_eq!(BrainSpec::parse("phase"), Ok(BrainSpec::default()));
        assert_eq!(
            BrainSpec::parse("random:0.5"),
            Ok(BrainSpec::Random { period: 0.5, seed: 0 })
        );
        assert_eq!(
            BrainSpec::parse("mlp:16,8").unwrap(),
            BrainSpec::Mlp {
                hidden: Some(vec![16, 8]),
                activation: Activation::Tanh,
                input_activation: true,
                weights: vec![]
            }
        );
        assert!(matches!(
            BrainSpec::parse("mlp"),
            Ok(BrainSpec::Mlp { hidden: None, .. })
        ));
        assert!(matches!(
            BrainSpec::parse("distributed-mlp-hetero:3"),
            Ok(BrainSpec::DistributedMlp {
                signals: 3,
                layout: Layout::Heterogeneous,
                ..
            })
        ));
        assert!(matches!(
            BrainSpec::parse("distributed-mlp"),
            Ok(BrainSpec::DistributedMlp {
                signals: 1,
                layout: Layout::Homogeneous,
                ..
            })
        ));
        let nested = BrainSpec::parse("step:0.33:smoothed:5:random:0.1").unwrap();
        assert_eq!(
            nested,
            BrainSpec::Step {
                period: 0.33,
                inner: Box::new(BrainSpec::Smoothed {
                    speed: 5.0,
                    inner: Box::new(BrainSpec::Random { period: 0.1, seed: 0 })
                })
            }
        );
        for bad in [
            "",
            "brain",
            "constant",
            "phase:1",
            "mlp:a",
            "mlp:",
            "distributed-mlp:x",
            "step:0.33",
            "step:x:phase",
            "smoothed:1:nope",
            "phase-grid:x",
        ] {
            let err = BrainSpec::parse(bad).unwrap_err();
            assert_eq!(err, BrainError::Unknown(bad.to_string()), "{bad}");
            assert!(err.to_string().contains("distributed-mlp-hetero[:<signals>]"), "{err}");
        }
    }

    #[test]
    fn json_templates_of_the_experiment_configs_parse_with_defaults() {
        let spec: BrainSpec = serde_json::from_str(
            r#"{"kind": "distributed-mlp", "signals": 1, "hidden": [], "layout": "heterogeneous"}"#,
        )
        .unwrap();
        assert_eq!(
            spec,
            BrainSpec::DistributedMlp {
                signals: 1,
                hidden: vec![],
                activation: Activation::Tanh,
                input_activation: true,
                layout: Layout::Heterogeneous,
                weights: vec![]
            }
        );
        let spec: BrainSpec = serde_json::from_str(r#"{"kind": "mlp"}"#).unwrap();
        assert_eq!(spec, BrainSpec::parse("mlp").unwrap());
        let spec: BrainSpec = serde_json::from_str(
            r#"{"kind": "step", "period": 0.33, "inner": {"kind": "mlp", "hidden": [3], "activation": "relu"}}"#,
        )
        .unwrap();
        assert!(matches!(spec, BrainSpec::Step { .. }));
        for bad in [
            r#"{"kind": "mlp", "hiden": [3]}"#,
            r#"{"kind": "distributed-mlp", "layout": "mixed"}"#,
            r#"{"kind": "mlp", "activation": "softmax"}"#,
            r#"{"kind": "step", "inner": {"kind": "phase"}}"#,
            r#"{"kind": "smoothed", "speed": 1, "inner": {"kind": "phase", "extra": 1}}"#,
        ] {
            assert!(serde_json::from_str::<BrainSpec>(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn every_kind_round_trips_through_json_bit_for_bit() {
        for spec in every_kind() {
            let json = serde_json::to_string_pretty(&spec).unwrap();
            let back: BrainSpec = serde_json::from_str(&json).unwrap();
            assert_eq!(back, spec, "{json}");
            let (a, b) = (spec.parameters(), back.parameters());
            assert_eq!(a.len(), b.len());
            assert!(a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits()));
            assert!(json.contains(&format!("\"kind\": \"{}\"", spec.kind())), "{json}");
        }
        let json = serde_json::to_string(&homogeneous()).unwrap();
        assert_eq!(
            json,
            r#"{"kind":"distributed-mlp","signals":1,"hidden":[],"activation":"tanh","input_activation":true,"layout":"homogeneous","weights":[]}"#
        );
    }

    #[test]
    fn every_kind_builds_and_actuates_within_bounds() {
        let (m, rpv) = biped();
        for spec in every_kind() {
            let mut c = spec.build(&m, &rpv).unwrap_or_else(|e| panic!("{spec:?}: {e}"));
            c.reset();
            let mut a = vec![0.0; 10];
            for k in 1..=120 {
                let t = k as f64 / 60.0;
                let readings: Vec<f64> = (0..40).map(|i| (3.0 * t + i as f64).sin()).collect();
                c.control(t, &readings, &mut a);
                assert!(
                    a.iter().all(|v| (-1.0..=1.0).contains(v)),
                    "{} at step {k}: {a:?}",
                    spec.kind()
                );
            }
        }
    }

    #[test]
    fn build_rejects_missing_wrong_and_non_finite_weights() {
        let (m, rpv) = biped();
        let err = BrainSpec::parse("mlp").unwrap().build(&m, &rpv).err().unwrap();
        assert_eq!(
            err,
            BrainError::Invalid {
                field: "weights",
                msg: "expected 1336 for this body and sensors, got 0".into()
            }
        );
        let err = homogeneous()
            .with_parameters(&[0.1; 44])
            .unwrap()
            .build(&m, &rpv)
            .err()
            .unwrap();
        assert_eq!(
            err.to_string(),
            "brain.weights: expected 45 for this body and sensors, got 44"
        );
        let err = BrainSpec::parse("phase-grid").unwrap().build(&m, &rpv).err().unwrap();
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 12 for this body and sensors, got 0"
        );
        let err = BrainSpec::parse("step:0.3:distributed-mlp-hetero")
            .unwrap()
            .build(&m, &rpv)
            .err()
            .unwrap();
        assert_eq!(
            err.to_string(),
            "brain.weights: expected 540 for this body and sensors, got 0"
        );

        let mut w = vec![0.0; 45];
        w[3] = f64::INFINITY;
        let with_inf = BrainSpec::DistributedMlp {
            signals: 1,
            hidden: vec![],
            activation: Activation::Tanh,
            input_activation: true,
            layout: Layout::Homogeneous,
            weights: w,
        };
        let err = with_inf.build(&m, &rpv).err().unwrap();
        assert!(matches!(err, BrainError::Invalid { field: "weights", .. }), "{err}");
        assert!(err.to_string().contains("value 3 is inf"), "{err}");

        let err = homogeneous().build(&m, &[4, 4, 4, 4, 4, 4, 4, 4, 4, 3]).err().unwrap();
        assert!(
            matches!(
                err,
                BrainError::Invalid {
                    field: "readings_per_voxel",
                    ..
                }
            ),
            "{err}"
        );
        let err = BrainSpec::parse("mlp").unwrap().build(&m, &[4; 9]).err().unwrap();
        assert!(
            matches!(
                err,
                BrainError::Invalid {
                    field: "readings_per_voxel",
                    ..
                }
            ),
            "{err}"
        );
        let err = BrainSpec::parse("step:-1:phase")
            .unwrap()
            .build(&m, &rpv)
            .err()
            .unwrap();
        assert!(matches!(err, BrainError::Invalid { field: "period", .. }), "{err}");
        let err = BrainSpec::parse("smoothed:nan:phase")
            .unwrap()
            .build(&m, &rpv)
            .err()
            .unwrap();
        assert!(matches!(err, BrainError::Invalid { field: "speed", .. }), "{err}");
        let err = BrainSpec::parse("mlp:4,0")
            .unwrap()
            .parameter_count(&m, &rpv)
            .unwrap_err();
        assert!(matches!(err, BrainError::Invalid { field: "hidden", .. }), "{err}");
    }

    #[test]
    fn with_parameters_fills_checks_and_delegates() {
        let (m, rpv) = biped();
        let params: Vec<f64> = (0..45).map(|i| i as f64 / 100.0).collect();
        let filled = homogeneous().with_parameters(&params).unwrap();
        assert_eq!(filled.parameters(), &params[..]);
        let wrapped = BrainSpec::parse("smoothed:2:step:0.3:distributed-mlp")
            .unwrap()
            .with_parameters(&params)
            .unwrap();
        assert_eq!(wrapped.parameters(), &params[..]);
        assert!(wrapped.build(&m, &rpv).is_ok());

        let err = homogeneous().with_parameters_for(&params[..40], &m, &rpv).unwrap_err();
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 45 for this body and sensors, got 40"
        );
        assert!(homogeneous().with_parameters_for(&params, &m, &rpv).is_ok());

        let err = BrainSpec::default().with_parameters(&[1.0, 2.0]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 0 for a phase brain (it has none), got 2"
        );
        assert_eq!(BrainSpec::default().with_parameters(&[]), Ok(BrainSpec::default()));
        let err = homogeneous().with_parameters(&[0.0, f64::NAN]).unwrap_err();
        assert!(matches!(err, BrainError::Invalid { field: "weights", .. }), "{err}");
    }

    #[test]
    fn random_parameters_are_reproducible_and_in_range() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("mlp").unwrap();
        let a = spec.with_random_parameters(7, &m, &rpv).unwrap();
        let b = spec.with_random_parameters(7, &m, &rpv).unwrap();
        let c = spec.with_random_parameters(8, &m, &rpv).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_eq!(a.parameters().len(), 1336);
        assert!(a.parameters().iter().all(|w| (-1.0..=1.0).contains(w)));
        assert_eq!(
            BrainSpec::default().with_random_parameters(7, &m, &rpv),
            Ok(BrainSpec::default())
        );
    }

    #[test]
    fn a_built_distributed_brain_is_deterministic_across_reset() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("distributed-mlp-hetero:2")
            .unwrap()
            .with_random_parameters(3, &m, &rpv)
            .unwrap();
        let mut c = spec.build(&m, &rpv).unwrap();
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
