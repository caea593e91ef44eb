//! What a PSA senses (thesis §6.2.2, psa-model.md "Sensors"): 3n+3 values per step, averaged
//! over the last `sensor_window` seconds.
//!
//! Order (one block of three per mass, then one for the whole body, so that a brain that sees the
//! agent as n+1 units gives each unit its own readings):
//! for each mass i: touch (0 or 1), (x_i − x_c)/8.75, (y_i − y_c)/8.75; then
//! (x_c − x_c')/8, (y_c − y_c')/8 (the centre's displacement since the previous step) and p/p_max.
//! The original code lists all touch flags first; with a dense controller the order only
//! permutes weights.

use super::membrane::Psa;
use crate::body::Body;
use vsrlab_field::FieldError;
use vsrlab_physics::{Vec2, World};

/// The PSA's sensors and their moving-average window. Allocates only when built.
#[derive(Debug, Clone)]
pub struct PsaSensors {
    window: usize,
    /// The last `window` raw samples, a ring buffer of `window × readings` values.
    samples: Vec<f64>,
    sums: Vec<f64>,
    filled: usize,
    next: usize,
    previous_centre: Option<Vec2>,
    readings: usize,
}

/// Most readings the averaging window may hold (steps × readings): 2 × 10⁷ values, 160 MB.
pub const MAX_WINDOW_VALUES: f64 = 2e7;

impl PsaSensors {
    /// Sensors for `psa`, averaging over `round(sensor_window / dt)` steps (at least one); an
    /// error names `sensor_window` when that window would hold more than [`MAX_WINDOW_VALUES`]
    /// readings (a window of 1e300 s, or a time step of 1e-300 s).
    pub fn new(psa: &Psa, dt: f64) -> Result<PsaSensors, FieldError> {
        let readings = psa.params().reading_count();
        let steps = (psa.params().sensor_window / dt).round();
        let values = steps * readings as f64;
        if values.is_nan() || values > MAX_WINDOW_VALUES {
            return Err(FieldError::sentence(
                "sensor_window",
                format!(
                    "{} s is {steps:e} steps of {dt:e} s, {readings} readings each: the window may hold at most {MAX_WINDOW_VALUES:e} readings",
                    psa.params().sensor_window
                ),
            ));
        }
        let window = (steps as usize).max(1);
        Ok(PsaSensors {
            window,
            samples: vec![0.0; window * readings],
            sums: vec![0.0; readings],
            filled: 0,
            next: 0,
            previous_centre: None,
            readings,
        })
    }

    /// Number of readings (3n+3).
    pub fn reading_count(&self) -> usize {
        self.readings
    }
    /// Number of samples averaged.
    pub fn window(&self) -> usize {
        self.window
    }

    /// Takes this step's sample and writes the average of the last `window` samples to `out`.
    pub fn sense(&mut self, psa: &Psa, world: &World, out: &mut [f64]) {
        let params = psa.params();
        let centre = psa.center(world);
        let previous = self.previous_centre.replace(centre).unwrap_or(centre);
        let slot = self.next * self.readings;
        let sample = &mut self.samples[slot..slot + self.readings];
        // old sample leaves the sums, the new one enters
        for (s, x) in self.sums.iter_mut().zip(sample.iter()) {
            *s -= x;
        }
        for (i, &m) in psa.masses().iter().enumerate() {
            let p = world.part_position(m) - centre;
            sample[3 * i] = f64::from(u8::from(world.part_touching(m)));
            sample[3 * i + 1] = p.x / params.position_scale;
            sample[3 * i + 2] = p.y / params.position_scale;
        }
        let n = psa.mass_count();
        let d = centre - previous;
        sample[3 * n] = d.x / params.displacement_scale;
        sample[3 * n + 1] = d.y / params.displacement_scale;
        sample[3 * n + 2] = psa.pressure(world) / psa.max_pressure();
        for (s, x) in self.sums.iter_mut().zip(sample.iter()) {
            *s += x;
        }
        self.next = (self.next + 1) % self.window;
        self.filled = (self.filled + 1).min(self.window);
        let k = self.filled as f64;
        if self.next == 0 {
            // recompute the sums exactly once per window so rounding does not drift
            self.sums.iter_mut().for_each(|s| *s = 0.0);
            for w in self.samples.chunks_exact(self.readings) {
                for (s, x) in self.sums.iter_mut().zip(w) {
                    *s += x;
                }
            }
        }
        for (o, s) in out.iter_mut().zip(&self.sums) {
            *o = s / k;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::psa::params::{PsaParams, PsaSize};
    use vsrlab_physics::{WorldBuilder, WorldSettings};

    #[test]
    fn readings_are_normalised_and_averaged_over_the_window() {
        let params = PsaParams::of_size(PsaSize::Small);
        let mut b = WorldBuilder::new(WorldSettings {
            gravity: Vec2::ZERO,
            ..WorldSettings::default()
        });
        let psa = Psa::assemble(&mut b, &params, Vec2::new(3.0, 4.0), 1);
        let mut w = b.build().unwrap();
        let mut s = PsaSensors::new(&psa, 1.0 / 60.0).unwrap();
        assert_eq!((s.window(), s.reading_count()), (15, 33));
        let mut out = vec![0.0; 33];
        s.sense(&psa, &w, &mut out);
        // mass 0 sits at angle 0, radius 5: x = 5/8.75, y = 0; nothing touches; no motion yet
        assert_eq!(out[0], 0.0);
        assert!((out[1] - 5.0 / 8.75).abs() < 1e-12);
        assert!(out[2].abs() < 1e-12);
        assert_eq!((out[30], out[31]), (0.0, 0.0));
        let p0 = psa.pressure(&w) / psa.max_pressure();
        assert!((out[32] - p0).abs() < 1e-12);
        // a constant pressure change: the average lags behind the reading and catches up after
        // the window
        let values = vec![0.0; 11];
        psa.set_pressure(&mut w, psa.max_pressure() * 0.5, true);
        psa.actuate(&mut w, &values);
        for k in 1..=15 {
            s.sense(&psa, &w, &mut out);
            let expected = (p0 + k as f64 * 0.5) / (k + 1).min(15) as f64;
            let expected = if k + 1 > 15 { 0.5 } else { expected };
            assert!(
                (out[32] - expected).abs() < 1e-12,
                "step {k}: {} vs {expected}",
                out[32]
            );
        }
        for _ in 0..40 {
            s.sense(&psa, &w, &mut out);
        }
        assert!((out[32] - 0.5).abs() < 1e-12);
    }
}
