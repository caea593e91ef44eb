//! Physical constants of a voxel, with the two named presets of vsr-model.md §0.

use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;
use vsrlab_physics::SpringMassModel;

/// A named set of physical constants.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
pub enum Preset {
    /// The thesis era (2D-VSR-Sim v1.6.11 … v1.10.0, dyn4j 3.3.0): the default.
    #[default]
    #[serde(rename = "2021")]
    Y2021,
    /// 2D-VSR-Sim HEAD (v1.12.1, dyn4j 4.2.1).
    #[serde(rename = "2022")]
    Y2022,
}

impl std::str::FromStr for Preset {
    type Err = FieldError;
    fn from_str(s: &str) -> Result<Self, FieldError> {
        match s {
            "2021" => Ok(Preset::Y2021),
            "2022" => Ok(Preset::Y2022),
            other => Err(FieldError::message(format!(
                "unknown preset '{other}': expected 2021 or 2022"
            ))),
        }
    }
}

impl std::fmt::Display for Preset {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Preset::Y2021 => "2021",
            Preset::Y2022 => "2022",
        })
    }
}

/// Every physical constant of a voxel. Lengths in world units (a voxel side is 3), masses in
/// world mass units, times in seconds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VoxelParams {
    /// Side length L of an undeformed voxel (length).
    pub side_length: f64,
    /// Side of each corner square as a fraction r of L (dimensionless, 0 < r < 0.5).
    pub mass_side_ratio: f64,
    /// Total mass of the four corner squares of one voxel (mass).
    pub voxel_mass: f64,
    /// Natural frequency of every spring (Hz).
    pub spring_frequency: f64,
    /// Damping ratio of every spring (dimensionless).
    pub spring_damping_ratio: f64,
    /// Which mass turns frequency and damping ratio into stiffness (dyn4j 3.3.0: effective mass;
    /// 4.2.1: reduced mass).
    pub spring_mass_model: SpringMassModel,
    /// Linear velocity damping of each corner square (1/s).
    pub linear_damping: f64,
    /// Angular velocity damping of each corner square (1/s).
    pub angular_damping: f64,
    /// Coulomb friction coefficient of the corner squares (mixed as √(μ₁μ₂) with the ground's).
    pub friction: f64,
    /// Restitution of the corner squares (mixed as max).
    pub restitution: f64,
    /// Area ratio reached at actuation +1 (full contraction), e.g. 0.775.
    pub min_area_ratio: f64,
    /// Area ratio reached at actuation −1 (full expansion), e.g. 1.225.
    pub max_area_ratio: f64,
    /// Whether ropes keep neighbouring corner squares at least one square side apart.
    pub ropes: bool,
    /// Whether corner squares of the same voxel may collide with each other.
    pub same_voxel_collision: bool,
    /// Whether parts of one robot may collide with other parts of the same robot at all.
    pub self_collision: bool,
}

impl VoxelParams {
    /// The constants of a named preset.
    pub fn preset(p: Preset) -> VoxelParams {
        match p {
            Preset::Y2021 => VoxelParams {
                side_length: 3.0,
                mass_side_ratio: 0.4,
                voxel_mass: 1.44,
                spring_frequency: 8.0,
                spring_damping_ratio: 0.3,
                spring_mass_model: SpringMassModel::EffectiveMass,
                linear_damping: 0.1,
                angular_damping: 0.1,
                friction: 10.0,
                restitution: 0.1,
                min_area_ratio: 0.775,
                max_area_ratio: 1.225,
                ropes: true,
                same_voxel_collision: false,
                self_collision: true,
            },
            Preset::Y2022 => VoxelParams {
                side_length: 3.0,
                mass_side_ratio: 0.35,
                voxel_mass: 1.0,
                spring_frequency: 8.0,
                spring_damping_ratio: 0.3,
                spring_mass_model: SpringMassModel::ReducedMass,
                linear_damping: 0.1,
                angular_damping: 0.1,
                friction: 10.0,
                restitution: 0.1,
                min_area_ratio: 0.8,
                max_area_ratio: 1.2,
                ropes: false,
                same_voxel_collision: true,
                self_collision: true,
            },
        }
    }

