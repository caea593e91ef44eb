//! The voxel robot's `[representation] body` forms: a fixed body (a shape name, a text grid or a
//! list of rows; no genes) or a body encoding (`{ kind = "direct" | "gmm", … }`: the first genes).

use super::robot::RobotSpec;
use crate::body_part::{BodyPart, BodySource};
use crate::kinds::{AnyRobot, RobotKind};
use crate::representation::{EvaluationError, Representation};
use serde::{Deserialize, Serialize};
use vsrlab_body::encodings::BodyEncoding;
use vsrlab_body::sensors::SensorSuite;
use vsrlab_body::Morphology;
use vsrlab_brain::{BrainShape, BrainSpec};
use vsrlab_field::FieldError;

/// Where a voxel robot's body comes from.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum VoxelBody {
    /// The same body for every genotype (no body genes).
    Fixed(Morphology),
    /// A body decoded from the first genes of the genotype.
    Encoded(BodyEncoding),
}

/// Reads a voxel body form: a table is a body encoding, anything else a fixed body. The error
/// is about the form as a whole.
pub(crate) fn decode(value: serde_json::Value) -> Result<BodyPart, FieldError> {
    let invalid = |e: &dyn std::fmt::Display| FieldError::message(e.to_string());
    let body = match value {
        serde_json::Value::String(s) => VoxelBody::Fixed(Morphology::parse(&s).map_err(|e| invalid(&e))?),
        serde_json::Value::Object(_) => VoxelBody::Encoded(BodyEncoding::deserialize(value).map_err(|e| invalid(&e))?),
        other => VoxelBody::Fixed(Morphology::deserialize(other).map_err(|e| invalid(&e))?),
    };
    Ok(BodyPart::new(body))
}

/// An error of a part of the representation, as a representation error on `field`.
fn representation_error<E: std::fmt::Display>(field: &'static str) -> impl Fn(E) -> EvaluationError {
    move |e| EvaluationError::Representation(FieldError::new(field, e.to_string()))
}

/// Brain parameters for the representation's sensors and brain on `body`.
fn brain_parameters_for(representation: &Representation, body: &Morphology) -> Result<usize, EvaluationError> {
    let suite = SensorSuite::new(representation.sensors()?, body, 0).map_err(representation_error("sensors"))?;
    let per_voxel: Vec<usize> = (0..body.voxel_count()).map(|v| suite.readings_per_voxel(v)).collect();
    representation
        .brain
        .parameter_count(&BrainShape::grid(body, &per_voxel))
        .map_err(|e| EvaluationError::Representation(e.into()))
}

impl BodySource for VoxelBody {
    fn kind(&self) -> &'static RobotKind {
        &super::KIND
    }

    fn genes(&self) -> usize {
        match self {
            VoxelBody::Fixed(_) => 0,
            VoxelBody::Encoded(encoding) => encoding.gene_count(),
        }
    }

    /// With an encoded body the count is taken on the full W×H grid and must be the same for a
    /// single-voxel body, otherwise the brain cannot follow an evolving body.
    fn brain_genes(&self, representation: &Representation) -> Result<usize, EvaluationError> {
        match self {
            VoxelBody::Fixed(body) => brain_parameters_for(representation, body),
            VoxelBody::Encoded(encoding) => {
                encoding.validate().map_err(representation_error("body"))?;
                let (w, h) = (encoding.width(), encoding.height());
                let full = Morphology::from_fn(w, h, |_, _| true).map_err(representation_error("body"))?;
                let single =
                    Morphology::from_fn(w, h, |x, y| x == 0 && y == 0).map_err(representation_error("body"))?;
                let count = brain_parameters_for(representation, &full)?;
                if brain_parameters_for(representation, &single)? != count {
                    return Err(EvaluationError::Representation(FieldError::new(
                        "brain",
                        "its parameter count depends on the body's voxels, so it cannot be used with an evolved \
                         body; use a fixed body or a distributed brain",
                    )));
                }
                Ok(count)
            }
        }
    }

    fn robot(
        &self,
        representation: &Representation,
        genes: &[f64],
        brain: BrainSpec,
    ) -> Result<AnyRobot, EvaluationError> {
        let body = match self {
            VoxelBody::Fixed(body) => body.clone(),
            VoxelBody::Encoded(encoding) => encoding
                .decode(genes)
                .map_err(|e| EvaluationError::Genotype(FieldError::new("body", e.to_string())))?,
        };
        Ok(AnyRobot::new(RobotSpec {
            body,
            preset: representation.preset,
            voxel: None,
            sensors: representation.sensors()?.clone(),
            brain,
        }))
    }

    fn size(&self) -> usize {
        match self {
            VoxelBody::Encoded(e) => e.width() * e.height(),
            VoxelBody::Fixed(m) => m.width() * m.height(),
        }
    }

    fn fixed_grid(&self) -> Option<&Morphology> {
        match self {
            VoxelBody::Fixed(m) => Some(m),
            VoxelBody::Encoded(_) => None,
        }
    }
}
