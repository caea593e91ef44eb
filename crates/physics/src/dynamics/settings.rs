//! World-wide simulation settings.

use crate::math::Vec2;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

impl std::str::FromStr for Solver {
    type Err = FieldError;
    /// Parses a solver's name as experiment files write it (`soft-substeps`,
    /// `sequential-impulses`).
    fn from_str(name: &str) -> Result<Solver, FieldError> {
        match name {
            "soft-substeps" => Ok(Solver::SoftSubsteps),
            "sequential-impulses" => Ok(Solver::SequentialImpulses),
            _ => Err(FieldError::message(format!(
                "expected soft-substeps or sequential-impulses, got '{name}'"
            ))),
        }
    }
}

/// How a spring's stiffness k = M·ω² and damping c = 2·M·ζ·ω choose the mass M.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum SpringMassModel {
    /// Effective mass of the constraint along its axis, including the rotational terms of the two
    /// anchored parts (recomputed every step as the axis turns).
    #[default]
    EffectiveMass,
    /// Reduced mass m₁·m₂/(m₁+m₂) of the two parts, ignoring anchor offsets.
    ReducedMass,
}

/// Which constraint solver steps the world.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Solver {
    /// vsrlab's own solver: welded parts merged into rigid bodies, soft contacts with a speculative
    /// margin, `substeps` sub-steps per step. Fast; matches the original's calibration figures.
    #[default]
    SoftSubsteps,
    /// dyn4j's pipeline (the engine of 2D-VSR-Sim): every part its own body, welds as rigid joints,
    /// contacts only between overlapping shapes, sequential impulses with warm starting
    /// (`velocity_iterations`), then a position pass (`position_iterations`, Baumgarte, slop).
    SequentialImpulses,
}

/// How the soft solver's contacts behave.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ContactModel {
    /// Soft contacts with a speculative margin, solved in every sub-step (vsrlab's).
    #[default]
    Soft,
    /// The original's (dyn4j's): contacts between overlapping shapes only, rigid and warm started,
    /// a position pass and continuous collision (the `dyn4j` version's); a fidelity candidate.
    Dyn4j,
}

/// Which dyn4j the sequential-impulse solver follows where the two versions behind 2D-VSR-Sim
/// differ: the contact position pass's masses, continuous collision detection and its distance
/// routine (docs/physics.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Dyn4jVersion {
    /// dyn4j 3.3.0 (2D-VSR-Sim up to v1.10.0, preset 2021).
    #[serde(rename = "3.3.0")]
    V3_3_0,
    /// dyn4j 4.2.1 (2D-VSR-Sim HEAD, preset 2022).
    #[serde(rename = "4.2.1")]
    V4_2_1,
}

/// Settings shared by the whole world. Units are the world's nominal units (length, mass, s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct WorldSettings {
    /// Time step of one [`crate::World::step`], in seconds.
    pub dt: f64,
    /// Number of sub-steps the constraint solver takes inside one step (≥ 1).
    pub substeps: u32,
    /// Gauss–Seidel iterations over the springs in each sub-step (≥ 1).
    pub iterations: u32,
    /// Largest distance (length) the fastest body should travel in one sub-step: faster steps get
    /// more sub-steps, up to four times `substeps` (0 = always exactly `substeps`).
    pub substep_travel: f64,
    /// Gravity acceleration (length/s²); zero for a top-down world.
    pub gravity: Vec2,
    /// Largest distance a body may travel in one step; faster bodies are slowed down.
    pub max_translation: f64,
    /// Largest rotation (radians) a body may turn in one step.
    pub max_rotation: f64,
    /// Stiffness of contacts and ropes as a natural frequency, in Hz (capped at a quarter of the
    /// sub-step rate).
    pub contact_hertz: f64,
    /// Damping ratio of contacts and ropes.
    pub contact_damping_ratio: f64,
    /// Largest speed (length/s) at which overlapping bodies are pushed apart.
    pub contact_push_max: f64,
    /// Relative normal speed (length/s) below which contacts do not bounce.
    pub restitution_threshold: f64,
    /// Gap (length) under which contacts are created before shapes actually touch.
    pub speculative_distance: f64,
    /// Gap (length) under which a shape counts as touching another.
    pub touch_tolerance: f64,
    /// How the soft solver's contacts behave (`soft-substeps` only). `dyn4j` contacts are swept
    /// `iterations` times per sub-step, after the springs, and read `warm_starting`,
    /// `position_iterations`, `baumgarte`, `linear_slop`, `max_linear_correction`, `dyn4j` and
    /// `continuous_collision` below.
    pub contact_model: ContactModel,
    /// Which solver steps the world; the fields below apply to `sequential-impulses` only.
    pub solver: Solver,
    /// Velocity iterations per step (joints, then contacts, each iteration).
    pub velocity_iterations: u32,
    /// Most position iterations per step (stops early once every constraint is within tolerance).
    pub position_iterations: u32,
    /// Whether contact and joint impulses of the last step start this step's solve.
    pub warm_starting: bool,
    /// Fraction of the contact overlap the position pass removes per iteration.
    pub baumgarte: f64,
    /// Overlap (length) that contacts keep (dyn4j's linear tolerance).
    pub linear_slop: f64,
    /// Angle (radians) within which a weld counts as solved.
    pub angular_slop: f64,
    /// Largest position correction (length) of one contact or rope per iteration.
    pub max_linear_correction: f64,
    /// Which dyn4j to follow; unset, the version the world's bodies were made for
    /// ([`crate::WorldBuilder::made_for`]), or 3.3.0 when none says.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dyn4j: Option<Dyn4jVersion>,
    /// Whether bodies that would pass into static geometry within a step are stopped at the time
    /// of impact (dyn4j's continuous collision detection, mode ALL).
    pub continuous_collision: bool,
    /// Whole sequential-impulse steps taken per step, each of `dt / sequential_substeps` (1 =
    /// dyn4j's pipeline; more is the "sub-stepped" variant of docs/fidelity.md).
    pub sequential_substeps: u32,
    /// Whether each velocity and position sweep takes the joints grouped by greedy colour (no two
    /// joints of a colour share a body, the island walk's order kept within a colour), the order a
    /// vectorised sweep needs; off, the island walk's order (dyn4j's).
    pub coloured_joints: bool,
    /// Whether welded parts become one rigid body, as in the soft solver, instead of bodies joined
    /// by weld joints (dyn4j's); a fidelity candidate of docs/fidelity.md.
    pub merge_welds: bool,
}

