//! Materials: a voxel's elastic, inertial, frictional, thermal and damping properties, and what
//! a link between two voxels takes from them (`docs/voxelyze-model.md` §1.2, §2, §3.2, §4).

use vsrlab_field::FieldError;

/// A voxel material (SI units). Poisson's ratio is 0: the linear model without volume effects,
/// as voxcraft-sim ran the affordance study.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus (Pa).
    pub youngs_modulus: f64,
    /// Density (kg/m³).
    pub density: f64,
    /// Thermal expansion per unit temperature (a voxel's rest size is `s (1 + cte T)`).
    pub cte: f64,
    /// Static friction coefficient against the floor.
    pub static_friction: f64,
    /// Kinetic friction coefficient against the floor.
    pub kinetic_friction: f64,
    /// Internal (bond) damping ratio.
    pub internal_damping: f64,
    /// Global ("to ground") damping ratio.
    pub global_damping: f64,
    /// Collision damping ratio (at the floor, on vertical speed).
    pub collision_damping: f64,
}

impl Material {
    /// Voxelyze's `addMaterial` defaults: E 1e6 Pa, density 1e3 kg/m³, no expansion, no
    /// friction, internal damping 1, no global or collision damping.
    pub fn voxelyze(youngs_modulus: f64, density: f64) -> Material {
        Material {
            youngs_modulus,
            density,
            cte: 0.0,
            static_friction: 0.0,
            kinetic_friction: 0.0,
            internal_damping: 1.0,
            global_damping: 0.0,
            collision_damping: 0.0,
        }
    }

    /// The affordance study's robot material (thesis §5.1.2.1 and its voxcraft-sim settings):
    /// E 1e4 Pa, density 10 kg/m³, friction 1 / 0.5, CTE 0.01, damping bond 1, collision 0.8,
    /// global 0.01.
    pub fn affordance() -> Material {
        Material {
            youngs_modulus: 1e4,
            density: 10.0,
            cte: 0.01,
            static_friction: 1.0,
            kinetic_friction: 0.5,
            internal_damping: 1.0,
            global_damping: 0.01,
            collision_damping: 0.8,
        }
    }

    /// Checks that every value is finite and in range, naming the first that is not.
    pub fn validate(&self) -> Result<(), FieldError> {
        let positive = [("youngs_modulus", self.youngs_modulus), ("density", self.density)];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(FieldError::new(name, format!("must be a finite number > 0, got {v}")));
            }
        }
        let non_negative = [
            ("static_friction", self.static_friction),
            ("kinetic_friction", self.kinetic_friction),
            ("internal_damping", self.internal_damping),
            ("global_damping", self.global_damping),
            ("collision_damping", self.collision_damping),
        ];
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(FieldError::new(name, format!("must be a finite number ≥ 0, got {v}")));
            }
        }
        if !self.cte.is_finite() {
            return Err(FieldError::new("cte", format!("must be finite, got {}", self.cte)));
        }
        Ok(())
    }
}

/// What a voxel of a material and size needs each step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct VoxelConstants {
    pub mass: f64,
    pub inertia: f64,
    pub sqrt_mass: f64,
    /// `2 √(m E s)`: the linear damping coefficient per unit damping ratio.
    pub linear_damping: f64,
    /// `2 √(I E s³)`: the angular one.
    pub angular_damping: f64,
    /// Floor penalty stiffness `2 E s`.
    pub floor_stiffness: f64,
}

impl VoxelConstants {
    pub fn new(m: &Material, size: f64) -> VoxelConstants {
        let mass = m.density * size.powi(3);
        let inertia = mass * size * size / 6.0;
        VoxelConstants {
            mass,
            inertia,
            sqrt_mass: mass.sqrt(),
            linear_damping: 2.0 * (mass * m.youngs_modulus * size).sqrt(),
            angular_damping: 2.0 * (inertia * m.youngs_modulus * size.powi(3)).sqrt(),
            floor_stiffness: 2.0 * m.youngs_modulus * size,
        }
    }
}

/// A link's beam constants (ν = 0), from the harmonic mean of the two voxels' moduli and the
/// lattice size `l` (`docs/voxelyze-model.md` §3.2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct LinkConstants {
    /// Young's modulus of the link: `2 E1 E2 / (E1 + E2)`.
    pub e: f64,
    pub a1: f64,
    pub a2: f64,
    pub b1: f64,
    pub b2: f64,
    pub b3: f64,
    /// Damping helpers: √a1, √(a2 l²/6), √b1, √(b2 l/2), √(b3 l²/6).
    pub sqrt_a1: f64,
    pub sqrt_a2: f64,
    pub sqrt_b1: f64,
    pub sqrt_b2: f64,
    pub sqrt_b3: f64,
}

impl LinkConstants {
    pub fn new(e1: f64, e2: f64, l: f64) -> LinkConstants {
        let e = if e1 == e2 { e1 } else { 2.0 * e1 * e2 / (e1 + e2) };
        let (a1, a2, b1, b2, b3) = (e * l, e * l.powi(3) / 12.0, e * l, e * l * l / 2.0, e * l.powi(3) / 6.0);
        LinkConstants {
            e,
            a1,
            a2,
            b1,
            b2,
            b3,
            sqrt_a1: a1.sqrt(),
            sqrt_a2: (a2 * l * l / 6.0).sqrt(),
            sqrt_b1: b1.sqrt(),
            sqrt_b2: (b2 * l / 2.0).sqrt(),
            sqrt_b3: (b3 * l * l / 6.0).sqrt(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Voxelyze's test material (s 1 mm, E 1e6, ρ 1e3): m 1e-6 kg, I 1.667e-13, a1 = b1 = 1000 N/m,
    /// b2 0.5 N, b3 1.667e-4 N·m, a2 8.333e-5 N·m; a link of E 1e6 and 1e9 is the two in series.
    #[test]
    fn constants_are_voxelyzes() {
        let v = VoxelConstants::new(&Material::voxelyze(1e6, 1e3), 1e-3);
        assert!((v.mass - 1e-6).abs() < 1e-20 && (v.inertia - 1e-12 / 6.0).abs() < 1e-25);
        let l = LinkConstants::new(1e6, 1e6, 1e-3);
        assert!((l.a1 - 1000.0).abs() < 1e-9 && (l.b1 - 1000.0).abs() < 1e-9);
        assert!((l.b2 - 0.5).abs() < 1e-12 && (l.b3 - 1e-3 / 6.0).abs() < 1e-15 && (l.a2 - 1e-3 / 12.0).abs() < 1e-15);
        let mixed = LinkConstants::new(1e6, 1e9, 1e-3);
        assert!((mixed.a1 - 2.0 / (1.0 / 1000.0 + 1.0 / 1e6)).abs() < 1e-9);
        let err = Material::voxelyze(-1.0, 1.0).validate().unwrap_err();
        assert_eq!(err.path, "youngs_modulus");
        assert_eq!(err.to_string(), "youngs_modulus: must be a finite number > 0, got -1");
        assert!(Material::affordance().validate().is_ok());
    }
}
