//! [`GridLayout`]: the voxels of a 2D grid body, each with 4 neighbours.

use super::{Cell, Grid3Layout, UnitLayout};
use vsrlab_body::Morphology;

/// Grid offsets (dx, dy) of the directions N, E, S, W, in this order. Since y = 0 is the bottom
/// row, "N" is physically the voxel below and "S" the one above (2D-VSR-Sim's index semantics).
pub const DIRECTION_OFFSETS: [(isize, isize); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

/// The voxels of a W×H grid (units in grid order: row-major from the bottom row) with their
/// neighbours in directions N, E, S, W ([`DIRECTION_OFFSETS`]); opposite directions are two apart.
/// It is a [`Grid3Layout`] one voxel deep whose first 4 directions are these, without the two
/// along z.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GridLayout {
    grid: Grid3Layout,
}

impl GridLayout {
    /// The layout of a morphology's voxels.
    pub fn new(morphology: &Morphology) -> GridLayout {
        let extent = [morphology.width(), morphology.height(), 1];
        GridLayout {
            grid: Grid3Layout::from_fn(extent, |x, y, _| morphology.has(x, y)),
        }
    }
}

impl UnitLayout for GridLayout {
    fn units(&self) -> usize {
        self.grid.units()
    }

    fn cell(&self, unit: usize) -> Cell {
        self.grid.cell(unit)
    }

    fn extent(&self) -> Cell {
        self.grid.extent()
    }

    fn directions(&self) -> usize {
        4
    }

    fn opposite(&self, direction: usize) -> usize {
        (direction + 2) % 4
    }

    fn neighbour(&self, unit: usize, direction: usize) -> Option<usize> {
        // the 3D grid's first four directions are N, E, S, W in the plane
        self.grid.neighbour(unit, direction)
    }

    fn unit_at(&self, cell: Cell) -> Option<usize> {
        self.grid.unit_at(cell)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbours_follow_the_original_direction_order() {
        // #.#
        // ###    units in grid order: 0 (1,0) on the bottom row, 1 (0,1), 2 (1,1), 3 (2,1), …
        // .#.
        let m = Morphology::from_rows(&["#.#", "###", ".#."]).unwrap();
        let g = GridLayout::new(&m);
        assert_eq!(g.units(), 6);
        assert_eq!(g.cell(0), [1, 0, 0]);
        // the centre voxel (1, 1) is unit 2: N is below (unit 0), E unit 3, S nothing, W unit 1
        assert_eq!(g.unit_at([1, 1, 0]), Some(2));
        let n: Vec<_> = (0..4).map(|d| g.neighbour(2, d)).collect();
        assert_eq!(n, [Some(0), Some(3), None, Some(1)]);
        // the offsets say the same
        for (d, (dx, dy)) in DIRECTION_OFFSETS.iter().enumerate() {
            let at = [(1 + dx) as usize, (1 + dy) as usize, 0];
            assert_eq!(g.neighbour(2, d), g.unit_at(at), "direction {d}");
        }
        assert_eq!(g.slot(2), 4);
        assert_eq!(g.slots(), 9);
        assert_eq!(g.cell_text(5), "(2, 2)");
    }
}
