//! Centre-of-mass spectra (thesis §3.3.3.2 "centre movement"; thesis-code-facts §3.5).
//!
//! 1. First differences of one coordinate of the robot's centre, step by step.
//! 2. Zero-padded to the next power of two N, real FFT, magnitudes of bins 0..=N/2.
//! 3. Frequency of FFT bin i: i/(N·Δt) (exact); 2D-VSR-Sim used (1/Δt)/2 · i/(N/2 + 1), available
//!    as [`FrequencyConvention::Original`].
//! 4. Resampled to `bins` values over (0, f_max]: output bin j covers (j·f_max/bins,
//!    (j+1)·f_max/bins] and holds the mean magnitude of the FFT bins falling in it (0 if none).
//!
//! The thesis text takes the differences as they are; 2D-VSR-Sim took their absolute values
//! (|Δy|), which folds an oscillation at f onto 2f and a DC term: [`SpectrumParams::absolute`].

use realfft::RealFftPlanner;
use serde::{Deserialize, Serialize};
use vsrlab_physics::Vec2;

/// How FFT bin indices map to frequencies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum FrequencyConvention {
    /// f_i = i / (N Δt).
    #[default]
    Exact,
    /// f_i = (1/Δt)/2 · i/(N/2 + 1), as 2D-VSR-Sim's `Outcome` (slightly below the exact value).
    Original,
}

/// Which coordinate of the centre.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Axis {
    /// Horizontal.
    X,
    /// Vertical.
    Y,
}

/// Spectrum settings; the defaults are the thesis' (f_max = 10 Hz, n_freq = 100).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SpectrumParams {
    /// Highest frequency kept (Hz).
    pub max_frequency: f64,
    /// Number of output bins.
    pub bins: usize,
    /// Take |Δ| instead of Δ (2D-VSR-Sim); false follows the thesis text.
    pub absolute: bool,
    /// Bin-frequency convention.
    pub convention: FrequencyConvention,
}

impl Default for SpectrumParams {
    fn default() -> Self {
        SpectrumParams {
            max_frequency: 10.0,
            bins: 100,
            absolute: false,
            convention: FrequencyConvention::Exact,
        }
    }
}

impl SpectrumParams {
    /// Upper edge (Hz) of output bin j: bin j covers (j·w, (j+1)·w], w = f_max/bins.
    pub fn bin_upper(&self, j: usize) -> f64 {
        (j + 1) as f64 * self.max_frequency / self.bins as f64
    }

    /// The output bin holding frequency f (None outside (0, f_max]).
    pub fn bin_of(&self, f: f64) -> Option<usize> {
        if f <= 0.0 || f > self.max_frequency {
            return None;
        }
        let w = self.max_frequency / self.bins as f64;
        // (j·w, (j+1)·w] → j = ceil(f/w) − 1, guarded against rounding at the edges.
        let mut j = ((f / w).ceil() as usize).saturating_sub(1);
        if j + 1 < self.bins && f > (j + 1) as f64 * w {
            j += 1;
        }
        if j > 0 && f <= j as f64 * w {
            j -= 1;
        }
        Some(j.min(self.bins - 1))
    }
}

/// Magnitude spectrum (bins 0..=N/2 of the zero-padded real FFT) of a signal.
pub fn magnitudes(signal: &[f64]) -> Vec<f64> {
    if signal.is_empty() {
        return Vec::new();
    }
    let n = signal.len().next_power_of_two().max(2);
    let mut planner = RealFftPlanner::<f64>::new();
    let fft = planner.plan_fft_forward(n);
    let mut input = fft.make_input_vec();
    input[..signal.len()].copy_from_slice(signal);
    let mut output = fft.make_output_vec();
    fft.process(&mut input, &mut output)
        .expect("buffer sizes come from the plan");
    output.iter().map(|c| c.norm()).collect()
}

/// Resampled spectrum of a signal sampled every `dt` seconds.
pub fn resampled_spectrum(signal: &[f64], dt: f64, params: &SpectrumParams) -> Vec<f64> {
    let mut sums = vec![0.0; params.bins];
    let mut counts = vec![0usize; params.bins];
    let mags = magnitudes(signal);
    if !mags.is_empty() && dt > 0.0 {
        let n = (mags.len() - 1) * 2;
        for (i, m) in mags.iter().enumerate() {
            let f = match params.convention {
                FrequencyConvention::Exact => i as f64 / (n as f64 * dt),
                FrequencyConvention::Original => (1.0 / dt) / 2.0 * i as f64 / (n / 2 + 1) as f64,
            };
            if let Some(j) = params.bin_of(f) {
                sums[j] += m;
                counts[j] += 1;
            }
        }
    }
    sums.iter()
        .zip(&counts)
        .map(|(&s, &c)| if c > 0 { s / c as f64 } else { 0.0 })
        .collect()
}

