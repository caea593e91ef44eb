//! Open-loop phase controller (vsr-model.md §4.5): a(x, y, t) = A·sin(2πft + φ(x, y)), with
//! φ = phase_x·π·x/W + phase_y·π·y/H. No parameters. Short form: `phase`.

use crate::layout::UnitLayout;
use crate::short_form::ShortForm;
use crate::validation::finite;
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};

/// Each voxel oscillates with a common frequency and amplitude and its own phase.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseController {
    /// Frequency (Hz).
    pub frequency: f64,
    /// Amplitude.
    pub amplitude: f64,
    /// One phase per voxel, grid order (radians).
    pub phases: Vec<f64>,
}

impl PhaseController {
    /// φ = phase_x·π·x/W + phase_y·π·y/H for each unit, (x, y) its cell in the layout and W×H
    /// the layout's extent.
    pub fn for_layout(layout: &dyn UnitLayout, frequency: f64, amplitude: f64, phase_x: f64, phase_y: f64) -> Self {
        let [w, h, _] = layout.extent().map(|n| n as f64);
        let phases = (0..layout.units())
            .map(|u| {
                let [x, y, _] = layout.cell(u).map(|c| c as f64);
                std::f64::consts::PI * (phase_x * x / w + phase_y * y / h)
            })
            .collect();
        PhaseController {
            frequency,
            amplitude,
            phases,
        }
    }
}

impl Controller for PhaseController {
    fn reset(&mut self) {}

    fn control(&mut self, t: f64, _readings: &[f64], actuations: &mut [f64]) {
        let w = 2.0 * std::f64::consts::PI * self.frequency * t;
        for (a, phi) in actuations.iter_mut().zip(&self.phases) {
            *a = self.amplitude * (w + phi).sin();
        }
    }
}

/// Description of a phase brain (`{"kind": "phase", …}`); every field has a default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhaseSpec {
    /// Frequency f (Hz); default 1.
    pub frequency: f64,
    /// Amplitude A; default 1.
    pub amplitude: f64,
    /// Phase shift across the width, in units of π; default 1.
    pub phase_x: f64,
    /// Phase shift across the height, in units of π; default 0.
    pub phase_y: f64,
}

impl Default for PhaseSpec {
    fn default() -> Self {
        PhaseSpec {
            frequency: 1.0,
            amplitude: 1.0,
            phase_x: 1.0,
            phase_y: 0.0,
        }
    }
}

impl BrainKind for PhaseSpec {
    fn name(&self) -> &'static str {
        "phase"
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        let PhaseSpec {
            frequency,
            amplitude,
            phase_x,
            phase_y,
        } = *self;
        for (field, v) in [
            ("frequency", frequency),
            ("amplitude", amplitude),
            ("phase_x", phase_x),
            ("phase_y", phase_y),
        ] {
            finite(field, v)?;
        }
        Ok(Box::new(PhaseController::for_layout(
            shape.layout(),
            frequency,
            amplitude,
            phase_x,
            phase_y,
        )))
    }
}

/// `phase`: the defaults.
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "phase",
    usage: "phase",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    match argument {
        None => Some(BrainSpec::Phase(PhaseSpec::default())),
        Some(_) => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_follow_grid_x() {
        let m = vsrlab_body::Morphology::named("worm-4x1").unwrap();
        let mut c = PhaseController::for_layout(&crate::GridLayout::new(&m), 1.0, 1.0, 1.0, 0.0);
        let mut out = vec![0.0; 4];
        c.control(0.0, &[], &mut out);
        let expected: Vec<f64> = (0..4).map(|x| (std::f64::consts::PI * x as f64 / 4.0).sin()).collect();
        assert_eq!(out, expected);
        c.control(0.25, &[], &mut out);
        assert!((out[0] - 1.0).abs() < 1e-12);
    }
}
