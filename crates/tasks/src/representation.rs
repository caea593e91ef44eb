//! From a flat genotype to a robot (thesis §3.3.5): a representation is a body part and a brain
//! part over one vector `v = [v_body v_brain]`, plus the sensors and the physical preset.
//!
//! - The body part is either a fixed [`Morphology`] (no genes) or a [`BodyEncoding`] (Direct: W·H
//!   genes, GMM: 5 genes per Gaussian).
//! - The brain part is a [`BrainSpec`] *template*: its kind and shape; its parameters come from
//!   the genotype. With an evolved body the brain's parameter count must not depend on which cells
//!   the decoded body occupies (distributed MLPs, homogeneous or one block per grid cell); a brain
//!   whose count does (a centralised MLP) needs a fixed body, and is rejected otherwise.
//!
//! [`evaluate`] is the pure function (mapper, genotype, task, seed) → outcome that the optimizers
//! call, from as many threads as they like; [`Mapper`] makes it generic over the genotype.

use crate::agent::Robot;
use crate::episode::{self, EpisodeError};
use crate::kinds::psa::robot::PsaRobot;
use crate::kinds::voxel::robot::RobotSpec;
use crate::outcome::{Outcome, TraceLevel};
use crate::task::Task;
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use vsrlab_body::encodings::BodyEncoding;
use vsrlab_body::psa::PsaBody;
use vsrlab_body::sensors::{SensorConfig, SensorSuite};
use vsrlab_body::{Morphology, Preset};
use vsrlab_brain::BrainShape;
use vsrlab_brain::BrainSpec;

/// Where the body comes from. In configs: a shape name or text grid (`"biped-4x3"`, `"##/#."`) or
/// a list of rows for a fixed body; a table with `kind = "direct"` or `"gmm"` for an encoded one;
/// a table with `kind = "psa"` for a pressure-based soft agent (fixed body, thesis ch. 6).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum BodyPart {
    /// The same body for every genotype (no body genes).
    Fixed(Morphology),
    /// A body decoded from the first genes of the genotype.
    Encoded(BodyEncoding),
    /// A pressure-based soft agent (no body genes; the genotype is its brain).
    Psa(PsaTable),
}

/// A PSA body in an experiment file: `{ kind = "psa", size = …, … }` (see [`PsaBody`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PsaTable {
    /// Always `psa`.
    pub kind: PsaKind,
    /// Size and constants.
    #[serde(flatten)]
    pub body: PsaBody,
}

/// The `kind` tag of a PSA body table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PsaKind {
    /// A pressure-based soft agent.
    Psa,
}

impl<'de> Deserialize<'de> for BodyPart {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(BodyPartVisitor)
    }
}

struct BodyPartVisitor;

impl<'de> Visitor<'de> for BodyPartVisitor {
    type Value = BodyPart;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a shape name, a text grid, a list of rows, or a body encoding {kind = \"direct\" | \"gmm\", …}")
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<BodyPart, E> {
        Morphology::parse(s).map(BodyPart::Fixed).map_err(E::custom)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<BodyPart, A::Error> {
        Morphology::deserialize(SeqAccessDeserializer::new(seq)).map(BodyPart::Fixed)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<BodyPart, A::Error> {
        let table = serde_json::Value::deserialize(MapAccessDeserializer::new(map))?;
        if table.get("kind").and_then(serde_json::Value::as_str) == Some("psa") {
            return PsaBody::deserialize(table).map_err(de::Error::custom).map(|body| {
                BodyPart::Psa(PsaTable {
                    kind: PsaKind::Psa,
                    body,
                })
            });
        }
        BodyEncoding::deserialize(table)
            .map_err(de::Error::custom)
            .map(BodyPart::Encoded)
    }
}

/// A genotype → robot mapping: body part, sensors, brain template and preset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Representation {
    /// The body: fixed, or decoded from the body genes.
    pub body: BodyPart,
    /// Sensors on every voxel (thesis ch. 3: `uniform-vxy+a+t-0` style placements); required for
    /// voxel bodies, absent for a PSA (it has its own).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sensors: Option<SensorConfig>,
    /// The brain's kind and shape; its parameters are the brain genes.
    pub brain: BrainSpec,
    /// Physical preset of the voxels (ignored for a PSA).
    #[serde(default)]
    pub preset: Preset,
}

/// Why a genotype could not become a robot, or an evaluation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EvaluationError {
    /// The representation itself is unusable; the message names the field.
    #[error("representation.{0}")]
    Representation(String),
    /// The genotype does not fit the representation.
    #[error("genotype: {0}")]
    Genotype(String),
    /// The episode could not be run or blew up.
    #[error(transparent)]
    Episode(#[from] EpisodeError),
}

impl Representation {
    /// Number of body genes (0 for a fixed body).
    pub fn body_genes(&self) -> usize {
        match &self.body {
            BodyPart::Fixed(_) | BodyPart::Psa(_) => 0,
            BodyPart::Encoded(encoding) => encoding.gene_count(),
        }
    }

