//! From a flat genotype to a robot (thesis §3.3.5): a representation is a body part and a brain
//! part over one vector `v = [v_body v_brain]`, plus the sensors and the physical preset.
//!
//! - The body part ([`BodyPart`]) belongs to a robot kind, which reads its forms: for voxel
//!   robots a fixed [`vsrlab_body::Morphology`] (no genes) or a body encoding (Direct: W·H genes,
//!   GMM: 5 genes per Gaussian); for a PSA its size and constants (no genes).
//! - The brain part is a [`BrainSpec`] *template*: its kind and shape; its parameters come from
//!   the genotype. With an evolved body the brain's parameter count must not depend on which cells
//!   the decoded body occupies (distributed MLPs, homogeneous or one block per grid cell); a brain
//!   whose count does (a centralised MLP) needs a fixed body, and is rejected otherwise.
//!
//! [`evaluate`] is the pure function (mapper, genotype, task, seed) → outcome that the optimizers
//! call, from as many threads as they like; [`Mapper`] makes it generic over the genotype.

use crate::agent::Robot;
pub use crate::body_part::{BodyPart, BodySource};
use crate::episode::{self, EpisodeError};
use crate::kinds::voxel::robot::RobotSpec;
use crate::outcome::{Outcome, TraceLevel};
use crate::task::Task;
use serde::{Deserialize, Serialize};
use vsrlab_body::sensors::SensorConfig;
use vsrlab_body::Preset;
use vsrlab_brain::BrainSpec;
use vsrlab_field::FieldError;

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
    /// The representation itself is unusable; the error's path is relative to the
    /// representation (`body.masses`; see [`EvaluationError::field_error`]).
    #[error("representation.{0}")]
    Representation(FieldError),
    /// The genotype does not fit the representation; the error's path is the part of the
    /// genotype at fault (`body`, `brain`), empty for the genotype as a whole.
    #[error("genotype: {0}")]
    Genotype(FieldError),
    /// The episode could not be run or blew up.
    #[error(transparent)]
    Episode(#[from] EpisodeError),
}

impl EvaluationError {
    /// A representation error as an error on its field of an experiment file
    /// (`representation.body.masses`, or `representation` alone for the whole table); `None` for
    /// errors of a genotype or an episode.
    pub fn field_error(&self) -> Option<FieldError> {
        match self {
            EvaluationError::Representation(e) => Some(e.clone().at("representation")),
            _ => None,
        }
    }
}

impl Representation {
    /// Number of body genes (0 for a fixed body).
    pub fn body_genes(&self) -> usize {
        self.body.genes()
    }

    /// The voxel sensors; an error for a voxel body without them.
    pub fn sensors(&self) -> Result<&SensorConfig, EvaluationError> {
        self.sensors.as_ref().ok_or_else(|| {
            EvaluationError::Representation(FieldError::new(
                "sensors",
                "missing: voxel bodies need a sensor placement",
            ))
        })
    }

    /// Number of brain genes (the body's kind counts them; with an encoded voxel body they must
    /// not depend on which cells the body occupies).
    pub fn brain_genes(&self) -> Result<usize, EvaluationError> {
        self.body.brain_genes(self)
    }

    /// Total genotype length: body genes then brain genes.
    pub fn genotype_length(&self) -> Result<usize, EvaluationError> {
        self.body_genes()
            .checked_add(self.brain_genes()?)
            .ok_or_else(|| EvaluationError::Representation(FieldError::message("too many genes to count")))
    }

    /// Checks that the representation is usable (body encoding, sensors and brain fit together).
    pub fn validate(&self) -> Result<(), EvaluationError> {
        self.genotype_length().map(|_| ())
    }

    /// Builds the robot a genotype stands for, of any body kind.
    pub fn any_robot(&self, genotype: &[f64]) -> Result<crate::AnyRobot, EvaluationError> {
        let expected = self.genotype_length()?;
        if genotype.len() != expected {
            return Err(EvaluationError::Genotype(FieldError::message(format!(
                "expected {expected} genes ({} body + {} brain), got {}",
                self.body_genes(),
                expected - self.body_genes(),
                genotype.len()
            ))));
        }
        let (body_genes, brain_genes) = genotype.split_at(self.body_genes());
        let brain = self
            .brain
            .with_parameters(brain_genes)
            .map_err(|e| EvaluationError::Genotype(FieldError::new("brain", e.to_string())))?;
        self.body.robot(self, body_genes, brain)
    }

    /// Builds the voxel robot a genotype stands for (an error for a robot of another kind).
    pub fn robot(&self, genotype: &[f64]) -> Result<RobotSpec, EvaluationError> {
        let robot = self.any_robot(genotype)?;
        robot.downcast_ref::<RobotSpec>().cloned().ok_or_else(|| {
            EvaluationError::Representation(FieldError::new(
                "body",
                format!(
                    "a {} robot is not a voxel robot (this analysis reads voxel robots only)",
                    robot.kind().name
                ),
            ))
        })
    }
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
        self.any_robot(genotype).map(crate::AnyRobot::into_robot)
    }
}

/// Genotypes in the form snapshots and checkpoints store them (JSON) → robots: how analyses
/// replay the individuals of any genotype kind without knowing its type.
pub trait StoredGenotypes: Send + Sync {
    /// The robot a stored genotype stands for (an error when it is not of this kind).
    fn robot(&self, genotype: &serde_json::Value) -> Result<Box<dyn Robot>, EvaluationError>;
}

/// A [`Mapper`] of a serde genotype type read as [`StoredGenotypes`].
pub struct Stored<G, M> {
    mapper: M,
    genotype: std::marker::PhantomData<fn() -> G>,
}

impl<G, M> Stored<G, M> {
    /// Reads stored genotypes of type `G` and maps them with `mapper`.
    pub fn new(mapper: M) -> Self {
        Stored {
            mapper,
            genotype: std::marker::PhantomData,
        }
    }
}

impl<G: serde::de::DeserializeOwned, M: Mapper<G>> StoredGenotypes for Stored<G, M> {
    fn robot(&self, genotype: &serde_json::Value) -> Result<Box<dyn Robot>, EvaluationError> {
        let genotype = G::deserialize(genotype).map_err(|e| {
            EvaluationError::Genotype(FieldError::message(format!("not a genotype of this experiment: {e}")))
        })?;
        self.mapper.robot(&genotype)
    }
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
