//! A material grid: EvoGym's description of an object (a robot or a piece of terrain), cells of
//! [`Material`] plus which 4-neighbours are connected.
//!
//! Rows run from the top (row 0) down, as in EvoGym's `structure` arrays (`evogym/world.py:297`)
//! and in the text form `"33333/31113/..."`. Two present neighbours share their side only when
//! they are connected; by default every adjacent pair is (`get_full_connectivity`,
//! `evogym/utils.py:240`). What EvoGym asks of a robot (`sample_robot`, `evogym/utils.py:135`):
//! connected (`is_connected`, `:190`) and with an actuator (`has_actuator`, `:224`); of any object
//! (`ObjectCreator.cpp:520-532`): one connected component through its connections.

use super::materials::Material;
use vsrlab_field::FieldError;

/// Largest width or height of any object, in cells (EvoGym has no limit; this one keeps a wrong
/// file from allocating without bound).
pub const MAX_SIDE: usize = 1024;
/// Largest width or height of a robot, in cells (EvoGym's benchmarks use 5 × 5).
pub const MAX_ROBOT_SIDE: usize = 64;

/// Cells of materials with their connections, row 0 at the top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MaterialGrid {
    width: usize,
    height: usize,
    cells: Vec<Material>,
    /// Cell `(x, y)` is connected to `(x + 1, y)`.
    right: Vec<bool>,
    /// Cell `(x, y)` is connected to `(x, y + 1)` (the cell below).
    down: Vec<bool>,
}

impl MaterialGrid {
    /// A `width × height` grid of `cells` (row-major, top row first) with every adjacent pair of
    /// present cells connected. Errors name `cells` or the size.
    pub fn new(width: usize, height: usize, cells: Vec<Material>) -> Result<MaterialGrid, FieldError> {
        check_size(width, height, MAX_SIDE)?;
        if cells.len() != width * height {
            return Err(FieldError::new(
                "cells",
                format!("{} cells for a {width} × {height} grid", cells.len()),
            ));
        }
        let mut grid = MaterialGrid::unconnected(width, height, cells);
        grid.connect_all();
        Ok(grid)
    }

    /// A grid with no connections.
    pub(crate) fn unconnected(width: usize, height: usize, cells: Vec<Material>) -> MaterialGrid {
        MaterialGrid {
            width,
            height,
            cells,
            right: vec![false; width * height],
            down: vec![false; width * height],
        }
    }

    /// Reads the text form: rows joined by `/`, top row first, one character per cell (`0`–`5`,
    /// `.` for empty), all rows of the same length; fully connected. Errors name `rows[i]`.
    pub fn from_rows(text: &str) -> Result<MaterialGrid, FieldError> {
        let rows: Vec<&str> = text.trim().split('/').collect();
        let width = rows[0].chars().count();
        let mut cells = Vec::with_capacity(width * rows.len());
        for (i, row) in rows.iter().enumerate() {
            let at = format!("rows[{i}]");
            if row.chars().count() != width {
                return Err(FieldError::new(
                    at,
                    format!("{} cells where row 0 has {width}", row.chars().count()),
                ));
            }
            for (j, c) in row.chars().enumerate() {
                let m = Material::from_char(c).ok_or_else(|| {
                    FieldError::new(&at, format!("'{c}' at column {j} is no material: expected 0-5 or '.'"))
                })?;
                cells.push(m);
            }
        }
        check_size(width, rows.len(), MAX_SIDE).map_err(|e| e.at("rows"))?;
        MaterialGrid::new(width, rows.len(), cells)
    }