    /// The voxel sensors; an error for a voxel body without them.
    pub fn sensors(&self) -> Result<&SensorConfig, EvaluationError> {
        self.sensors.as_ref().ok_or_else(|| {
            EvaluationError::Representation("sensors: missing: voxel bodies need a sensor placement".into())
        })
    }

    /// The PSA robot (brain as a template) of a PSA representation.
    fn psa_robot(&self, body: &PsaBody) -> Result<PsaRobot, EvaluationError> {
        if self.sensors.is_some() {
            return Err(EvaluationError::Representation(
                "sensors: a PSA has its own sensors (3 per mass and 3 for the whole); remove this field".into(),
            ));
        }
        Ok(PsaRobot {
            body: body.clone(),
            brain: self.brain.clone(),
        })
    }

    /// Number of brain genes. With an encoded body it is computed on the full W×H grid and must be
    /// the same for a single-voxel body, otherwise the brain cannot follow an evolving body.
    pub fn brain_genes(&self) -> Result<usize, EvaluationError> {
        match &self.body {
            BodyPart::Fixed(body) => self.brain_parameters_for(body),
            BodyPart::Psa(table) => {
                let robot = self.psa_robot(&table.body)?;
                robot.validate_body().map_err(representation_message)?;
                robot.brain_parameters().map_err(representation_message)
            }
            BodyPart::Encoded(encoding) => {
                encoding
                    .validate()
                    .map_err(|e| EvaluationError::Representation(format!("body: {e}")))?;
                let (w, h) = (encoding.width(), encoding.height());
                let full = Morphology::from_fn(w, h, |_, _| true).map_err(representation_error("body"))?;
                let single =
                    Morphology::from_fn(w, h, |x, y| x == 0 && y == 0).map_err(representation_error("body"))?;
                let count = self.brain_parameters_for(&full)?;
                if self.brain_parameters_for(&single)? != count {
                    return Err(EvaluationError::Representation(
                        "brain: its parameter count depends on the body's voxels, so it cannot be used with an \
                         evolved body; use a fixed body or a distributed brain"
                            .to_string(),
                    ));
                }
                Ok(count)
            }
        }
    }

    /// Total genotype length: body genes then brain genes.
    pub fn genotype_length(&self) -> Result<usize, EvaluationError> {
        self.body_genes()
            .checked_add(self.brain_genes()?)
            .ok_or_else(|| EvaluationError::Representation("too many genes to count".to_string()))
    }

    /// Checks that the representation is usable (body encoding, sensors and brain fit together).
    pub fn validate(&self) -> Result<(), EvaluationError> {
        self.genotype_length().map(|_| ())
    }

    /// Builds the robot a genotype stands for, of any body kind.
    pub fn any_robot(&self, genotype: &[f64]) -> Result<Box<dyn Robot>, EvaluationError> {
        let BodyPart::Psa(table) = &self.body else {
            return Ok(Box::new(self.robot(genotype)?));
        };
        let expected = self.genotype_length()?;
        if genotype.len() != expected {
            return Err(EvaluationError::Genotype(format!(
                "expected {expected} genes (brain), got {}",
                genotype.len()
            )));
        }
        let mut robot = self.psa_robot(&table.body)?;
        robot.brain = self
            .brain
            .with_parameters(genotype)
            .map_err(|e| EvaluationError::Genotype(e.to_string()))?;
        Ok(Box::new(robot))
    }

