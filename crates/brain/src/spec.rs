//! [`BrainSpec`]: the serialisable description of a brain — the list of registered brain kinds.

use crate::controllers::attention::AttentionSpec;
use crate::controllers::centralized_mlp::MlpSpec;
use crate::controllers::constant::ConstantSpec;
use crate::controllers::distributed_mlp::DistributedMlpSpec;
use crate::controllers::elman::ElmanSpec;
use crate::controllers::graph::GraphSpec;
use crate::controllers::heads::HeadsSpec;
use crate::controllers::hebbian::HebbianSpec;
use crate::controllers::phase::PhaseSpec;
use crate::controllers::phase_grid::PhaseGridSpec;
use crate::controllers::policy::PolicySpec;
use crate::controllers::random::RandomSpec;
use crate::controllers::smoothed::SmoothedSpec;
use crate::controllers::step::StepSpec;
use crate::validation::check_count;
use crate::{short_form, BrainError, BrainKind, BrainShape, Controller};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Description of a brain, as written in configs and robot files (JSON or TOML, tagged by `kind`).
///
/// Each variant registers one brain kind: it wraps that kind's description, which lives next to its
/// controller and implements [`BrainKind`]; every method here delegates to it
/// ([`BrainSpec::as_kind`]).
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
/// {"kind": "hebbian", "model": "full", "eta": 0.01, "normalisation": "none", "init": "zero",
///  "learning": true, "parameters": [...]}
/// {"kind": "attention", "d_k": 8, "layout": "homogeneous", "slow": false, "parameters": [...]}
/// {"kind": "graph", "neurons": [{"kind": "sensing", "x": 0, "y": 0, "reading": 0}, ...],
///  "edges": [{"from": 0, "to": 4}, ...], "parameters": [...]}
/// {"kind": "heads", "linear_outputs": 1, "weights": [...]}
/// {"kind": "policy", "hidden": [64, 64], "mean": [...], "var": [...], "scale": 2.0,
///  "offset": -0.2, "weights": [...]}
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum BrainSpec {
    /// Open-loop sinusoid with a phase gradient across the body ([`PhaseSpec`]).
    Phase(PhaseSpec),
    /// The same constant actuation on every voxel ([`ConstantSpec`]).
    Constant(ConstantSpec),
    /// Uniform random actuations, redrawn periodically ([`RandomSpec`]).
    Random(RandomSpec),
    /// Open-loop sinusoids with evolvable per-voxel phases and frequencies ([`PhaseGridSpec`]).
    PhaseGrid(PhaseGridSpec),
    /// Centralized MLP: all readings in, one actuation per voxel out ([`MlpSpec`]).
    Mlp(MlpSpec),
    /// One MLP per voxel with neighbour signals ([`DistributedMlpSpec`]).
    DistributedMlp(DistributedMlpSpec),
    /// Holds the inner brain's output for a period ([`StepSpec`]).
    Step(StepSpec),
    /// Rate-limits the inner brain's output ([`SmoothedSpec`]).
    Smoothed(SmoothedSpec),
    /// Centralized network whose weights follow evolved Hebbian ABCD rules ([`HebbianSpec`]).
    Hebbian(HebbianSpec),
    /// The same self-attention network in every voxel, no communication ([`AttentionSpec`]).
    Attention(AttentionSpec),
    /// A graph of neurons located in voxels (the self-organizing controller, [`GraphSpec`]).
    Graph(GraphSpec),
    /// One layer, tanh heads and linear heads (the PSA controller, [`HeadsSpec`]).
    Heads(HeadsSpec),
    /// The affordance study's Elman network in every voxel, with a vote ([`ElmanSpec`]).
    Elman(ElmanSpec),
    /// A policy learned by PPO in the co-design loop ([`PolicySpec`]).
    Policy(PolicySpec),
}

/// Every `kind` tag, in the order of [`BrainSpec`]'s variants.
const KINDS: &[&str] = &[
    "phase",
    "constant",
    "random",
    "phase-grid",
    "mlp",
    "distributed-mlp",
    "step",
    "smoothed",
    "hebbian",
    "attention",
    "graph",
    "heads",
    "elman",
    "policy",
];