impl Default for WorldSettings {
    fn default() -> Self {
        WorldSettings {
            dt: 1.0 / 60.0,
            substeps: 4,
            iterations: 1,
            substep_travel: 0.0,
            gravity: Vec2::new(0.0, -9.8),
            max_translation: 2.0,
            max_rotation: std::f64::consts::FRAC_PI_2,
            contact_hertz: 60.0,
            contact_damping_ratio: 10.0,
            contact_push_max: 12.0,
            restitution_threshold: 1.0,
            speculative_distance: 0.1,
            touch_tolerance: 0.005,
            contact_model: ContactModel::Soft,
            solver: Solver::SoftSubsteps,
            velocity_iterations: 10,
            position_iterations: 10,
            warm_starting: true,
            baumgarte: 0.2,
            linear_slop: 0.005,
            angular_slop: 2f64.to_radians(),
            max_linear_correction: 0.2,
            dyn4j: None,
            continuous_collision: true,
            sequential_substeps: 1,
            coloured_joints: false,
            merge_welds: false,
        }
    }
}

impl WorldSettings {
    /// The dyn4j the sequential-impulse solver follows: the one named, or 3.3.0.
    pub fn dyn4j_version(&self) -> Dyn4jVersion {
        self.dyn4j.unwrap_or(Dyn4jVersion::V3_3_0)
    }

    /// Checks that every field is in range; the error names the field (`dt must be …`).
    pub fn validate(&self) -> Result<(), FieldError> {
        let positive = [
            ("dt", self.dt),
            ("max_translation", self.max_translation),
            ("max_rotation", self.max_rotation),
            ("contact_hertz", self.contact_hertz),
            ("contact_damping_ratio", self.contact_damping_ratio),
            ("contact_push_max", self.contact_push_max),
            ("baumgarte", self.baumgarte),
            ("max_linear_correction", self.max_linear_correction),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(FieldError::sentence(
                    name,
                    format!("must be a positive number, got {v}"),
                ));
            }
        }
        let non_negative = [
            ("restitution_threshold", self.restitution_threshold),
            ("speculative_distance", self.speculative_distance),
            ("substep_travel", self.substep_travel),
            ("touch_tolerance", self.touch_tolerance),
            ("linear_slop", self.linear_slop),
            ("angular_slop", self.angular_slop),
        ];
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(FieldError::sentence(
                    name,
                    format!("must be a non-negative number, got {v}"),
                ));
            }
        }
        if self.substeps == 0 || self.substeps > 64 {
            return Err(FieldError::sentence(
                "substeps",
                format!("must be in 1..=64, got {}", self.substeps),
            ));
        }
        if self.iterations == 0 || self.iterations > 64 {
            return Err(FieldError::sentence(
                "iterations",
                format!("must be in 1..=64, got {}", self.iterations),
            ));
        }
        if self.sequential_substeps == 0 || self.sequential_substeps > 64 {
            return Err(FieldError::sentence(
                "sequential_substeps",
                format!("must be in 1..=64, got {}", self.sequential_substeps),
            ));
        }
        if self.velocity_iterations == 0 || self.velocity_iterations > 1000 {
            return Err(FieldError::sentence(
                "velocity_iterations",
                format!("must be in 1..=1000, got {}", self.velocity_iterations),
            ));
        }
        if self.position_iterations > 1000 {
            return Err(FieldError::sentence(
                "position_iterations",
                format!("must be in 0..=1000, got {}", self.position_iterations),
            ));
        }
        if !self.gravity.is_finite() {
            return Err(FieldError::sentence("gravity", "must be finite"));
        }
        Ok(())
    }
}
