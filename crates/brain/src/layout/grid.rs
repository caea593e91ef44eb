//! [`GridLayout`]: the voxels of a 2D grid body, each with 4 neighbours.

use super::{step, Cell, UnitLayout};
use vsrlab_body::Morphology;

/// Grid offsets (dx, dy) of the directions N, E, S, W, in this order. Since y = 0 is the bottom
/// row, "N" is physically the voxel below and "S" the one above (2D-VSR-Sim's index semantics).
pub const DIRECTION_OFFSETS: [(isize, isize); 4] = [(0, -1), (1, 0), (0, 1), (-1, 0)];

/// The voxels of a W×H grid (units in grid order: row-major from the bottom row) with their
/// neighbours in directions N, E, S, W ([`DIRECTION_OFFSETS`]); opposite directions are two apart.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GridLayout {
    extent: Cell,
    cells: Vec<Cell>,
    /// Per grid cell (y·W + x): its unit.
    unit_of: Vec<Option<usize>>,
}

impl GridLayout {
    /// The layout of a morphology's voxels.
    pub fn new(morphology: &Morphology) -> GridLayout {
        let (w, h) = (morphology.width(), morphology.height());
        let cells: Vec<Cell> = morphology.voxels().map(|(x, y)| [x, y, 0]).collect();
        let mut unit_of = vec![None; w * h];
        for (u, &[x, y, _]) in cells.iter().enumerate() {
            unit_of[y * w + x] = Some(u);
        }
        GridLayout {
            extent: [w, h, 1],
            cells,
            unit_of,
        }
    }
}

impl UnitLayout for GridLayout {
    fn units(&self) -> usize {
        self.cells.len()
    }

    fn cell(&self, unit: usize) -> Cell {
        self.cells[unit]
    }

    fn extent(&self) -> Cell {
        self.extent
    }

    fn directions(&self) -> usize {
        4
    }

    fn opposite(&self, direction: usize) -> usize {
        (direction + 2) % 4
    }

    fn neighbour(&self, unit: usize, direction: usize) -> Option<usize> {
        let (dx, dy) = DIRECTION_OFFSETS[direction];
        self.unit_at(step(self.cells[unit], [dx, dy, 0], self.extent)?)
    }

    fn unit_at(&self, [x, y, z]: Cell) -> Option<usize> {
        let [w, h, _] = self.extent;
        if x < w && y < h && z == 0 {
            self.unit_of[y * w + x]
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn neighbours_follow_the_original_direction_order() {
        // #.#
        // ###    units in grid order: 0 (0,0)  1 (1,0)  2 (2,0) on the bottom row …
        // .#.
        let m = Morphology::from_rows(&["#.#", "###", ".#."]).unwrap();
        let g = GridLayout::new(&m);
        assert_eq!(g.units(), 6);
        assert_eq!(g.cell(0), [1, 0, 0]);
        // the centre voxel (1, 1) is unit 2: N is below (unit 0), E unit 3, S nothing, W unit 1
        assert_eq!(g.unit_at([1, 1, 0]), Some(2));
        let n: Vec<_> = (0..4).map(|d| g.neighbour(2, d)).collect();
        assert_eq!(n, [Some(0), Some(3), None, Some(1)]);
        assert_eq!(g.slot(2), 4);
        assert_eq!(g.slots(), 9);
        assert_eq!(g.cell_text(5), "(2, 2)");
    }
}
