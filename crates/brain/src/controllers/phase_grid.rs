//! Open-loop sinusoids with evolvable per-voxel phases (and optionally frequencies):
//! a_v(t) = clamp(A·sin(2π·f_v·t + φ_v), −1, 1).
//!
//! # Parameter layout
//!
//! One block per *unit*: a unit is a grid cell (layout `grid`: W·H units, index y·W + x, empty
//! cells included, so the count does not depend on which cells hold voxels) or a voxel (layout
//! `voxels`: one unit per voxel, voxel order). A block is `[p_φ]`, or `[p_φ, p_f]` when the
//! frequency is evolved too; the count is units × block size. The genes map to
//! - φ_v = π·p_φ (radians; genes in [−1, 1] cover the whole circle),
//! - f_v = f₀ + p_f (Hz), f₀ being the spec's `frequency` (f_v = f₀ when frequencies are fixed).
//!
//! Short forms: `phase-grid` (phases only) and `phase-grid:freq` (phases and frequencies).

use crate::short_form::ShortForm;
use crate::validation::{check_count, check_finite, finite, set_finite};
use crate::{BrainError, BrainKind, BrainShape, BrainSpec, Controller};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Which units the phase parameters belong to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PhaseLayout {
    /// One block per grid cell (W·H), empty cells included: usable with an evolved body.
    #[default]
    Grid,
    /// One block per voxel, in voxel order: no unused genes, fixed bodies only.
    Voxels,
}

/// Number of parameters: units × (1 + evolve_frequency).
pub fn parameter_count(shape: &BrainShape, layout: PhaseLayout, evolve_frequency: bool) -> usize {
    let units = match layout {
        PhaseLayout::Grid => shape.layout().slots(),
        PhaseLayout::Voxels => shape.units(),
    };
    units * (1 + usize::from(evolve_frequency))
}

/// Each voxel oscillates with its own phase and frequency (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseGridController {
    amplitude: f64,
    /// Per voxel (voxel order): frequency in Hz.
    frequencies: Vec<f64>,
    /// Per voxel (voxel order): phase in radians.
    phases: Vec<f64>,
}

impl PhaseGridController {
    /// Decodes the parameters (count [`parameter_count`], checked by the caller) for a body.
    ///
    /// # Panics
    /// If `parameters` is shorter than [`parameter_count`].
    pub fn new(
        shape: &BrainShape,
        amplitude: f64,
        frequency: f64,
        layout: PhaseLayout,
        evolve_frequency: bool,
        parameters: &[f64],
    ) -> Self {
        let block = 1 + usize::from(evolve_frequency);
        let (frequencies, phases) = (0..shape.units())
            .map(|v| {
                let unit = match layout {
                    PhaseLayout::Grid => shape.layout().slot(v),
                    PhaseLayout::Voxels => v,
                };
                let p = &parameters[unit * block..(unit + 1) * block];
                let f = if evolve_frequency { frequency + p[1] } else { frequency };
                (f, PI * p[0])
            })
            .unzip();
        PhaseGridController {
            amplitude,
            frequencies,
            phases,
        }
    }

    /// Per-voxel frequencies (Hz), voxel order.
    pub fn frequencies(&self) -> &[f64] {
        &self.frequencies
    }
    /// Per-voxel phases (radians), voxel order.
    pub fn phases(&self) -> &[f64] {
        &self.phases
    }
}

impl Controller for PhaseGridController {
    fn reset(&mut self) {}

    fn control(&mut self, t: f64, _readings: &[f64], actuations: &mut [f64]) {
        let w = 2.0 * PI * t;
        for ((a, f), phi) in actuations.iter_mut().zip(&self.frequencies).zip(&self.phases) {
            *a = (self.amplitude * (w * f + phi).sin()).clamp(-1.0, 1.0);
        }
    }
}

/// Description of a phase-grid brain (`{"kind": "phase-grid", …}`): a_v = clamp(A·sin(2π·f_v·t +
/// φ_v), −1, 1) with evolvable per-voxel phases and optionally frequencies (module documentation).
/// Every field has a default.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PhaseGridSpec {
    /// Base frequency f₀ (Hz); default 1.
    pub frequency: f64,
    /// Amplitude A; default 1.
    pub amplitude: f64,
    /// Whether each voxel also has a frequency parameter; default false.
    pub evolve_frequency: bool,
    /// One block per grid cell (`grid`, default) or per voxel (`voxels`).
    pub layout: PhaseLayout,
    /// The parameters: units × (1 + evolve_frequency) values; default none (a template).
    pub parameters: Vec<f64>,
}

impl Default for PhaseGridSpec {
    fn default() -> Self {
        PhaseGridSpec {
            frequency: 1.0,
            amplitude: 1.0,
            evolve_frequency: false,
            layout: PhaseLayout::Grid,
            parameters: Vec::new(),
        }
    }
}

