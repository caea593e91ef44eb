//! `vsrlab-brain`: controllers that turn sensor readings into voxel actuations.
//!
//! Every controller implements [`Controller`]: at each control step it receives the time and all
//! voxels' readings (grid order) and writes one actuation per voxel in [-1, 1] (grid order).
#![warn(missing_docs)]

pub mod controllers;

pub use controllers::constant::ConstantController;
pub use controllers::phase::PhaseController;
pub use controllers::random::RandomController;

use serde::{Deserialize, Serialize};
use vsrlab_body::Morphology;

/// A brain: maps (time, readings) to actuations, possibly with internal state.
pub trait Controller: Send {
    /// Clears internal state, as at the start of an episode.
    fn reset(&mut self);
    /// Computes one actuation per voxel (grid order) from all readings (grid order).
    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]);
}

/// Description of a brain, as written in configs and robot files.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum BrainSpec {
    /// Open-loop a = A·sin(2πft + φ(x, y)) with φ = phase_x·π·x/W + phase_y·π·y/H.
    Phase {
        /// Frequency f (Hz).
        #[serde(default = "one")]
        frequency: f64,
        /// Amplitude A.
        #[serde(default = "one")]
        amplitude: f64,
        /// Phase shift across the width, in units of π.
        #[serde(default = "one")]
        phase_x: f64,
        /// Phase shift across the height, in units of π.
        #[serde(default)]
        phase_y: f64,
    },
    /// The same constant actuation on every voxel (calibration, passive bodies).
    Constant {
        /// Actuation in [-1, 1] (positive contracts).
        value: f64,
    },
    /// Independent uniform random actuations in [-1, 1], redrawn every `period` seconds
    /// (a baseline, and a stress test for the physics).
    Random {
        /// Seconds between redraws (0 = every step).
        #[serde(default)]
        period: f64,
        /// Seed of the generator.
        #[serde(default)]
        seed: u64,
    },
}

fn one() -> f64 {
    1.0
}

impl Default for BrainSpec {
    fn default() -> Self {
        BrainSpec::Phase {
            frequency: 1.0,
            amplitude: 1.0,
            phase_x: 1.0,
            phase_y: 0.0,
        }
    }
}

/// Why a brain could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BrainError {
    /// A parameter is out of range.
    #[error("brain.{field}: {msg}")]
    Invalid {
        /// The offending field.
        field: &'static str,
        /// What is wrong.
        msg: String,
    },
    /// The brain name is unknown.
    #[error("unknown brain '{0}': expected phase, constant:<value> or random[:<period s>]")]
    Unknown(String),
}

impl BrainSpec {
    /// Parses a short name from the command line: `phase`, `constant:<value>`, `random[:<period>]`.
    pub fn parse(s: &str) -> Result<BrainSpec, BrainError> {
        let (name, arg) = s.split_once(':').map_or((s, None), |(a, b)| (a, Some(b)));
        let number = |a: &str| a.parse::<f64>().map_err(|_| BrainError::Unknown(s.to_string()));
        match (name, arg) {
            ("phase", None) => Ok(BrainSpec::default()),
            ("constant", Some(v)) => Ok(BrainSpec::Constant { value: number(v)? }),
            ("random", None) => Ok(BrainSpec::Random { period: 0.0, seed: 0 }),
            ("random", Some(p)) => Ok(BrainSpec::Random {
                period: number(p)?,
                seed: 0,
            }),
            _ => Err(BrainError::Unknown(s.to_string())),
        }
    }

    /// Builds the controller for a body.
    pub fn build(
        &self,
        morphology: &Morphology,
        _readings_per_voxel: &[usize],
    ) -> Result<Box<dyn Controller>, BrainError> {
        match *self {
            BrainSpec::Phase {
                frequency,
                amplitude,
                phase_x,
                phase_y,
            } => {
                for (field, v) in [
                    ("frequency", frequency),
                    ("amplitude", amplitude),
                    ("phase_x", phase_x),
                    ("phase_y", phase_y),
                ] {
                    if !v.is_finite() {
                        return Err(BrainError::Invalid {
                            field,
                            msg: format!("must be a finite number, got {v}"),
                        });
                    }
                }
                Ok(Box::new(PhaseController::for_morphology(
                    morphology, frequency, amplitude, phase_x, phase_y,
                )))
            }
            BrainSpec::Constant { value } => {
                if !value.is_finite() {
                    return Err(BrainError::Invalid {
                        field: "value",
                        msg: format!("must be a finite number, got {value}"),
                    });
                }
                Ok(Box::new(ConstantController { value }))
            }
            BrainSpec::Random { period, seed } => {
                if !(period.is_finite() && period >= 0.0) {
                    return Err(BrainError::Invalid {
                        field: "period",
                        msg: format!("must be ≥ 0 seconds, got {period}"),
                    });
                }
                Ok(Box::new(RandomController::new(period, seed)))
            }
        }
    }
}
