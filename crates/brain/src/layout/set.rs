//! [`UnitSet`]: units with no arrangement.

use super::{Cell, UnitLayout};

/// Units without neighbours, unit i at cell (i, 0, 0): for brains that need only the unit count
/// (a centralised MLP) on a body with no structure to speak of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UnitSet {
    units: usize,
}

impl UnitSet {
    /// A set of `units` units.
    pub fn new(units: usize) -> UnitSet {
        UnitSet { units }
    }
}

impl UnitLayout for UnitSet {
    fn units(&self) -> usize {
        self.units
    }

    fn cell(&self, unit: usize) -> Cell {
        [unit, 0, 0]
    }

    fn extent(&self) -> Cell {
        [self.units, 1, 1]
    }

    fn directions(&self) -> usize {
        0
    }

    fn opposite(&self, direction: usize) -> usize {
        direction
    }

    fn neighbour(&self, _unit: usize, _direction: usize) -> Option<usize> {
        None
    }
}
