//! [`BodyPart`]: the body part of a representation, of any robot kind. Each kind reads its own
//! `[representation] body` forms ([`crate::RobotKind::decode_body`]) into a [`BodySource`]: how
//! the first genes (if any) become a body, and a body and a brain become a robot.

use crate::kinds::{self, AnyRobot, RobotKind};
use crate::representation::{EvaluationError, Representation};
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::any::Any;
use std::fmt::Debug;
use vsrlab_body::Morphology;
use vsrlab_brain::BrainSpec;

/// A robot kind's body in a representation. The type-erased plumbing ([`BodyFormCopy`]) comes
/// with any `Clone + PartialEq + Serialize` type.
pub trait BodySource: Debug + Send + Sync + BodyFormCopy {
    /// The robot kind it makes.
    fn kind(&self) -> &'static RobotKind;
    /// Number of body genes (0 for a fixed body).
    fn genes(&self) -> usize;
    /// Number of brain genes of the representation's brain template on this body (errors name
    /// the field: `sensors: …`, `brain: …`).
    fn brain_genes(&self, representation: &Representation) -> Result<usize, EvaluationError>;
    /// The robot of these body genes and this brain (its parameters filled).
    fn robot(
        &self,
        representation: &Representation,
        genes: &[f64],
        brain: BrainSpec,
    ) -> Result<AnyRobot, EvaluationError>;
    /// Units of the largest body it makes (for memory estimates): grid cells, a PSA's masses.
    fn size(&self) -> usize;
    /// Bytes one episode holds beyond the usual simulation state, for buffers whose size follows
    /// from the settings (a PSA's sensor window at time step `dt`); for memory estimates.
    fn episode_bytes(&self, _dt: f64) -> u128 {
        0
    }
    /// The body's fixed voxel grid, when it is one (graph genotypes, analyses of voxel robots).
    fn fixed_grid(&self) -> Option<&Morphology> {
        None
    }
}

/// What a boxed [`BodySource`] needs to be copied, compared and written; implemented for every
/// `Clone + PartialEq + Serialize` body form.
pub trait BodyFormCopy {
    /// The experiment-file form, for writing resolved experiment files.
    fn as_serialize(&self) -> &dyn erased_serde::Serialize;
    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn BodySource>;
    /// The body source itself, for comparisons within its kind.
    fn as_any(&self) -> &dyn Any;
    /// Whether `other` is the same body.
    fn same_as(&self, other: &dyn BodySource) -> bool;
}

impl<T: BodySource + Clone + PartialEq + Serialize + 'static> BodyFormCopy for T {
    fn as_serialize(&self) -> &dyn erased_serde::Serialize {
        self
    }
    fn clone_box(&self) -> Box<dyn BodySource> {
        Box::new(self.clone())
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn same_as(&self, other: &dyn BodySource) -> bool {
        other.as_any().downcast_ref::<T>() == Some(self)
    }
}

/// Where the body comes from, for any robot kind: in experiment files a shape name, a text grid
/// or a list of rows (a fixed voxel body), or a table whose `kind` names a body form of a robot
/// kind (`direct`, `gmm`: encoded voxel bodies; `psa`: a pressure-based soft agent).
#[derive(Debug)]
pub struct BodyPart(Box<dyn BodySource>);

impl BodyPart {
    /// Wraps a kind's body source.
    pub fn new(source: impl BodySource + 'static) -> BodyPart {
        BodyPart(Box::new(source))
    }

    /// The body source.
    pub fn source(&self) -> &dyn BodySource {
        self.0.as_ref()
    }
}

impl std::ops::Deref for BodyPart {
    type Target = dyn BodySource;
    fn deref(&self) -> &Self::Target {
        self.0.as_ref()
    }
}

impl Clone for BodyPart {
    fn clone(&self) -> Self {
        BodyPart(self.0.clone_box())
    }
}

impl PartialEq for BodyPart {
    fn eq(&self, other: &Self) -> bool {
        self.0.same_as(other.0.as_ref())
    }
}

impl Serialize for BodyPart {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        erased_serde::serialize(self.0.as_serialize(), serializer)
    }
}

impl<'de> Deserialize<'de> for BodyPart {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(BodyPartVisitor)
    }
}

/// Reads any body form into a JSON value and hands it to the kind it belongs to: a table to the
/// kind that lists its `kind` tag, anything else (names, grids, rows) to the default kind.
struct BodyPartVisitor;

impl BodyPartVisitor {
    fn decode<E: de::Error>(value: serde_json::Value) -> Result<BodyPart, E> {
        let tag = value.get("kind").and_then(serde_json::Value::as_str);
        let kind = tag
            .and_then(|t| kinds::ROBOT_KINDS.iter().find(|k| k.body_tables.contains(&t)))
            .unwrap_or_else(kinds::default_kind);
        (kind.decode_body)(value).map_err(E::custom)
    }
}

impl<'de> Visitor<'de> for BodyPartVisitor {
    type Value = BodyPart;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str(
            "a shape name, a text grid, a list of rows, or a body table {kind = \"direct\" | \"gmm\" | \"psa\", …}",
        )
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<BodyPart, E> {
        Self::decode(serde_json::Value::String(s.to_string()))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<BodyPart, A::Error> {
        Self::decode(serde_json::Value::deserialize(SeqAccessDeserializer::new(seq))?)
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<BodyPart, A::Error> {
        Self::decode(serde_json::Value::deserialize(MapAccessDeserializer::new(map))?)
    }
}