    /// Side m of a corner square.
    pub fn corner_side(&self) -> f64 {
        self.mass_side_ratio * self.side_length
    }

    /// Checks every field; the error names the field under `voxel` (`voxel.side_length must be
    /// …`) and the problem.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.check().map_err(|e| e.at("voxel"))
    }

    /// [`VoxelParams::validate`] with paths relative to the constants.
    fn check(&self) -> Result<(), FieldError> {
        let positive = [
            ("side_length", self.side_length),
            ("voxel_mass", self.voxel_mass),
            ("spring_frequency", self.spring_frequency),
            ("min_area_ratio", self.min_area_ratio),
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
            ("spring_damping_ratio", self.spring_damping_ratio),
            ("linear_damping", self.linear_damping),
            ("angular_damping", self.angular_damping),
            ("friction", self.friction),
            ("restitution", self.restitution),
        ];
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(FieldError::sentence(
                    name,
                    format!("must be a non-negative number, got {v}"),
                ));
            }
        }
        if !(self.mass_side_ratio > 0.0 && self.mass_side_ratio < 0.5) {
            return Err(FieldError::sentence(
                "mass_side_ratio",
                format!("must be in (0, 0.5), got {}", self.mass_side_ratio),
            ));
        }
        if !(self.max_area_ratio.is_finite() && self.min_area_ratio <= 1.0 && self.max_area_ratio >= 1.0) {
            return Err(FieldError::sentence(
                "min_area_ratio",
                format!(
                    "must be ≤ 1 ≤ voxel.max_area_ratio, got {} and {}",
                    self.min_area_ratio, self.max_area_ratio
                ),
            ));
        }
        let min_side = (self.min_area_ratio).sqrt() * self.side_length;
        if min_side < 2.0 * self.corner_side() {
            return Err(FieldError::sentence(
                "min_area_ratio",
                format!(
                    "{} is too small: the corner squares would overlap (needs ≥ (2·mass_side_ratio)² = {})",
                    self.min_area_ratio,
                    (2.0 * self.mass_side_ratio).powi(2)
                ),
            ));
        }
        Ok(())
    }
}

impl Default for VoxelParams {
    fn default() -> Self {
        VoxelParams::preset(Preset::Y2021)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_valid_and_differ_where_the_spec_says() {
        let a = VoxelParams::preset(Preset::Y2021);
        let b = VoxelParams::preset(Preset::Y2022);
        a.validate().unwrap();
        b.validate().unwrap();
        assert!((a.corner_side() - 1.2).abs() < 1e-12);
        assert!((b.corner_side() - 1.05).abs() < 1e-12);
        assert!(a.ropes && !b.ropes);
        // 2021 part mass 0.36 = 0.25·m²
        assert!((a.voxel_mass / 4.0 - 0.25 * 1.2 * 1.2).abs() < 1e-12);
    }

    #[test]
    fn bad_fields_are_named() {
        let p = VoxelParams {
            mass_side_ratio: 0.7,
            ..VoxelParams::default()
        };
        let e = p.validate().unwrap_err();
        assert_eq!(e.path, "voxel.mass_side_ratio");
        assert_eq!(e.to_string(), "voxel.mass_side_ratio must be in (0, 0.5), got 0.7");
        let p = VoxelParams {
            min_area_ratio: 0.2,
            ..VoxelParams::default()
        };
        let e = p.validate().unwrap_err();
        assert_eq!(e.path, "voxel.min_area_ratio");
        assert!(
            e.to_string().starts_with("voxel.min_area_ratio 0.2 is too small"),
            "{e}"
        );
    }
}
