//! Lossless (de)serialisation of `f64` values that may be non-finite.
//!
//! Why: fitness values of robots can be NaN or infinite (an exploding simulation), and JSON has
//! no literal for them (`serde_json` writes `null` and then fails to read it back), which would
//! make a checkpoint unreadable. In human-readable formats finite values are written as numbers
//! and non-finite ones as the strings `"NaN"`, `"inf"` and `"-inf"`; binary formats get the raw
//! `f64`.

use serde::de::{self, Deserializer, Visitor};
use serde::ser::{SerializeSeq, Serializer};
use serde::{Deserialize, Serialize};
use std::fmt;

/// An `f64` with the lossless representation described in the module docs.
#[derive(Debug, Clone, Copy)]
pub struct Lossless(pub f64);

impl Serialize for Lossless {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let v = self.0;
        if !serializer.is_human_readable() || v.is_finite() {
            serializer.serialize_f64(v)
        } else if v.is_nan() {
            serializer.serialize_str("NaN")
        } else if v > 0.0 {
            serializer.serialize_str("inf")
        } else {
            serializer.serialize_str("-inf")
        }
    }
}

struct LosslessVisitor;

impl Visitor<'_> for LosslessVisitor {
    type Value = Lossless;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number or one of \"NaN\", \"inf\", \"-inf\"")
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Lossless, E> {
        Ok(Lossless(v))
    }

    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Lossless, E> {
        Ok(Lossless(v as f64))
    }

    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Lossless, E> {
        Ok(Lossless(v as f64))
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<Lossless, E> {
        match v {
            "NaN" => Ok(Lossless(f64::NAN)),
            "inf" => Ok(Lossless(f64::INFINITY)),
            "-inf" => Ok(Lossless(f64::NEG_INFINITY)),
            other => Err(E::invalid_value(de::Unexpected::Str(other), &self)),
        }
    }
}

impl<'de> Deserialize<'de> for Lossless {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        if deserializer.is_human_readable() {
            deserializer.deserialize_any(LosslessVisitor)
        } else {
            deserializer.deserialize_f64(LosslessVisitor)
        }
    }
}

/// `#[serde(with = "vsrlab_evolution::serde_float::vec")]` for `Vec<f64>` fields.
pub mod vec {
    use super::*;

    /// Writes the values, non-finite ones as strings in human-readable formats.
    pub fn serialize<S: Serializer>(values: &[f64], serializer: S) -> Result<S::Ok, S::Error> {
        let mut seq = serializer.serialize_seq(Some(values.len()))?;
        for &v in values {
            seq.serialize_element(&Lossless(v))?;
        }
        seq.end()
    }

    /// Reads what [`serialize`] wrote.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<f64>, D::Error> {
        let values: Vec<Lossless> = Vec::deserialize(deserializer)?;
        Ok(values.into_iter().map(|v| v.0).collect())
    }
}

#[cfg(test)]
mod tests {
    use serde::{Deserialize, Serialize};

    #[derive(Serialize, Deserialize)]
    struct Holder {
        #[serde(with = "super::vec")]
        values: Vec<f64>,
    }

    #[test]
    fn non_finite_values_survive_json() {
        let h = Holder {
            values: vec![1.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, -0.1, 3.0],
        };
        let text = serde_json::to_string(&h).unwrap();
        let back: Holder = serde_json::from_str(&text).unwrap();
        for (a, b) in h.values.iter().zip(&back.values) {
            assert!(a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()), "{a} vs {b}");
        }
    }
}