    /// The text form ([`MaterialGrid::from_rows`] reads it back; connections are not written).
    pub fn to_rows(&self) -> String {
        (0..self.height)
            .map(|y| {
                (0..self.width)
                    .map(|x| char::from(b'0' + self.at(x, y).code()))
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("/")
    }

    /// Width in cells.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in cells.
    pub fn height(&self) -> usize {
        self.height
    }

    /// The material at column `x`, row `y` (row 0 at the top); empty outside the grid.
    pub fn at(&self, x: usize, y: usize) -> Material {
        if x < self.width && y < self.height {
            self.cells[y * self.width + x]
        } else {
            Material::Empty
        }
    }

    /// Whether `(x, y)` and `(x + 1, y)` are connected.
    pub fn connected_right(&self, x: usize, y: usize) -> bool {
        x + 1 < self.width && y < self.height && self.right[y * self.width + x]
    }

    /// Whether `(x, y)` and `(x, y + 1)` (below) are connected.
    pub fn connected_down(&self, x: usize, y: usize) -> bool {
        y + 1 < self.height && x < self.width && self.down[y * self.width + x]
    }

    /// Whether `(x, y)` is connected to its left neighbour.
    pub fn connected_left(&self, x: usize, y: usize) -> bool {
        x > 0 && self.connected_right(x - 1, y)
    }

    /// Whether `(x, y)` is connected to the cell above it.
    pub fn connected_up(&self, x: usize, y: usize) -> bool {
        y > 0 && self.connected_down(x, y - 1)
    }

    /// Connects two present 4-adjacent cells; refuses anything else.
    pub fn connect(&mut self, a: (usize, usize), b: (usize, usize)) -> Result<(), ConnectionError> {
        let (a, b) = if (a.1, a.0) <= (b.1, b.0) { (a, b) } else { (b, a) };
        if !self.at(a.0, a.1).is_present() || !self.at(b.0, b.1).is_present() {
            return Err(ConnectionError::EmptyCell(a, b));
        }
        let i = a.1 * self.width + a.0;
        if a.1 == b.1 && a.0 + 1 == b.0 {
            self.right[i] = true;
        } else if a.0 == b.0 && a.1 + 1 == b.1 {
            self.down[i] = true;
        } else {
            return Err(ConnectionError::NotNeighbours(a, b));
        }
        Ok(())
    }

    fn connect_all(&mut self) {
        for y in 0..self.height {
            for x in 0..self.width {
                let here = self.at(x, y).is_present();
                self.right[y * self.width + x] = here && self.at(x + 1, y).is_present() && x + 1 < self.width;
                self.down[y * self.width + x] = here && self.at(x, y + 1).is_present() && y + 1 < self.height;
            }
        }
    }

    /// Present cells, row-major from the top: EvoGym's order of cells (and of actuators).
    pub fn present(&self) -> impl Iterator<Item = (usize, usize, Material)> + '_ {
        (0..self.height)
            .flat_map(move |y| (0..self.width).map(move |x| (x, y, self.at(x, y))))
            .filter(|c| c.2.is_present())
    }

    /// Number of present cells.
    pub fn cell_count(&self) -> usize {
        self.cells.iter().filter(|m| m.is_present()).count()
    }

    /// Number of actuator cells: the robot's number of actions.
    pub fn actuator_count(&self) -> usize {
        self.cells.iter().filter(|m| m.is_actuator()).count()
    }

    /// Whether the present cells form one component through their connections (false when there
    /// is none).
    pub fn is_connected(&self) -> bool {
        let Some((x0, y0, _)) = self.present().next() else {
            return false;
        };
        let mut seen = vec![false; self.cells.len()];
        let mut stack = vec![(x0, y0)];
        seen[y0 * self.width + x0] = true;
        let mut reached = 1;
        while let Some((x, y)) = stack.pop() {
            for (n, linked) in self.neighbours(x, y) {
                if linked && !seen[n.1 * self.width + n.0] {
                    seen[n.1 * self.width + n.0] = true;
                    reached += 1;
                    stack.push(n);
                }
            }
        }
        reached == self.cell_count()
    }

    fn neighbours(&self, x: usize, y: usize) -> [((usize, usize), bool); 4] {
        [
            ((x + 1, y), self.connected_right(x, y)),
            ((x, y + 1), self.connected_down(x, y)),
            ((x.wrapping_sub(1), y), self.connected_left(x, y)),
            ((x, y.wrapping_sub(1)), self.connected_up(x, y)),
        ]
    }

    /// Checks what EvoGym asks of any object: at least one cell, one connected component.
    pub fn validate_object(&self) -> Result<(), FieldError> {
        if self.cell_count() == 0 {
            return Err(FieldError::new("cells", "no cell: an object needs at least one"));
        }
        if !self.is_connected() {
            return Err(FieldError::new(
                "cells",
                "not connected: every cell must be reachable through connections",
            ));
        }
        Ok(())
    }

    /// Checks what EvoGym asks of a robot: a connected object of at most
    /// [`MAX_ROBOT_SIDE`] per side with at least one actuator (code 3 or 4) and no fixed cell.
    pub fn validate_robot(&self) -> Result<(), FieldError> {
        check_size(self.width, self.height, MAX_ROBOT_SIDE)?;
        self.validate_object()?;
        if self.actuator_count() == 0 {
            return Err(FieldError::new(
                "cells",
                "no actuator: a robot needs a cell of code 3 or 4",
            ));
        }
        if self.cells.contains(&Material::Fixed) {
            return Err(FieldError::new("cells", "a robot cannot have fixed cells (code 5)"));
        }
        Ok(())
    }
}

/// Refuses empty grids and sides above `max`, naming `width` or `height`.
fn check_size(width: usize, height: usize, max: usize) -> Result<(), FieldError> {
    for (name, side) in [("width", width), ("height", height)] {
        if side == 0 || side > max {
            return Err(FieldError::sentence(
                name,
                format!("must be between 1 and {max}, not {side}"),
            ));
        }
    }
    Ok(())
}

/// Why two cells of a [`MaterialGrid`] cannot be connected (cells as `(x, y)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ConnectionError {
    /// One of the two cells is empty.
    #[error("connection {0:?}–{1:?} involves an empty cell")]
    EmptyCell((usize, usize), (usize, usize)),
    /// The cells do not share a side.
    #[error("cells {0:?} and {1:?} are not 4-neighbours")]
    NotNeighbours((usize, usize), (usize, usize)),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_rows_read_top_row_first_and_write_back() {
        let g = MaterialGrid::from_rows("30/12").unwrap();
        assert_eq!((g.width(), g.height()), (2, 2));
        assert_eq!(g.at(0, 0), Material::HorizontalActuator);
        assert_eq!(g.at(1, 0), Material::Empty);
        assert_eq!(g.at(1, 1), Material::Soft);
        assert!(g.connected_down(0, 0) && g.connected_right(0, 1));
        assert!(!g.connected_right(0, 0), "no connection to an empty cell");
        assert_eq!(g.to_rows(), "30/12");
        assert_eq!(MaterialGrid::from_rows("3./12").unwrap().to_rows(), "30/12");
    }