/// The spectrum of the first differences of the centre's `axis` coordinate.
pub fn center_spectrum(centers: &[Vec2], dt: f64, axis: Axis, params: &SpectrumParams) -> Vec<f64> {
    let diffs: Vec<f64> = centers
        .windows(2)
        .map(|w| {
            let d = match axis {
                Axis::X => w[1].x - w[0].x,
                Axis::Y => w[1].y - w[0].y,
            };
            if params.absolute {
                d.abs()
            } else {
                d
            }
        })
        .collect();
    resampled_spectrum(&diffs, dt, params)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn oscillation(freq: f64, seconds: f64, vertical: bool) -> Vec<Vec2> {
        let dt = 1.0 / 60.0;
        let steps = (seconds / dt).round() as usize + 1;
        (0..steps)
            .map(|k| {
                let t = k as f64 * dt;
                let s = (2.0 * std::f64::consts::PI * freq * t).sin();
                // Steady forward walk at 0.5 per second plus the oscillation on one axis.
                if vertical {
                    Vec2::new(0.5 * t, 3.0 + s)
                } else {
                    Vec2::new(0.5 * t + s, 3.0)
                }
            })
            .collect()
    }

    fn argmax(v: &[f64]) -> usize {
        (0..v.len()).max_by(|&a, &b| v[a].total_cmp(&v[b])).unwrap()
    }

    #[test]
    fn bins_are_left_open() {
        let p = SpectrumParams::default();
        assert_eq!(p.bin_of(0.0), None);
        assert_eq!(p.bin_of(0.05), Some(0));
        assert_eq!(p.bin_of(0.1), Some(0));
        assert_eq!(p.bin_of(2.0), Some(19));
        assert_eq!(p.bin_of(2.0000001), Some(20));
        assert_eq!(p.bin_of(10.0), Some(99));
        assert_eq!(p.bin_of(10.01), None);
        assert!((p.bin_upper(19) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_2hz_vertical_oscillation_peaks_in_the_2hz_bin() {
        let p = SpectrumParams::default();
        for seconds in [10.0, 20.0, 30.0] {
            let c = oscillation(2.0, seconds, true);
            let y = center_spectrum(&c, 1.0 / 60.0, Axis::Y, &p);
            assert_eq!(y.len(), 100);
            assert_eq!(argmax(&y), p.bin_of(2.0).unwrap(), "{seconds} s");
            // The horizontal motion is a steady drift: its constant differences, zero-padded, leak
            // into the lowest bins only, with nothing like the vertical peak at 2 Hz.
            let x = center_spectrum(&c, 1.0 / 60.0, Axis::X, &p);
            assert!(x[19] < 0.05 * y[19], "{} vs {}", x[19], y[19]);
        }
    }

    #[test]
    fn other_frequencies_land_in_their_bins() {
        let p = SpectrumParams::default();
        for f in [0.55, 1.25, 3.05, 7.45] {
            let c = oscillation(f, 30.0, false);
            let x = center_spectrum(&c, 1.0 / 60.0, Axis::X, &p);
            assert_eq!(argmax(&x), p.bin_of(f).unwrap(), "{f} Hz");
        }
    }

    #[test]
    fn absolute_differences_double_the_frequency() {
        let p = SpectrumParams {
            absolute: true,
            ..Default::default()
        };
        let c = oscillation(2.0, 30.0, true);
        let y = center_spectrum(&c, 1.0 / 60.0, Axis::Y, &p);
        // |Δy| has a DC term (leaking into the lowest bins) and its first harmonic at 4 Hz.
        let (two, four) = (p.bin_of(2.0).unwrap(), p.bin_of(4.0).unwrap());
        // 4 Hz is a bin edge: FFT bin 137 of 2048 (4.014 Hz) carries the peak into (4.0, 4.1].
        assert!([four, four + 1].contains(&(argmax(&y[10..]) + 10)));
        assert!(y[four] > 10.0 * y[two]);
    }

    #[test]
    fn original_convention_shifts_slightly_down() {
        // 30 s → 1800 differences → N = 2048. A tone on FFT bin 140 (140·60/2048 ≈ 4.1016 Hz) is
        // in (4.1, 4.2] exactly, but the original maps bin 140 to 30·140/1025 ≈ 4.0976 Hz.
        let f = 140.0 * 60.0 / 2048.0;
        let c = oscillation(f, 30.0, true);
        let exact = SpectrumParams::default();
        let original = SpectrumParams {
            convention: FrequencyConvention::Original,
            ..Default::default()
        };
        assert_eq!(argmax(&center_spectrum(&c, 1.0 / 60.0, Axis::Y, &exact)), 41);
        assert_eq!(argmax(&center_spectrum(&c, 1.0 / 60.0, Axis::Y, &original)), 40);
    }

    #[test]
    fn magnitudes_of_a_cosine() {
        // 8 samples of cos(2π·k/8): bin 1 holds N/2 = 4.
        let s: Vec<f64> = (0..8)
            .map(|k| (2.0 * std::f64::consts::PI * k as f64 / 8.0).cos())
            .collect();
        let m = magnitudes(&s);
        assert_eq!(m.len(), 5);
        assert!((m[1] - 4.0).abs() < 1e-9 && m[0].abs() < 1e-9 && m[2].abs() < 1e-9);
    }
}
