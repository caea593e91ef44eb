//! Constants of a pressure-based soft agent (thesis ch. 6, psa-model.md): the membrane, the gas,
//! the sensors, and which of springs and pressure the brain controls.
//!
//! Units are SI in a 2D world: metres, kilograms, seconds, newtons; a 2D pressure is a force per
//! unit length (N/m) and an area is in m². The masses are 1 m squares of 2,500 kg (the original's
//! Box2D bodies, read as SI). With the thesis's gas masses (0.05–0.1 kg of N₂) an SI gas could not
//! lift them, so the default gas masses are those that give the original code's amount of gas
//! (its n = m·M with m = 50/75/100): m = 0.78475 × {50, 75, 100} kg. The original's formula is
//! available as [`GasAmount::TimesMolarMass`] (then `gas_mass` is in the original's units).

use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

/// The three morphologies of the thesis (§6.3): masses, radius and gas.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PsaSize {
    /// 10 masses on a circle of radius 5.
    Small,
    /// 15 masses on a circle of radius 7.5.
    #[default]
    Medium,
    /// 20 masses on a circle of radius 10.
    Large,
}

impl PsaSize {
    /// Every size, smallest first.
    pub const ALL: [PsaSize; 3] = [PsaSize::Small, PsaSize::Medium, PsaSize::Large];

    /// Number of masses.
    pub fn masses(self) -> usize {
        match self {
            PsaSize::Small => 10,
            PsaSize::Medium => 15,
            PsaSize::Large => 20,
        }
    }
    /// Radius of the circle the masses start on (m).
    pub fn radius(self) -> f64 {
        match self {
            PsaSize::Small => 5.0,
            PsaSize::Medium => 7.5,
            PsaSize::Large => 10.0,
        }
    }
    /// The original code's gas "mass" for this size (50 / 75 / 100).
    pub fn original_gas_mass(self) -> f64 {
        match self {
            PsaSize::Small => 50.0,
            PsaSize::Medium => 75.0,
            PsaSize::Large => 100.0,
        }
    }
    /// The name used in configs.
    pub fn name(self) -> &'static str {
        match self {
            PsaSize::Small => "small",
            PsaSize::Medium => "medium",
            PsaSize::Large => "large",
        }
    }
}

/// How the amount of gas n follows from the gas mass m and the molar mass M.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GasAmount {
    /// n = m / M (mol), with m in kg and M in kg/mol.
    #[default]
    PerMolarMass,
    /// The original code's n = m · M·1000 (M in g/mol); `gas_mass` is then in the original's
    /// units (50 / 75 / 100 for small / medium / large).
    TimesMolarMass,
}

/// Which length L the pressure force p·L of a membrane edge uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum PressureLength {
    /// The edge's current length (thesis §6.2.1.2).
    #[default]
    Actual,
    /// The spring's target length, as the original code did.
    Target,
}

