//! [`Grid3Layout`]: the voxels of a 3D grid body, each with 6 neighbours.

use super::{step, Cell, UnitLayout};

/// Grid offsets (dx, dy, dz) of the 6 directions, in this order: the 2D grid's N, E, S, W
/// (`GridLayout`'s, at the same z), then −z and +z. Opposite directions: 0↔2, 1↔3, 4↔5.
pub const DIRECTION_OFFSETS: [[isize; 3]; 6] = [[0, -1, 0], [1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, 0, -1], [0, 0, 1]];

/// The voxels of a W×H×D grid, units in grid order (x fastest, then y, then z), with their
/// neighbours in the 6 directions of [`DIRECTION_OFFSETS`]. A grid one voxel deep has the same
/// units and, in its first 4 directions, the same neighbours as the 2D [`super::GridLayout`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Grid3Layout {
    extent: Cell,
    cells: Vec<Cell>,
    /// Per grid cell ((z·H + y)·W + x): its unit.
    unit_of: Vec<Option<usize>>,
}

impl Grid3Layout {
    /// The voxels of the cells (x, y, z) of a box of size `extent` for which `filled` holds.
    pub fn from_fn(extent: Cell, filled: impl Fn(usize, usize, usize) -> bool) -> Grid3Layout {
        let [w, h, d] = extent;
        let mut cells = Vec::new();
        let mut unit_of = vec![None; w * h * d];
        for z in 0..d {
            for y in 0..h {
                for x in 0..w {
                    if filled(x, y, z) {
                        unit_of[(z * h + y) * w + x] = Some(cells.len());
                        cells.push([x, y, z]);
                    }
                }
            }
        }
        Grid3Layout { extent, cells, unit_of }
    }
}

impl UnitLayout for Grid3Layout {
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
        6
    }

    fn opposite(&self, direction: usize) -> usize {
        match direction {
            4 => 5,
            5 => 4,
            d => (d + 2) % 4,
        }
    }

    fn neighbour(&self, unit: usize, direction: usize) -> Option<usize> {
        self.unit_at(step(self.cells[unit], DIRECTION_OFFSETS[direction], self.extent)?)
    }

    fn unit_at(&self, [x, y, z]: Cell) -> Option<usize> {
        let [w, h, d] = self.extent;
        if x < w && y < h && z < d {
            self.unit_of[(z * h + y) * w + x]
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::GridLayout;
    use vsrlab_body::Morphology;

    #[test]
    fn a_cube_has_six_neighbours_at_its_centre() {
        let cube = Grid3Layout::from_fn([3, 3, 3], |_, _, _| true);
        assert_eq!(cube.units(), 27);
        let centre = cube.unit_at([1, 1, 1]).unwrap();
        assert_eq!(centre, 13);
        let n: Vec<_> = (0..6).map(|d| cube.neighbour(centre, d)).collect();
        assert_eq!(n, [Some(10), Some(14), Some(16), Some(12), Some(4), Some(22)]);
        // a corner has 3
        assert_eq!((0..6).filter(|&d| cube.neighbour(0, d).is_some()).count(), 3);
        assert_eq!(cube.cell_text(centre), "(1, 1, 1)");
        assert_eq!(cube.slot(22), 22);
    }

    #[test]
    fn one_voxel_deep_it_is_the_2d_grid() {
        let m = Morphology::named("biped-4x3").unwrap();
        let flat = Grid3Layout::from_fn([4, 3, 1], |x, y, _| m.has(x, y));
        let grid = GridLayout::new(&m);
        // the planar directions are the 2D grid's offsets
        for (d, &(dx, dy)) in crate::layout::grid::DIRECTION_OFFSETS.iter().enumerate() {
            assert_eq!(DIRECTION_OFFSETS[d], [dx, dy, 0]);
        }
        assert_eq!(flat.units(), grid.units());
        for u in 0..grid.units() {
            assert_eq!(flat.cell(u), grid.cell(u));
            assert_eq!(flat.slot(u), grid.slot(u));
            for d in 0..4 {
                assert_eq!(flat.neighbour(u, d), grid.neighbour(u, d));
            }
            assert_eq!(flat.neighbour(u, 4), None);
            assert_eq!(flat.neighbour(u, 5), None);
        }
    }
}
