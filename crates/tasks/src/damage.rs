//! [`Damage`]: body parts that break in the middle of an episode (thesis §5.3.4.1). At time `at`
//! every actuated unit (a voxel) breaks independently with probability `probability`; a broken
//! unit's actuation stays 0 from then on, so its shape follows only the external forces.
//!
//! The broken units are drawn from the episode seed alone ([`Damage::mask`]), before the episode
//! starts, so the same seed breaks the same voxels whatever the brain does, and nothing changes
//! before `at`. Any controller can be damaged; the body must support it
//! ([`crate::Agent::break_actuators`]). The original code has no mid-episode trigger
//! (thesis-code-facts.md §6.2): this follows the thesis text.

use crate::episode::EpisodeError;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

/// Mixed into the episode seed so that the damage draw is a stream of its own.
const DAMAGE_STREAM: u64 = 0xda4a_6e5e_ed00_0001;

/// When and how likely body parts break.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Damage {
    /// Simulated time (s) at which the units break (thesis: 30 s of 60).
    pub at: f64,
    /// Probability that each unit breaks (thesis: 0.5).
    pub probability: f64,
}

impl Damage {
    /// Checks the fields; the error names them under `task.damage`.
    pub fn validate(&self) -> Result<(), EpisodeError> {
        self.check_under_task().map_err(EpisodeError::Field)
    }

    /// [`Damage::validate`] as a field error (`task.damage.at must be …`).
    fn check_under_task(&self) -> Result<(), FieldError> {
        self.check().map_err(|e| e.at("damage").at("task"))
    }

    /// The checks of [`Damage::validate`], with paths relative to the damage table.
    fn check(&self) -> Result<(), FieldError> {
        if !(self.at.is_finite() && self.at >= 0.0) {
            return Err(FieldError::sentence(
                "at",
                format!("must be a time ≥ 0 seconds, got {}", self.at),
            ));
        }
        if !(0.0..=1.0).contains(&self.probability) {
            return Err(FieldError::sentence(
                "probability",
                format!("must be in [0, 1], got {}", self.probability),
            ));
        }
        Ok(())
    }

    /// Which of `units` units break in the episode with this seed.
    pub fn mask(&self, units: usize, seed: u64) -> Vec<bool> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed ^ DAMAGE_STREAM);
        (0..units).map(|_| rng.random::<f64>() < self.probability).collect()
    }

    /// Parses the command-line form `<at>:<probability>` (e.g. `30:0.5`), checked; a value out
    /// of range is an error on its field under `task.damage`.
    pub fn parse(text: &str) -> Result<Damage, FieldError> {
        let (at, p) = text.split_once(':').ok_or_else(|| {
            FieldError::message(format!("damage '{text}': expected <time s>:<probability>, e.g. 30:0.5"))
        })?;
        let number = |s: &str| {
            s.trim()
                .parse::<f64>()
                .map_err(|_| FieldError::message(format!("damage '{text}': '{s}' is not a number")))
        };
        let damage = Damage {
            at: number(at)?,
            probability: number(p)?,
        };
        damage.check_under_task()?;
        Ok(damage)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mask_depends_on_the_seed_only_and_breaks_about_p_of_the_units() {
        let d = Damage {
            at: 30.0,
            probability: 0.5,
        };
        assert_eq!(d.mask(10, 7), d.mask(10, 7));
        assert_ne!(d.mask(64, 7), d.mask(64, 8));
        let broken = d.mask(10_000, 1).iter().filter(|&&b| b).count();
        assert!((4_800..5_200).contains(&broken), "{broken}");
        let none = Damage { probability: 0.0, ..d };
        assert!(none.mask(100, 3).iter().all(|&b| !b));
        let all = Damage { probability: 1.0, ..d };
        assert!(all.mask(100, 3).iter().all(|&b| b));
    }

    #[test]
    fn parse_and_validate_name_the_field() {
        assert_eq!(
            Damage::parse("30:0.5"),
            Ok(Damage {
                at: 30.0,
                probability: 0.5
            })
        );
        let e = Damage::parse("30").unwrap_err();
        assert!(e.to_string().contains("<time s>:<probability>"), "{e}");
        let e = Damage::parse("30:1.5").unwrap_err();
        assert_eq!(e.path, "task.damage.probability");
        assert_eq!(e.to_string(), "task.damage.probability must be in [0, 1], got 1.5");
        let e = Damage::parse("-1:0.5").unwrap_err();
        assert_eq!(e.path, "task.damage.at");
        assert!(Damage::parse("x:0.5").unwrap_err().to_string().contains("'x'"));
    }
}