/// Every constant of a PSA. Build one with [`PsaParams::of_size`] and change fields as needed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PsaParams {
    /// Number of masses on the membrane (≥ 3).
    pub masses: usize,
    /// Radius of the circle the masses start on (m).
    pub radius: f64,
    /// Side of each square mass (m).
    pub mass_side: f64,
    /// Mass per unit area of the squares (kg/m²).
    pub density: f64,
    /// Coulomb friction coefficient of the squares.
    pub friction: f64,
    /// Natural frequency of the membrane springs (Hz).
    pub spring_frequency: f64,
    /// Damping ratio of the membrane springs.
    pub spring_damping: f64,
    /// Shortest target length of a spring, as a fraction of its rest length (reached at s = 1).
    pub min_length: f64,
    /// Longest target length of a spring, as a fraction of its rest length (reached at s = −1).
    pub max_length: f64,
    /// Whether the brain sets the springs' target lengths (false: the "w/o spring control"
    /// ablation, springs keep their rest length).
    pub spring_control: bool,
    /// Whether the brain changes the pressure by Δp each step (false: the "w/o pressure control"
    /// ablation, p = nRT/A each step).
    pub pressure_control: bool,
    /// Mass of the gas (kg; see [`GasAmount`]).
    pub gas_mass: f64,
    /// Molar mass of the gas (kg/mol; N₂ 0.0280134).
    pub molar_mass: f64,
    /// Temperature (K).
    pub temperature: f64,
    /// Ideal gas constant (J/(mol·K)).
    pub gas_constant: f64,
    /// How n follows from the gas mass.
    pub gas_amount: GasAmount,
    /// p_max = `max_pressure_factor` · nRT/(π r²) (the original code: 1.25; thesis text: 1).
    pub max_pressure_factor: f64,
    /// p_min = `min_pressure_fraction` · p_max (0.2).
    pub min_pressure_fraction: f64,
    /// Which length the pressure force of an edge uses.
    pub pressure_length: PressureLength,
    /// Length of the sensors' moving average (s; 0.25 s is the original's 15 samples at 60 Hz).
    pub sensor_window: f64,
    /// Mass positions relative to the centre are divided by this (the original's 8.75).
    pub position_scale: f64,
    /// The centre's displacement since the previous step is divided by this (the original's 8).
    pub displacement_scale: f64,
}

impl PsaParams {
    /// The thesis's constants for one size.
    pub fn of_size(size: PsaSize) -> PsaParams {
        PsaParams {
            masses: size.masses(),
            radius: size.radius(),
            mass_side: 1.0,
            density: 2500.0,
            friction: 10.0,
            spring_frequency: 8.0,
            spring_damping: 0.3,
            min_length: 0.75,
            max_length: 1.25,
            spring_control: true,
            pressure_control: true,
            gas_mass: SI_GAS_MASS_PER_ORIGINAL_UNIT * size.original_gas_mass(),
            molar_mass: N2_MOLAR_MASS,
            temperature: 288.15,
            gas_constant: GAS_CONSTANT,
            gas_amount: GasAmount::PerMolarMass,
            max_pressure_factor: 1.25,
            min_pressure_fraction: 0.2,
            pressure_length: PressureLength::Actual,
            sensor_window: 0.25,
            position_scale: 8.75,
            displacement_scale: 8.0,
        }
    }

    /// Amount of gas n (mol).
    pub fn moles(&self) -> f64 {
        match self.gas_amount {
            GasAmount::PerMolarMass => self.gas_mass / self.molar_mass,
            GasAmount::TimesMolarMass => self.gas_mass * self.molar_mass * 1000.0,
        }
    }
    /// nRT (J), the constant of the ideal gas law pA = nRT.
    pub fn n_r_t(&self) -> f64 {
        self.moles() * self.gas_constant * self.temperature
    }
    /// Largest pressure (N/m).
    pub fn max_pressure(&self) -> f64 {
        self.max_pressure_factor * self.n_r_t() / (std::f64::consts::PI * self.radius * self.radius)
    }
    /// Smallest pressure (N/m).
    pub fn min_pressure(&self) -> f64 {
        self.min_pressure_fraction * self.max_pressure()
    }
    /// Rest length of a membrane spring: the chord 2r·sin(π/n).
    pub fn rest_length(&self) -> f64 {
        2.0 * self.radius * (std::f64::consts::PI / self.masses as f64).sin()
    }
    /// Area of the regular polygon through the masses at the start (m²).
    pub fn initial_area(&self) -> f64 {
        let n = self.masses as f64;
        0.5 * n * self.radius * self.radius * (2.0 * std::f64::consts::PI / n).sin()
    }
    /// Number of sensor readings: 3 per mass (touch, x, y) and 3 for the whole (Δx, Δy, p).
    pub fn reading_count(&self) -> usize {
        3 * self.masses + 3
    }

