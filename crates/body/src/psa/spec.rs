//! [`PsaBody`]: a PSA as written in robot files and experiment files: a size, whose constants are
//! the defaults, and any constant overridden by name.
//!
//! ```toml
//! body = { kind = "psa", size = "small", pressure_control = false }
//! ```
//! Written back, every constant is listed, so a file stands alone.

use super::params::{PsaParams, PsaSize};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use vsrlab_field::FieldError;

/// A PSA body description: a size preset and the constants in force.
#[derive(Debug, Clone, PartialEq)]
pub struct PsaBody {
    /// The size the defaults come from.
    pub size: PsaSize,
    /// The constants (the size's, with any overrides).
    pub params: PsaParams,
}

impl PsaBody {
    /// A body of one size with the thesis's constants.
    pub fn of_size(size: PsaSize) -> PsaBody {
        PsaBody {
            size,
            params: PsaParams::of_size(size),
        }
    }
}

impl Default for PsaBody {
    fn default() -> Self {
        PsaBody::of_size(PsaSize::default())
    }
}

impl Serialize for PsaBody {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = match serde_json::to_value(&self.params) {
            Ok(serde_json::Value::Object(map)) => map,
            _ => return Err(serde::ser::Error::custom("PSA constants serialise to a table")),
        };
        map.insert("size".into(), self.size.name().into());
        map.serialize(serializer)
    }
}

impl<'de> Deserialize<'de> for PsaBody {
    /// [`PsaBody::from_table`], with its error as serde's.
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let value = serde_json::Value::deserialize(deserializer)?;
        PsaBody::from_table(value).map_err(serde::de::Error::custom)
    }
}

impl PsaBody {
    /// Reads `size` (default medium), fills every constant from it, then applies the other
    /// fields by name; an unknown or mistyped field is an error naming it. The constants are
    /// then checked ([`PsaParams::validate`]). The error's path is relative to the table.
    pub fn from_table(value: serde_json::Value) -> Result<PsaBody, FieldError> {
        let mut fields = match value {
            serde_json::Value::Object(fields) => fields,
            other => {
                return Err(FieldError::message(format!(
                    "expected a table of PSA constants, got {other}"
                )))
            }
        };
        fields.remove("kind");
        let size: PsaSize = match fields.remove("size") {
            Some(v) => serde_json::from_value(v).map_err(|e| FieldError::new("size", e.to_string()))?,
            None => PsaSize::default(),
        };
        let mut merged = match serde_json::to_value(PsaParams::of_size(size)) {
            Ok(serde_json::Value::Object(map)) => map,
            _ => return Err(FieldError::message("PSA constants serialise to a table")),
        };
        for (k, v) in fields {
            if !merged.contains_key(&k) {
                let known: Vec<&str> = merged.keys().map(String::as_str).collect();
                return Err(FieldError::message(format!(
                    "unknown field `{k}`, expected size or one of {}",
                    known.join(", ")
                )));
            }
            merged.insert(k, v);
        }
        let params: PsaParams = serde_path_to_error::deserialize(serde_json::Value::Object(merged))
            .map_err(|e| FieldError::new(e.path().to_string(), e.into_inner().to_string()))?;
        params.validate()?;
        Ok(PsaBody { size, params })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn size_gives_defaults_and_fields_override_them() {
        let b: PsaBody = serde_json::from_str(r#"{"size": "small", "pressure_control": false}"#).unwrap();
        assert_eq!(b.size, PsaSize::Small);
        assert_eq!(b.params.masses, 10);
        assert!(!b.params.pressure_control);
        let round: PsaBody = serde_json::from_str(&serde_json::to_string(&b).unwrap()).unwrap();
        assert_eq!(round, b);
        let default: PsaBody = serde_json::from_str("{}").unwrap();
        assert_eq!(default, PsaBody::of_size(PsaSize::Medium));
    }

    #[test]
    fn errors_name_the_field() {
        let err = |text: &str| serde_json::from_str::<PsaBody>(text).unwrap_err().to_string();
        assert!(
            err(r#"{"masses": 2}"#).starts_with("masses must be at least 3"),
            "{}",
            err(r#"{"masses": 2}"#)
        );
        assert!(err(r#"{"radius": -1}"#).starts_with("radius"));
        assert!(err(r#"{"gas_mass": -5}"#).starts_with("gas_mass"));
        assert!(err(r#"{"min_pressure_fraction": 2}"#).contains("p_min ≤ p_max"));
        assert!(
            err(r#"{"radius": "big"}"#).starts_with("radius: invalid type"),
            "{}",
            err(r#"{"radius": "big"}"#)
        );
        assert!(err(r#"{"radios": 3}"#).contains("unknown field `radios`"));
        assert!(err(r#"{"size": "huge"}"#).starts_with("size: unknown variant"));
        let path = |value: serde_json::Value| PsaBody::from_table(value).unwrap_err().path;
        assert_eq!(path(serde_json::json!({"masses": 2})), "masses");
        assert_eq!(path(serde_json::json!({"radius": "big"})), "radius");
        assert_eq!(path(serde_json::json!({"size": "huge"})), "size");
        assert_eq!(path(serde_json::json!({"radios": 3})), "");
    }
}