    #[test]
    fn wrong_text_is_refused_naming_the_row() {
        let e = MaterialGrid::from_rows("333/33").unwrap_err();
        assert_eq!(e.path, "rows[1]");
        let e = MaterialGrid::from_rows("333/3x3").unwrap_err();
        assert_eq!(e.path, "rows[1]");
        assert!(e.message.contains("'x'"), "{e}");
        let e = MaterialGrid::from_rows("").unwrap_err();
        assert_eq!(e.path, "rows.width");
    }

    #[test]
    fn robots_must_be_connected_have_an_actuator_and_no_fixed_cell() {
        assert!(MaterialGrid::from_rows("313/222").unwrap().validate_robot().is_ok());
        let e = MaterialGrid::from_rows("3.3").unwrap().validate_robot().unwrap_err();
        assert_eq!(e.path, "cells");
        assert!(e.message.contains("not connected"), "{e}");
        // Diagonal neighbours are not connected (4-neighbourhood, utils.py:182-188).
        let e = MaterialGrid::from_rows("3./.3").unwrap().validate_robot().unwrap_err();
        assert!(e.message.contains("not connected"), "{e}");
        let e = MaterialGrid::from_rows("12/21").unwrap().validate_robot().unwrap_err();
        assert!(e.message.contains("actuator"), "{e}");
        let e = MaterialGrid::from_rows("35").unwrap().validate_robot().unwrap_err();
        assert!(e.message.contains("fixed"), "{e}");
        let e = MaterialGrid::from_rows("000").unwrap().validate_robot().unwrap_err();
        assert!(e.message.contains("no cell"), "{e}");
        let wide = "3".repeat(MAX_ROBOT_SIDE + 1);
        let e = MaterialGrid::from_rows(&wide).unwrap().validate_robot().unwrap_err();
        assert_eq!(e.path, "width");
    }

    #[test]
    fn connections_decide_connectivity() {
        let mut g = MaterialGrid::unconnected(2, 1, vec![Material::Rigid, Material::HorizontalActuator]);
        assert!(!g.is_connected());
        assert!(g.connect((1, 0), (0, 0)).is_ok());
        assert!(g.is_connected() && g.connected_right(0, 0) && g.connected_left(1, 0));
        assert!(g.connect((0, 0), (0, 0)).is_err());
        let mut g = MaterialGrid::unconnected(
            2,
            2,
            vec![Material::Rigid, Material::Empty, Material::Soft, Material::Soft],
        );
        assert_eq!(
            g.connect((0, 0), (1, 1)),
            Err(ConnectionError::NotNeighbours((0, 0), (1, 1)))
        );
        assert!(g
            .connect((0, 0), (1, 1))
            .unwrap_err()
            .to_string()
            .contains("4-neighbours"));
        assert!(g.connect((0, 0), (1, 0)).unwrap_err().to_string().contains("empty"));
        assert!(g.connect((0, 1), (1, 1)).is_ok() && g.connect((0, 0), (0, 1)).is_ok());
        assert!(g.is_connected() && g.connected_up(0, 1));
    }
}