    /// The fields that must be positive, by name.
    fn positive_fields(&self) -> [(&'static str, f64); 12] {
        [
            ("radius", self.radius),
            ("mass_side", self.mass_side),
            ("density", self.density),
            ("spring_frequency", self.spring_frequency),
            ("molar_mass", self.molar_mass),
            ("temperature", self.temperature),
            ("gas_constant", self.gas_constant),
            ("max_pressure_factor", self.max_pressure_factor),
            ("sensor_window", self.sensor_window),
            ("position_scale", self.position_scale),
            ("displacement_scale", self.displacement_scale),
            ("min_length", self.min_length),
        ]
    }

    /// The fields that may be zero but not negative, by name.
    fn non_negative_fields(&self) -> [(&'static str, f64); 3] {
        [
            ("friction", self.friction),
            ("spring_damping", self.spring_damping),
            ("gas_mass", self.gas_mass),
        ]
    }

    /// Checks every field; the error names it (`masses`, `radius`, `gas_mass`, …).
    pub fn validate(&self) -> Result<(), FieldError> {
        if self.masses < 3 {
            return Err(FieldError::sentence(
                "masses",
                format!("must be at least 3, got {}", self.masses),
            ));
        }
        if self.masses > MAX_MASSES {
            return Err(FieldError::sentence(
                "masses",
                format!("must be at most {MAX_MASSES}, got {}", self.masses),
            ));
        }
        let positive = self.positive_fields();
        let thesis = PsaParams::of_size(PsaSize::Small);
        let thesis_fields = [thesis.positive_fields().to_vec(), thesis.non_negative_fields().to_vec()].concat();
        let thesis_value = |name: &str| thesis_fields.iter().find(|f| f.0 == name).map_or(1.0, |f| f.1);
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(FieldError::sentence(name, format!("must be finite and > 0, got {v}")));
            }
            let typical = thesis_value(name);
            let (low, high) = (typical / SCALE_RANGE, typical * SCALE_RANGE);
            if !(low..=high).contains(&v) {
                return Err(FieldError::sentence(
                    name,
                    format!(
                        "must be within [{low:e}, {high:e}] (a factor {SCALE_RANGE:e} either side of the thesis's \
                         {typical}; beyond it the model's masses, forces or buffers overflow or vanish), got {v:e}"
                    ),
                ));
            }
        }
        let non_negative = self.non_negative_fields();
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(FieldError::sentence(name, format!("must be finite and ≥ 0, got {v}")));
            }
            let high = thesis_value(name).max(1.0) * SCALE_RANGE;
            if v > high {
                return Err(FieldError::sentence(
                    name,
                    format!("must be at most {high:e} (a factor {SCALE_RANGE:e} above the thesis's value), got {v:e}"),
                ));
            }
        }
        if !(self.min_pressure_fraction.is_finite() && (0.0..=1.0).contains(&self.min_pressure_fraction)) {
            return Err(FieldError::sentence(
                "min_pressure_fraction",
                format!("must be in [0, 1] (p_min ≤ p_max), got {}", self.min_pressure_fraction),
            ));
        }
        if !(self.min_length <= 1.0 && self.max_length.is_finite() && self.max_length >= 1.0) {
            return Err(FieldError::sentence(
                "min_length",
                format!(
                    "≤ 1 ≤ max_length required, got min_length {} and max_length {}",
                    self.min_length, self.max_length
                ),
            ));
        }
        if self.mass_side >= self.rest_length() {
            return Err(FieldError::sentence(
                "mass_side",
                format!(
                    "({}) must be smaller than the spacing of the masses ({:.3} for {} masses on radius {})",
                    self.mass_side,
                    self.rest_length(),
                    self.masses,
                    self.radius
                ),
            ));
        }
        if !(self.max_pressure().is_finite() && (self.n_r_t() / self.initial_area()).is_finite()) {
            return Err(FieldError::new(
                "gas_mass",
                format!(
                    "{} kg gives a pressure too large to represent (nRT = {})",
                    self.gas_mass,
                    self.n_r_t()
                ),
            ));
        }
        if !self.spring_control && !self.pressure_control {
            return Err(FieldError::sentence(
                "spring_control",
                "and pressure_control are both off: the brain would control nothing",
            ));
        }
        Ok(())
    }
}

