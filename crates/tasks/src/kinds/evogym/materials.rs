//! EvoGym's voxel materials: their codes and spring constants.
//!
//! Sources (EvoGym commit `f63c649`): codes `evogym/utils.py:8-15`; stiffnesses
//! `evogym/simulator/SimulatorCPP/ObjectCreator.h:40-47`; which cell sets which constant
//! `ObjectCreator.cpp:443-490`.

use serde::{Deserialize, Serialize};

/// Side-spring stiffness of rigid (and fixed) cells: 3e8 / 3.5.
pub const RIGID_SIDE: f64 = 300_000_000.0 / 3.5;
/// Side-spring stiffness of actuator cells: 3e8 / 5.
pub const ACTUATOR_SIDE: f64 = 300_000_000.0 / 5.0;
/// Side-spring stiffness of soft cells: 3e8 / 6.
pub const SOFT_SIDE: f64 = 300_000_000.0 / 6.0;

/// One cell of a material grid, with EvoGym's numeric code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Material {
    /// No cell (code 0).
    Empty,
    /// Rigid (code 1): stiff sides whose lengths are also held within ±3 %.
    Rigid,
    /// Soft (code 2): the softest sides, diagonals a quarter of them.
    Soft,
    /// Horizontal actuator (code 3): drives its top and bottom sides.
    HorizontalActuator,
    /// Vertical actuator (code 4): drives its left and right sides.
    VerticalActuator,
    /// Fixed (code 5): rigid constants, its four corners never move (terrain).
    Fixed,
}

impl Material {
    /// Every material, in code order.
    pub const ALL: [Material; 6] = [
        Material::Empty,
        Material::Rigid,
        Material::Soft,
        Material::HorizontalActuator,
        Material::VerticalActuator,
        Material::Fixed,
    ];

    /// The material with EvoGym's code `code` (0 to 5), if any.
    pub fn from_code(code: u64) -> Option<Material> {
        Material::ALL.get(usize::try_from(code).ok()?).copied()
    }

    /// EvoGym's code.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// The material of a text-grid character: a digit `0`–`5`, or `.` for empty.
    pub fn from_char(c: char) -> Option<Material> {
        match c {
            '.' => Some(Material::Empty),
            _ => Material::from_code(u64::from(c.to_digit(10)?)),
        }
    }

    /// Whether the cell exists.
    pub fn is_present(self) -> bool {
        self != Material::Empty
    }

    /// Whether the cell is driven by an action.
    pub fn is_actuator(self) -> bool {
        matches!(self, Material::HorizontalActuator | Material::VerticalActuator)
    }

    /// Whether the cell gets the tight ±3 % limits on its sides (rigid only, not fixed:
    /// `PhysicsEngine.cpp:680`).
    pub fn has_tight_limits(self) -> bool {
        self == Material::Rigid
    }

    /// The stiffness this cell writes on its four sides, or `None` when it leaves them as
    /// created (rigid and fixed cells: sides are created with the rigid constant and only soft
    /// and actuator cells overwrite them).
    pub fn side_override(self) -> Option<f64> {
        match self {
            Material::Soft => Some(SOFT_SIDE),
            Material::HorizontalActuator | Material::VerticalActuator => Some(ACTUATOR_SIDE),
            _ => None,
        }
    }

    /// Stiffness of the cell's two diagonal springs: half the side constant for rigid, fixed and
    /// actuator cells, a quarter for soft ones.
    pub fn diagonal_stiffness(self) -> f64 {
        match self {
            Material::Soft => SOFT_SIDE / 4.0,
            Material::HorizontalActuator | Material::VerticalActuator => ACTUATOR_SIDE / 2.0,
            _ => RIGID_SIDE / 2.0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip_and_out_of_range_codes_are_refused() {
        for (i, m) in Material::ALL.iter().enumerate() {
            assert_eq!(m.code() as usize, i);
            assert_eq!(Material::from_code(i as u64), Some(*m));
        }
        assert_eq!(Material::from_code(6), None);
        assert_eq!(Material::from_char('.'), Some(Material::Empty));
        assert_eq!(Material::from_char('3'), Some(Material::HorizontalActuator));
        assert_eq!(Material::from_char('7'), None);
        assert_eq!(Material::from_char('#'), None);
    }

    #[test]
    fn constants_are_evogyms() {
        // 3e8 / 3.5 = 85 714 285.71…, 3e8 / 5 = 6e7, 3e8 / 6 = 5e7.
        assert!((RIGID_SIDE - 85_714_285.714_285_7).abs() < 1e-3);
        assert_eq!(ACTUATOR_SIDE, 6.0e7);
        assert_eq!(SOFT_SIDE, 5.0e7);
        assert_eq!(Material::Soft.diagonal_stiffness(), 1.25e7);
        assert_eq!(Material::VerticalActuator.diagonal_stiffness(), 3.0e7);
        assert_eq!(Material::Fixed.diagonal_stiffness(), RIGID_SIDE / 2.0);
        assert_eq!(Material::Rigid.side_override(), None);
    }
}
