//! [`Fitness`]: which of a task's metrics are its fitness values, as written in configs.
//!
//! `fitness = "velocity"` (one metric, maximised), or a list for several objectives:
//! `fitness = ["velocity", { metric = "voxels", sense = "minimize" }]`.

use crate::task::{Objective, Sense};
use serde::de::value::MapAccessDeserializer;
use serde::de::{self, MapAccess, SeqAccess, Visitor};
use serde::ser::SerializeSeq;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A task's objectives, in order (the first is the fitness single-objective optimizers use).
#[derive(Debug, Clone, PartialEq)]
pub struct Fitness(pub Vec<Objective>);

impl Fitness {
    /// One metric, maximised.
    pub fn maximize(metric: &str) -> Self {
        Fitness(vec![Objective::maximize(metric)])
    }
}

impl Serialize for Fitness {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.0.as_slice() {
            [one] if one.sense == Sense::Maximize => serializer.serialize_str(&one.metric),
            many => {
                let mut seq = serializer.serialize_seq(Some(many.len()))?;
                for o in many {
                    seq.serialize_element(o)?;
                }
                seq.end()
            }
        }
    }
}

impl<'de> Deserialize<'de> for Fitness {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(FitnessVisitor)
    }
}

struct FitnessVisitor;

impl<'de> Visitor<'de> for FitnessVisitor {
    type Value = Fitness;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a metric name or a list of objectives (names or {metric, sense} tables)")
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<Fitness, E> {
        Ok(Fitness::maximize(s))
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Fitness, A::Error> {
        let mut objectives = Vec::new();
        while let Some(ObjectiveForm(o)) = seq.next_element()? {
            objectives.push(o);
        }
        Ok(Fitness(objectives))
    }
}

/// One list element: a bare metric name (maximised) or a full table.
struct ObjectiveForm(Objective);

impl<'de> Deserialize<'de> for ObjectiveForm {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_any(ObjectiveVisitor)
    }
}

struct ObjectiveVisitor;

impl<'de> Visitor<'de> for ObjectiveVisitor {
    type Value = ObjectiveForm;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a metric name or a table {metric = \"…\", sense = \"maximize\" | \"minimize\"}")
    }

    fn visit_str<E: de::Error>(self, s: &str) -> Result<ObjectiveForm, E> {
        Ok(ObjectiveForm(Objective::maximize(s)))
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<ObjectiveForm, A::Error> {
        Objective::deserialize(MapAccessDeserializer::new(map)).map(ObjectiveForm)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_name_or_a_list_round_trips() {
        let one: Fitness = serde_json::from_str(r#""velocity""#).unwrap();
        assert_eq!(one, Fitness::maximize("velocity"));
        assert_eq!(serde_json::to_string(&one).unwrap(), r#""velocity""#);
        let two: Fitness = serde_json::from_str(r#"["velocity", {"metric": "voxels", "sense": "minimize"}]"#).unwrap();
        assert_eq!(two.0.len(), 2);
        assert_eq!(two.0[1].sense, Sense::Minimize);
        let back: Fitness = serde_json::from_str(&serde_json::to_string(&two).unwrap()).unwrap();
        assert_eq!(back, two);
        assert!(serde_json::from_str::<Fitness>(r#"[{"metric": "voxels", "sens": "minimize"}]"#).is_err());
        assert!(serde_json::from_str::<Fitness>("3").is_err());
    }
}
