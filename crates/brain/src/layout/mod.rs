//! Unit layouts: how a body's units are arranged, as a brain sees them.
//!
//! A brain is built for a [`crate::BrainShape`]: the number of units (voxels, membrane springs,
//! links), the readings of each, and a [`UnitLayout`] that answers where each unit sits and which
//! unit is its neighbour in each direction. Brains ask the layout, never the body, so one brain
//! works on every robot kind whose layout answers its questions: a distributed MLP needs
//! neighbours, a phase brain positions, an MLP only the unit count.
//!
//! Layouts here: [`GridLayout`] (a 2D voxel grid, 4 neighbours), [`Grid3Layout`] (a 3D voxel
//! grid, 6 neighbours), [`RingLayout`] (a closed chain, 2 neighbours, plus loose units) and
//! [`UnitSet`] (units without neighbours). A new arrangement is one more type implementing
//! [`UnitLayout`].

pub mod grid;
pub mod grid3;
mod ring;
mod set;

pub use grid::GridLayout;
pub use grid3::Grid3Layout;
pub use ring::RingLayout;
pub use set::UnitSet;

use std::fmt::Debug;

/// Integer coordinates (x, y, z) of a unit; planar layouts have z = 0, chains y = z = 0.
pub type Cell = [usize; 3];

/// How the units of a body are arranged: positions and neighbours, in unit order.
///
/// Unit order is the order of the body's actuators and of the brain's readings and outputs.
pub trait UnitLayout: Debug + Send + Sync {
    /// Number of units.
    fn units(&self) -> usize;

    /// The cell of unit `unit`, within [`UnitLayout::extent`].
    fn cell(&self, unit: usize) -> Cell;

    /// Size (x, y, z) of the box of cells the units sit in: W×H×D (D = 1 when planar).
    fn extent(&self) -> Cell;

    /// Number of neighbour directions, the same for every unit (4 on a 2D grid, 6 on a 3D grid,
    /// 2 on a ring, 0 for a set).
    fn directions(&self) -> usize;

    /// The direction opposite to `direction`: a signal sent towards a neighbour arrives from
    /// this direction.
    fn opposite(&self, direction: usize) -> usize;

    /// The unit next to `unit` in `direction`, if there is one.
    fn neighbour(&self, unit: usize, direction: usize) -> Option<usize>;

    /// The unit at `cell`, if any. Default: a search over the units.
    fn unit_at(&self, cell: Cell) -> Option<usize> {
        (0..self.units()).find(|&u| self.cell(u) == cell)
    }

    /// Index of the unit's cell in the box of [`UnitLayout::extent`], x fastest then y then z
    /// (a 2D grid: y·W + x): what per-cell parameters are indexed by.
    fn slot(&self, unit: usize) -> usize {
        let [x, y, z] = self.cell(unit);
        let [w, h, _] = self.extent();
        (z * h + y) * w + x
    }

    /// Number of cells in the box of [`UnitLayout::extent`] (W·H·D), saturating.
    fn slots(&self) -> usize {
        let [w, h, d] = self.extent();
        w.saturating_mul(h).saturating_mul(d)
    }

    /// The unit's cell as text for messages: "(x, y)" when planar, "(x, y, z)" otherwise.
    fn cell_text(&self, unit: usize) -> String {
        let [x, y, z] = self.cell(unit);
        if self.extent()[2] <= 1 {
            format!("({x}, {y})")
        } else {
            format!("({x}, {y}, {z})")
        }
    }
}

/// The neighbour of `cell` one step along `offset` inside a box of size `extent`, if inside.
pub(crate) fn step(cell: Cell, offset: [isize; 3], extent: Cell) -> Option<Cell> {
    let mut out = [0; 3];
    for axis in 0..3 {
        let c = cell[axis].checked_add_signed(offset[axis])?;
        if c >= extent[axis] {
            return None;
        }
        out[axis] = c;
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_stay_inside_the_box() {
        let extent = [3, 2, 1];
        assert_eq!(step([0, 0, 0], [1, 0, 0], extent), Some([1, 0, 0]));
        assert_eq!(step([0, 0, 0], [-1, 0, 0], extent), None);
        assert_eq!(step([2, 1, 0], [1, 0, 0], extent), None);
        assert_eq!(step([2, 1, 0], [0, 1, 0], extent), None);
        assert_eq!(step([2, 1, 0], [0, 0, 1], extent), None);
        assert_eq!(step([2, 1, 0], [0, -1, 0], extent), Some([2, 0, 0]));
    }

    /// Every layout's neighbours are symmetric: b is a's neighbour in d iff a is b's in opposite(d).
    fn assert_symmetric(layout: &dyn UnitLayout) {
        for a in 0..layout.units() {
            for d in 0..layout.directions() {
                if let Some(b) = layout.neighbour(a, d) {
                    assert_eq!(
                        layout.neighbour(b, layout.opposite(d)),
                        Some(a),
                        "{layout:?}: {a} -{d}-> {b}"
                    );
                }
                assert_eq!(layout.opposite(layout.opposite(d)), d);
            }
            assert_eq!(layout.unit_at(layout.cell(a)), Some(a));
            assert!(layout.slot(a) < layout.slots());
        }
    }

    #[test]
    fn every_layout_has_symmetric_neighbours_and_unique_cells() {
        let biped = vsrlab_body::Morphology::named("biped-4x3").unwrap();
        assert_symmetric(&GridLayout::new(&biped));
        assert_symmetric(&Grid3Layout::from_fn([3, 2, 4], |x, y, z| (x + y + z) % 3 != 1));
        assert_symmetric(&RingLayout::new(7, 2));
        assert_symmetric(&RingLayout::new(2, 0));
        assert_symmetric(&UnitSet::new(5));
    }
}
