//! [`RingLayout`]: units on a closed chain (a membrane's springs), plus loose units.

use super::{Cell, UnitLayout};

/// `ring` units on a closed chain, each with 2 neighbours (direction 0: the previous unit,
/// direction 1: the next, wrapping around), followed by `loose` units without neighbours (a
/// pressure-based soft agent's pressure control). Unit i sits at cell (i, 0, 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RingLayout {
    ring: usize,
    loose: usize,
}

impl RingLayout {
    /// A ring of `ring` units followed by `loose` units.
    pub fn new(ring: usize, loose: usize) -> RingLayout {
        RingLayout { ring, loose }
    }
}

impl UnitLayout for RingLayout {
    fn units(&self) -> usize {
        self.ring + self.loose
    }

    fn cell(&self, unit: usize) -> Cell {
        [unit, 0, 0]
    }

    fn extent(&self) -> Cell {
        [self.units(), 1, 1]
    }

    fn directions(&self) -> usize {
        2
    }

    fn opposite(&self, direction: usize) -> usize {
        1 - direction
    }

    fn neighbour(&self, unit: usize, direction: usize) -> Option<usize> {
        // a ring of one has no neighbour but itself, which is none
        if unit >= self.ring || self.ring < 2 {
            return None;
        }
        Some(match direction {
            0 => (unit + self.ring - 1) % self.ring,
            _ => (unit + 1) % self.ring,
        })
    }

    fn unit_at(&self, [x, y, z]: Cell) -> Option<usize> {
        (x < self.units() && y == 0 && z == 0).then_some(x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ring_wraps_and_loose_units_have_no_neighbours() {
        let r = RingLayout::new(4, 1);
        assert_eq!(r.units(), 5);
        assert_eq!(r.neighbour(0, 0), Some(3));
        assert_eq!(r.neighbour(3, 1), Some(0));
        assert_eq!(r.neighbour(1, 1), Some(2));
        assert_eq!(r.neighbour(4, 0), None);
        assert_eq!(RingLayout::new(1, 0).neighbour(0, 1), None);
        assert_eq!(r.cell_text(2), "(2, 0)");
    }
}
