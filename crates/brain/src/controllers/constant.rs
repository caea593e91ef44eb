//! A controller that applies the same actuation to every voxel, always. No parameters. Short form:
//! `constant:<value>`.

use crate::short_form::{self, ShortForm};
use crate::validation::finite;
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};

/// Constant actuation (calibration runs, passive bodies with value 0).
#[derive(Debug, Clone, PartialEq)]
pub struct ConstantController {
    /// Actuation applied to every voxel.
    pub value: f64,
}

impl Controller for ConstantController {
    fn reset(&mut self) {}
    fn control(&mut self, _t: f64, _readings: &[f64], actuations: &mut [f64]) {
        actuations.fill(self.value);
    }
}

/// Description of a constant brain (`{"kind": "constant", "value": 0.0}`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ConstantSpec {
    /// Actuation in [-1, 1] (positive contracts); required.
    pub value: f64,
}

impl BrainKind for ConstantSpec {
    fn name(&self) -> &'static str {
        "constant"
    }

    fn build(&self, _shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        finite("value", self.value)?;
        Ok(Box::new(ConstantController { value: self.value }))
    }
}

/// `constant:<value>`.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "constant",
    usage: "constant:<value>",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let value = short_form::number(argument?)?;
    Some(BrainSpec::Constant(ConstantSpec { value }))
}