/// How far (as a factor, either way) a physical constant may stray from the thesis's value: far
/// enough for any study of the model, near enough that masses, forces and pressures stay
/// representable and the step stays meaningful.
pub const SCALE_RANGE: f64 = 1e6;

/// Most masses a membrane may have (a brain sees each as a unit of a one-row grid).
pub const MAX_MASSES: usize = 200;
/// Molar mass of N₂ (kg/mol), the original code's 28.0134 g/mol.
pub const N2_MOLAR_MASS: f64 = 0.028_013_4;
/// Ideal gas constant (J/(mol·K)), as the original code (8.314…).
pub const GAS_CONSTANT: f64 = 8.314_462_618;
/// Kilograms of N₂ whose n = m/M equals the original's n = m·M for one of its mass units:
/// (28.0134)·(0.0280134) = 0.784750… .
pub const SI_GAS_MASS_PER_ORIGINAL_UNIT: f64 = 28.0134 * 0.028_013_4;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constants_far_from_the_thesis_scale_are_refused_naming_the_field() {
        for size in [PsaSize::Small, PsaSize::Medium, PsaSize::Large] {
            PsaParams::of_size(size).validate().unwrap();
        }
        let refused = |change: fn(&mut PsaParams), field: &str| {
            let mut p = PsaParams::of_size(PsaSize::Small);
            change(&mut p);
            let e = p.validate().unwrap_err().to_string();
            assert!(e.contains(field) && e.contains("thesis"), "{field}: {e}");
        };
        refused(|p| p.radius = 1e150, "radius");
        refused(|p| p.mass_side = 1e-300, "mass_side");
        refused(|p| p.density = 1e308, "density");
        refused(|p| p.temperature = 1e300, "temperature");
        refused(|p| p.friction = 1e300, "friction");
        let mut edge = PsaParams::of_size(PsaSize::Small);
        edge.density *= 0.99 * SCALE_RANGE;
        edge.validate().unwrap();
    }

    #[test]
    fn default_gas_equals_the_original_amount_and_gives_its_pressures() {
        let m = PsaParams::of_size(PsaSize::Medium);
        let original = PsaParams {
            gas_amount: GasAmount::TimesMolarMass,
            gas_mass: 75.0,
            molar_mass: N2_MOLAR_MASS,
            temperature: 288.20,
            ..m.clone()
        };
        assert!((m.moles() - original.moles()).abs() < 1e-9 * m.moles());
        // psa-model.md: medium agent, code units: p_max ≈ 35,612, p_min ≈ 7,122, p0 ≈ 29,340
        assert!(
            (original.max_pressure() - 35_612.0).abs() < 1.0,
            "{}",
            original.max_pressure()
        );
        assert!((original.min_pressure() - 7_122.0).abs() < 1.0);
        assert!((original.n_r_t() / original.initial_area() - 29_340.0).abs() < 5.0);
        assert!((m.initial_area() / (std::f64::consts::PI * 7.5 * 7.5) - 0.971).abs() < 1e-3);
    }

    #[test]
    fn bad_constants_name_their_field() {
        let bad = |f: fn(&mut PsaParams), field: &str| {
            let mut p = PsaParams::of_size(PsaSize::Small);
            f(&mut p);
            let e = p.validate().unwrap_err();
            assert_eq!(e.path, field, "{e}");
            assert!(e.to_string().starts_with(field), "{e}");
        };
        bad(|p| p.masses = 2, "masses");
        bad(|p| p.radius = 0.0, "radius");
        bad(|p| p.radius = -1.0, "radius");
        bad(|p| p.gas_mass = -1.0, "gas_mass");
        bad(|p| p.min_pressure_fraction = 1.5, "min_pressure_fraction");
        bad(|p| p.max_length = 0.5, "min_length");
        bad(|p| p.mass_side = 4.0, "mass_side");
        bad(
            |p| {
                p.spring_control = false;
                p.pressure_control = false
            },
            "spring_control",
        );
        for size in PsaSize::ALL {
            PsaParams::of_size(size).validate().unwrap();
        }
    }
}
