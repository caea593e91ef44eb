//! Open-loop phase controller (vsr-model.md §4.5): a(x, y, t) = A·sin(2πft + φ(x, y)).

use crate::Controller;
use vsrlab_body::Morphology;

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
    /// φ = phase_x·π·x/W + phase_y·π·y/H for each voxel of the morphology.
    pub fn for_morphology(m: &Morphology, frequency: f64, amplitude: f64, phase_x: f64, phase_y: f64) -> Self {
        let (w, h) = (m.width() as f64, m.height() as f64);
        let phases = m
            .voxels()
            .map(|(x, y)| std::f64::consts::PI * (phase_x * x as f64 / w + phase_y * y as f64 / h))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn phases_follow_grid_x() {
        let m = Morphology::named("worm-4x1").unwrap();
        let mut c = PhaseController::for_morphology(&m, 1.0, 1.0, 1.0, 0.0);
        let mut out = vec![0.0; 4];
        c.control(0.0, &[], &mut out);
        let expected: Vec<f64> = (0..4).map(|x| (std::f64::consts::PI * x as f64 / 4.0).sin()).collect();
        assert_eq!(out, expected);
        c.control(0.25, &[], &mut out);
        assert!((out[0] - 1.0).abs() < 1e-12);
    }
}