impl<'de> Deserialize<'de> for BrainSpec {
    /// Reads the `kind` tag, then that kind's fields, so that an error names the field inside the
    /// brain (`signals: invalid type…`), which serde's derive for tagged enums cannot do.
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        use serde::de::Error;
        let mut fields = match serde_json::Value::deserialize(deserializer)? {
            serde_json::Value::Object(fields) => fields,
            other => return Err(D::Error::custom(format!("expected a table with a `kind`, got {other}"))),
        };
        let kind = match fields.remove("kind") {
            Some(serde_json::Value::String(kind)) => kind,
            Some(other) => return Err(D::Error::custom(format!("kind: expected a string, got {other}"))),
            None => return Err(D::Error::missing_field("kind")),
        };
        let fields = serde_json::Value::Object(fields);
        Ok(match kind.as_str() {
            "phase" => BrainSpec::Phase(payload(fields)?),
            "constant" => BrainSpec::Constant(payload(fields)?),
            "random" => BrainSpec::Random(payload(fields)?),
            "phase-grid" => BrainSpec::PhaseGrid(payload(fields)?),
            "mlp" => BrainSpec::Mlp(payload(fields)?),
            "distributed-mlp" => BrainSpec::DistributedMlp(payload(fields)?),
            "step" => BrainSpec::Step(payload(fields)?),
            "smoothed" => BrainSpec::Smoothed(payload(fields)?),
            "hebbian" => BrainSpec::Hebbian(payload(fields)?),
            "attention" => BrainSpec::Attention(payload(fields)?),
            "graph" => BrainSpec::Graph(payload(fields)?),
            "heads" => BrainSpec::Heads(payload(fields)?),
            "elman" => BrainSpec::Elman(payload(fields)?),
            "policy" => BrainSpec::Policy(payload(fields)?),
            other => {
                return Err(D::Error::custom(format!(
                    "kind: unknown brain kind `{other}`, expected one of {}",
                    KINDS.join(", ")
                )))
            }
        })
    }
}

/// Decodes one kind's fields, prefixing an error with the path of the field inside them.
fn payload<T: serde::de::DeserializeOwned, E: serde::de::Error>(fields: serde_json::Value) -> Result<T, E> {
    serde_path_to_error::deserialize(fields).map_err(|e| {
        let path = e.path().to_string();
        if path == "." {
            E::custom(e.into_inner())
        } else {
            E::custom(format!("{path}: {}", e.into_inner()))
        }
    })
}

impl Default for BrainSpec {
    /// A phase brain with its defaults.
    fn default() -> Self {
        BrainSpec::Phase(PhaseSpec::default())
    }
}

impl BrainSpec {
    /// The registered kind's description, through which every other method goes.
    pub fn as_kind(&self) -> &dyn BrainKind {
        match self {
            BrainSpec::Phase(kind) => kind,
            BrainSpec::Constant(kind) => kind,
            BrainSpec::Random(kind) => kind,
            BrainSpec::PhaseGrid(kind) => kind,
            BrainSpec::Mlp(kind) => kind,
            BrainSpec::DistributedMlp(kind) => kind,
            BrainSpec::Step(kind) => kind,
            BrainSpec::Smoothed(kind) => kind,
            BrainSpec::Hebbian(kind) => kind,
            BrainSpec::Attention(kind) => kind,
            BrainSpec::Graph(kind) => kind,
            BrainSpec::Heads(kind) => kind,
            BrainSpec::Elman(kind) => kind,
            BrainSpec::Policy(kind) => kind,
        }
    }

    /// [`BrainSpec::as_kind`], mutable.
    pub fn as_kind_mut(&mut self) -> &mut dyn BrainKind {
        match self {
            BrainSpec::Phase(kind) => kind,
            BrainSpec::Constant(kind) => kind,
            BrainSpec::Random(kind) => kind,
            BrainSpec::PhaseGrid(kind) => kind,
            BrainSpec::Mlp(kind) => kind,
            BrainSpec::DistributedMlp(kind) => kind,
            BrainSpec::Step(kind) => kind,
            BrainSpec::Smoothed(kind) => kind,
            BrainSpec::Hebbian(kind) => kind,
            BrainSpec::Attention(kind) => kind,
            BrainSpec::Graph(kind) => kind,
            BrainSpec::Heads(kind) => kind,
            BrainSpec::Elman(kind) => kind,
            BrainSpec::Policy(kind) => kind,
        }
    }

