//! [`FixedBody`]: the `[representation] body` form of a robot kind whose body is fixed by its
//! table (no body genes: the genotype is the brain's parameters) and whose sensors come with the
//! body. A kind implements these few methods and gets its [`BodySource`] (the PSA, EvoGym's
//! multi-material robot and the 3D voxel robot do).

use crate::body_part::BodySource;
use crate::kinds::{AnyRobot, RobotKind};
use crate::representation::{EvaluationError, Representation};
use serde::Serialize;
use std::fmt::Debug;
use vsrlab_brain::{BrainShape, BrainSpec};
use vsrlab_field::FieldError;

/// A body table that fixes the body; only the brain's parameters are genes.
pub trait FixedBody: Debug + Clone + PartialEq + Serialize + Send + Sync + 'static {
    /// The robot kind it makes.
    fn robot_kind(&self) -> &'static RobotKind;
    /// Why the representation's `sensors` field is refused (the kind's sensors come with it).
    fn sensors_refused(&self) -> &'static str;
    /// Parameters of `brain` on this body; paths are relative to the representation (`body…`
    /// for the body table's fields, `brain…` for the brain's).
    fn brain_parameters(&self, brain: &BrainSpec) -> Result<usize, FieldError>;
    /// The robot of this body with `brain` (its parameters filled).
    fn robot_of(&self, brain: BrainSpec) -> AnyRobot;
    /// Units of the body, for memory estimates.
    fn body_units(&self) -> usize;
    /// Bytes one episode holds beyond the usual simulation state ([`BodySource::episode_bytes`]).
    fn extra_episode_bytes(&self, _dt: f64) -> u128 {
        0
    }
}

/// Parameters of `brain` on `shape`, a robot's brain shape whose error paths are relative to the
/// robot: they are put under `body`, and the brain's under `brain`.
pub fn brain_parameters_on(shape: Result<BrainShape, FieldError>, brain: &BrainSpec) -> Result<usize, FieldError> {
    let shape = shape.map_err(|e| e.at("body"))?;
    brain
        .parameter_count(&shape)
        .map_err(|e| FieldError::from(e).at("brain"))
}

fn refuse_sensors(body: &impl FixedBody, representation: &Representation) -> Result<(), EvaluationError> {
    match representation.sensors {
        Some(_) => Err(EvaluationError::Representation(FieldError::new(
            "sensors",
            body.sensors_refused(),
        ))),
        None => Ok(()),
    }
}

impl<T: FixedBody> BodySource for T {
    fn kind(&self) -> &'static RobotKind {
        self.robot_kind()
    }

    fn genes(&self) -> usize {
        0
    }

    fn brain_genes(&self, representation: &Representation) -> Result<usize, EvaluationError> {
        refuse_sensors(self, representation)?;
        self.brain_parameters(&representation.brain)
            .map_err(EvaluationError::Representation)
    }

    fn robot(
        &self,
        representation: &Representation,
        _genes: &[f64],
        brain: BrainSpec,
    ) -> Result<AnyRobot, EvaluationError> {
        refuse_sensors(self, representation)?;
        Ok(self.robot_of(brain))
    }

    fn size(&self) -> usize {
        self.body_units()
    }

    fn episode_bytes(&self, dt: f64) -> u128 {
        self.extra_episode_bytes(dt)
    }
}