    /// Builds the voxel robot a genotype stands for (an error for a PSA: see
    /// [`Representation::any_robot`]).
    pub fn robot(&self, genotype: &[f64]) -> Result<RobotSpec, EvaluationError> {
        let expected = self.genotype_length()?;
        if genotype.len() != expected {
            return Err(EvaluationError::Genotype(format!(
                "expected {expected} genes ({} body + {} brain), got {}",
                self.body_genes(),
                expected - self.body_genes(),
                genotype.len()
            )));
        }
        let (body_genes, brain_genes) = genotype.split_at(self.body_genes());
        let body = match &self.body {
            BodyPart::Fixed(body) => body.clone(),
            BodyPart::Encoded(encoding) => encoding
                .decode(body_genes)
                .map_err(|e| EvaluationError::Genotype(format!("body: {e}")))?,
            BodyPart::Psa(_) => {
                return Err(EvaluationError::Representation(
                    "body: a PSA is not a voxel robot (this analysis reads voxel robots only)".into(),
                ))
            }
        };
        let brain = self
            .brain
            .with_parameters(brain_genes)
            .map_err(|e| EvaluationError::Genotype(e.to_string()))?;
        Ok(RobotSpec {
            body,
            preset: self.preset,
            voxel: None,
            sensors: self.sensors()?.clone(),
            brain,
        })
    }

    fn brain_parameters_for(&self, body: &Morphology) -> Result<usize, EvaluationError> {
        let suite = SensorSuite::new(self.sensors()?, body, 0).map_err(representation_error("sensors"))?;
        let per_voxel: Vec<usize> = (0..body.voxel_count()).map(|v| suite.readings_per_voxel(v)).collect();
        self.brain
            .parameter_count(&BrainShape::grid(body, &per_voxel))
            .map_err(|e| EvaluationError::Representation(e.to_string()))
    }
}

fn representation_error<E: std::fmt::Display>(field: &'static str) -> impl Fn(E) -> EvaluationError {
    move |e| EvaluationError::Representation(format!("{field}: {e}"))
}

/// A genotype → robot mapping (JGEA's "mapper"): flat vectors through [`Representation`]; graph
/// genomes or material grids through their own types.
pub trait Mapper<G>: Send + Sync {
    /// The robot a genotype stands for.
    fn robot(&self, genotype: &G) -> Result<Box<dyn Robot>, EvaluationError>;
    /// Names of statistics of a genotype worth logging (a graph's size, …); none by default.
    fn stats_columns(&self) -> &'static [&'static str] {
        &[]
    }
    /// The statistics named by [`Mapper::stats_columns`].
    fn stats(&self, _genotype: &G) -> Vec<f64> {
        Vec::new()
    }
}

impl Mapper<Vec<f64>> for Representation {
    fn robot(&self, genotype: &Vec<f64>) -> Result<Box<dyn Robot>, EvaluationError> {
        self.any_robot(genotype)
    }
}

/// An episode error's message ("robot.brain.x: …") as a representation error ("brain.x: …").
fn representation_message(e: EpisodeError) -> EvaluationError {
    let text = e.to_string();
    EvaluationError::Representation(text.strip_prefix("robot.").unwrap_or(&text).to_string())
}

/// Evaluates a genotype on a task: pure, thread-safe, summary outcome only (no trace). The one
/// genotype → outcome path of vsrlab: the experiment runner, replays and bindings call it.
pub fn evaluate<G, M: Mapper<G> + ?Sized>(
    mapper: &M,
    genotype: &G,
    task: &dyn Task,
    seed: u64,
) -> Result<Outcome, EvaluationError> {
    evaluate_traced(mapper, genotype, task, seed, TraceLevel::None).map(|(outcome, _)| outcome)
}

/// [`evaluate`] with a per-step trace at the given level (for analyses and videos); also
/// returns the robot the genotype became.
pub fn evaluate_traced<G, M: Mapper<G> + ?Sized>(
    mapper: &M,
    genotype: &G,
    task: &dyn Task,
    seed: u64,
    trace: TraceLevel,
) -> Result<(Outcome, Box<dyn Robot>), EvaluationError> {
    let robot = mapper.robot(genotype)?;
    let outcome = episode::run(robot.as_ref(), task, seed, trace)?;
    Ok((outcome, robot))
}