    /// The `kind` tag, as in configs.
    pub fn kind(&self) -> &'static str {
        self.as_kind().name()
    }

    /// Parses a short name from the command line, one of the [`crate::SHORT_FORMS`]:
    /// - `phase`, `constant:<value>`, `random[:<period s>]`;
    /// - `phase-grid` (per-cell phases) or `phase-grid:freq` (per-cell phases and frequencies);
    /// - `mlp` (default hidden layer), `mlp:<sizes>` (e.g. `mlp:26` or `mlp:16,8`), `mlp:none`
    ///   (no hidden layer);
    /// - `distributed-mlp[:<signals>]` (homogeneous), `distributed-mlp-hetero[:<signals>]`
    ///   (heterogeneous), both without hidden layer, default 1 signal;
    /// - `step:<period s>:<brain>`, `smoothed:<speed>:<brain>` wrapping any of these.
    ///
    /// Anything else is [`BrainError::Unknown`], whose message lists every form. Parameterised
    /// brains come with no parameters: fill them with [`BrainSpec::with_parameters`] or
    /// [`BrainSpec::with_random_parameters`] before building.
    pub fn parse(s: &str) -> Result<BrainSpec, BrainError> {
        short_form::parse(s)
    }

    /// Number of parameters this brain needs for a body of this shape (units, their readings
    /// counts, their layout): 0 for parameterless brains (`phase`, `constant`, `random`); wrappers
    /// delegate to their inner brain. Errors when the shape does not fit the body (for example
    /// unequal readings counts for a distributed MLP).
    pub fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        self.as_kind().parameter_count(shape)
    }

    /// The parameter vector (empty for parameterless brains and unfilled templates); wrappers give
    /// their inner brain's.
    pub fn parameters(&self) -> &[f64] {
        self.as_kind().parameters()
    }

    /// The same brain with this parameter vector (weights of an MLP, parameters of a phase grid;
    /// wrappers pass it to their inner brain).
    ///
    /// Errors when a parameterless brain gets a non-empty vector (field `parameters`, naming both
    /// counts) or a value is not finite. The count for a body is checked by [`BrainSpec::build`],
    /// or here already with [`BrainSpec::with_parameters_for`].
    pub fn with_parameters(&self, params: &[f64]) -> Result<BrainSpec, BrainError> {
        let mut spec = self.clone();
        spec.as_kind_mut().set_parameters(params)?;
        Ok(spec)
    }

    /// [`BrainSpec::with_parameters`], first checking the count against
    /// [`BrainSpec::parameter_count`] for this body: a mismatch is an error on field `parameters`,
    /// "expected N for this body and sensors, got M".
    pub fn with_parameters_for(&self, params: &[f64], shape: &BrainShape) -> Result<BrainSpec, BrainError> {
        let expected = self.parameter_count(shape)?;
        check_count("parameters", expected, params.len())?;
        self.with_parameters(params)
    }

    /// The same brain with [`BrainSpec::parameter_count`] parameters drawn uniformly in [−1, 1]
    /// from a ChaCha8 generator seeded with `seed` (reproducible: a random brain for the command
    /// line or a benchmark). Parameterless brains come back unchanged.
    pub fn with_random_parameters(&self, seed: u64, shape: &BrainShape) -> Result<BrainSpec, BrainError> {
        let n = self.parameter_count(shape)?;
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let params: Vec<f64> = (0..n).map(|_| rng.random_range(-1.0..=1.0)).collect();
        self.with_parameters(&params)
    }

    /// Builds the controller for a body of this shape.
    ///
    /// Validates every field; a parameter vector of the wrong length is an error on `weights`
    /// (MLPs) or `parameters` (phase grid): "expected N for this body and sensors, got M" (an
    /// unfilled template has M = 0).
    pub fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        self.as_kind().build(shape)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{assert_invalid, biped};
    use crate::{Activation, Layout, PhaseLayout};

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
            "hebbian",
            "hebbian:incoming",
            "hebbian:dew",
            "hebbian:l2",
            "attention",
            "attention:hetero",
            "attention:slow",
            "local-mlp",
            "local-mlp:1",
            "step:0.33:attention",
            "graph",
        ];
        let mut specs: Vec<BrainSpec> = templates
            .iter()
            .enumerate()
            .map(|(k, s)| {
                BrainSpec::parse(s)
                    .unwrap()
                    .with_random_parameters(k as u64, &BrainShape::grid(&m, &rpv))
                    .unwrap()
            })
            .collect();
        specs.push(
            BrainSpec::DistributedMlp(DistributedMlpSpec {
                signals: 2,
                hidden: vec![6, 4],
                activation: Activation::Sin,
                input_activation: false,
                layout: Layout::Heterogeneous,
                positional: false,
                weights: Vec::new(),
            })
            .with_random_parameters(99, &BrainShape::grid(&m, &rpv))
            .unwrap(),
        );
        specs.push(
            BrainSpec::PhaseGrid(PhaseGridSpec {
                frequency: 0.5,
                amplitude: 0.8,
                evolve_frequency: true,
                layout: PhaseLayout::Voxels,
                parameters: Vec::new(),
            })
            .with_random_parameters(100, &BrainShape::grid(&m, &rpv))
            .unwrap(),
        );
        specs.push(
            BrainSpec::Mlp(MlpSpec {
                hidden: Some(vec![7]),
                activation: Activation::Relu,
                input_activation: false,
                weights: Vec::new(),
            })
            .with_random_parameters(101, &BrainShape::grid(&m, &rpv))
            .unwrap(),
        );
        specs
    }

    #[test]
    fn every_variant_is_exercised_and_its_name_is_its_tag() {
        let mut names: Vec<&str> = every_kind().iter().map(BrainSpec::kind).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(
            names,
            [
                "attention",
                "constant",
                "distributed-mlp",
                "graph",
                "hebbian",
                "mlp",
                "phase",
                "phase-grid",
                "random",
                "smoothed",
                "step"
            ]
        );
        for spec in every_kind() {
            let value = serde_json::to_value(&spec).unwrap();
            assert_eq!(value["kind"], spec.kind(), "{value}");
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
            BrainSpec::DistributedMlp(DistributedMlpSpec {
                signals: 1,
                hidden: vec![],
                activation: Activation::Tanh,
                input_activation: true,
                layout: Layout::Heterogeneous,
                positional: false,
                weights: vec![]
            })
        );
        let spec: BrainSpec = serde_json::from_str(r#"{"kind": "mlp"}"#).unwrap();
        assert_eq!(spec, BrainSpec::parse("mlp").unwrap());
        let spec: BrainSpec = serde_json::from_str(r#"{"kind": "phase", "phase_y": 0.5}"#).unwrap();
        assert_eq!(
            spec,
            BrainSpec::Phase(PhaseSpec {
                phase_y: 0.5,
                ..PhaseSpec::default()
            })
        );
        let spec: BrainSpec = serde_json::from_str(r#"{"kind": "random", "seed": 4}"#).unwrap();
        assert_eq!(spec, BrainSpec::Random(RandomSpec { period: 0.0, seed: 4 }));
        let spec: BrainSpec = serde_json::from_str(r#"{"kind": "phase-grid"}"#).unwrap();
        assert_eq!(spec, BrainSpec::parse("phase-grid").unwrap());
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
            r#"{"kind": "phase", "frequency": 1, "extra": 1}"#,
            r#"{"kind": "constant"}"#,
            r#"{"kind": "constant", "value": 1, "seed": 2}"#,
            r#"{"kind": "random", "period": 1, "value": 2}"#,
            r#"{"kind": "phase-grid", "weights": []}"#,
            r#"{"kind": "distributed-mlp", "parameters": []}"#,
            r#"{"kind": "step", "period": 1, "speed": 2, "inner": {"kind": "phase"}}"#,
            r#"{"kind": "neat"}"#,
            r#"{"frequency": 1}"#,
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
    fn every_kind_serialises_its_fields_in_declaration_order() {
        let forms = [
            (
                BrainSpec::default(),
                r#"{"kind":"phase","frequency":1.0,"amplitude":1.0,"phase_x":1.0,"phase_y":0.0}"#,
            ),
            (
                BrainSpec::parse("constant:0.5").unwrap(),
                r#"{"kind":"constant","value":0.5}"#,
            ),
            (
                BrainSpec::parse("random:0.25").unwrap(),
                r#"{"kind":"random","period":0.25,"seed":0}"#,
            ),
            (
                BrainSpec::parse("phase-grid:freq").unwrap(),
                r#"{"kind":"phase-grid","frequency":1.0,"amplitude":1.0,"evolve_frequency":true,"layout":"grid","parameters":[]}"#,
            ),
            (
                BrainSpec::parse("mlp").unwrap(),
                r#"{"kind":"mlp","activation":"tanh","input_activation":true,"weights":[]}"#,
            ),
            (
                BrainSpec::parse("mlp:3").unwrap(),
                r#"{"kind":"mlp","hidden":[3],"activation":"tanh","input_activation":true,"weights":[]}"#,
            ),
            (
                BrainSpec::parse("step:0.5:smoothed:2:constant:1").unwrap(),
                r#"{"kind":"step","period":0.5,"inner":{"kind":"smoothed","speed":2.0,"inner":{"kind":"constant","value":1.0}}}"#,
            ),
        ];
        for (spec, json) in forms {
            assert_eq!(serde_json::to_string(&spec).unwrap(), json);
        }
    }

    #[test]
    fn parameterless_kinds_count_no_parameters() {
        let (m, rpv) = biped();
        for s in ["phase", "constant:0", "random", "step:1:phase"] {
            assert_eq!(
                BrainSpec::parse(s)
                    .unwrap()
                    .parameter_count(&BrainShape::grid(&m, &rpv)),
                Ok(0),
                "{s}"
            );
        }
    }

    #[test]
    fn every_kind_builds_and_actuates_within_bounds() {
        let (m, rpv) = biped();
        for spec in every_kind() {
            let mut c = spec
                .build(&BrainShape::grid(&m, &rpv))
                .unwrap_or_else(|e| panic!("{spec:?}: {e}"));
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
        assert!(wrapped.build(&BrainShape::grid(&m, &rpv)).is_ok());

        let err = homogeneous()
            .with_parameters_for(&params[..40], &BrainShape::grid(&m, &rpv))
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 45 for this body and sensors, got 40"
        );
        assert!(homogeneous()
            .with_parameters_for(&params, &BrainShape::grid(&m, &rpv))
            .is_ok());

        let err = BrainSpec::default().with_parameters(&[1.0, 2.0]).unwrap_err();
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 0 for a phase brain (it has none), got 2"
        );
        let err = BrainSpec::parse("step:1:random")
            .unwrap()
            .with_parameters(&[1.0])
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 0 for a random brain (it has none), got 1"
        );
        assert_eq!(BrainSpec::default().with_parameters(&[]), Ok(BrainSpec::default()));
        let err = homogeneous().with_parameters(&[0.0, f64::NAN]).unwrap_err();
        assert_invalid(&err, "weights");
        let err = BrainSpec::parse("phase-grid")
            .unwrap()
            .with_parameters(&[f64::INFINITY])
            .unwrap_err();
        assert_invalid(&err, "parameters");
    }

    #[test]
    fn random_parameters_are_reproducible_and_in_range() {
        let (m, rpv) = biped();
        let spec = BrainSpec::parse("mlp").unwrap();
        let a = spec.with_random_parameters(7, &BrainShape::grid(&m, &rpv)).unwrap();
        let b = spec.with_random_parameters(7, &BrainShape::grid(&m, &rpv)).unwrap();
        let c = spec.with_random_parameters(8, &BrainShape::grid(&m, &rpv)).unwrap();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_eq!(a.parameters().len(), 1336);
        assert!(a.parameters().iter().all(|w| (-1.0..=1.0).contains(w)));
        assert_eq!(
            BrainSpec::default().with_random_parameters(7, &BrainShape::grid(&m, &rpv)),
            Ok(BrainSpec::default())
        );
    }
}