impl BrainKind for PhaseGridSpec {
    fn name(&self) -> &'static str {
        "phase-grid"
    }

    fn parameter_count(&self, shape: &BrainShape) -> Result<usize, BrainError> {
        Ok(parameter_count(shape, self.layout, self.evolve_frequency))
    }

    fn parameters(&self) -> &[f64] {
        &self.parameters
    }

    fn set_parameters(&mut self, params: &[f64]) -> Result<(), BrainError> {
        set_finite("parameters", &mut self.parameters, params)
    }

    fn build(&self, shape: &BrainShape) -> Result<Box<dyn Controller>, BrainError> {
        finite("frequency", self.frequency)?;
        finite("amplitude", self.amplitude)?;
        let expected = parameter_count(shape, self.layout, self.evolve_frequency);
        check_count("parameters", expected, self.parameters.len())?;
        check_finite("parameters", &self.parameters)?;
        Ok(Box::new(PhaseGridController::new(
            shape,
            self.amplitude,
            self.frequency,
            self.layout,
            self.evolve_frequency,
            &self.parameters,
        )))
    }
}

/// `phase-grid` (per-cell phases) or `phase-grid:freq` (per-cell phases and frequencies).
pub const SHORT_FORM: ShortForm = ShortForm {
    name: "phase-grid",
    usage: "phase-grid[:freq]",
    parse: parse_short_form,
};

fn parse_short_form(argument: Option<&str>) -> Option<BrainSpec> {
    let evolve_frequency = match argument {
        None => false,
        Some("freq") => true,
        Some(_) => return None,
    };
    Some(BrainSpec::PhaseGrid(PhaseGridSpec {
        evolve_frequency,
        ..PhaseGridSpec::default()
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::{biped, build_error};
    use vsrlab_body::Morphology;

    #[test]
    fn counts_by_layout() {
        let m = Morphology::named("biped-4x3").unwrap();
        assert_eq!(
            parameter_count(&BrainShape::grid(&m, &[]), PhaseLayout::Grid, false),
            12
        );
        assert_eq!(parameter_count(&BrainShape::grid(&m, &[]), PhaseLayout::Grid, true), 24);
        assert_eq!(
            parameter_count(&BrainShape::grid(&m, &[]), PhaseLayout::Voxels, false),
            10
        );
        assert_eq!(
            parameter_count(&BrainShape::grid(&m, &[]), PhaseLayout::Voxels, true),
            20
        );
    }

    #[test]
    fn grid_blocks_follow_cells_and_voxel_blocks_follow_voxels() {
        // 2×2 with (1, 0) empty: voxels (0,0), (0,1), (1,1) = cells 0, 2, 3
        let m = Morphology::from_rows(&["##", "#."]).unwrap();
        let g = PhaseGridController::new(
            &BrainShape::grid(&m, &[]),
            1.0,
            2.0,
            PhaseLayout::Grid,
            true,
            &[0.0, 0.5, 9.0, 9.0, 0.5, -1.0, -0.5, 0.25],
        );
        assert_eq!(g.phases(), &[0.0, PI * 0.5, -PI * 0.5]);
        assert_eq!(g.frequencies(), &[2.5, 1.0, 2.25]);
        let v = PhaseGridController::new(
            &BrainShape::grid(&m, &[]),
            1.0,
            2.0,
            PhaseLayout::Voxels,
            false,
            &[0.0, 0.5, -0.5],
        );
        assert_eq!(v.phases(), &[0.0, PI * 0.5, -PI * 0.5]);
        assert_eq!(v.frequencies(), &[2.0; 3]);
    }

    #[test]
    fn actuation_is_a_clamped_sinusoid() {
        let m = Morphology::named("worm-2x1").unwrap();
        let mut c = PhaseGridController::new(
            &BrainShape::grid(&m, &[]),
            2.0,
            1.0,
            PhaseLayout::Voxels,
            false,
            &[0.0, 0.5],
        );
        let mut a = [0.0; 2];
        for k in 1..=120 {
            let t = k as f64 / 60.0;
            c.control(t, &[], &mut a);
            assert_eq!(a[0], (2.0 * (2.0 * PI * t).sin()).clamp(-1.0, 1.0));
            assert_eq!(a[1], (2.0 * (2.0 * PI * t + PI * 0.5).sin()).clamp(-1.0, 1.0));
        }
    }

    #[test]
    fn the_spec_counts_and_checks_its_parameters() {
        let (m, rpv) = biped();
        assert_eq!(
            BrainSpec::parse("phase-grid:freq")
                .unwrap()
                .parameter_count(&BrainShape::grid(&m, &rpv)),
            Ok(24)
        );
        let err = build_error(&BrainSpec::parse("phase-grid").unwrap(), &rpv);
        assert_eq!(
            err.to_string(),
            "brain.parameters: expected 12 for this body and sensors, got 0"
        );
    }
}
