//! [`BodyGrid3`]: which cells of a W×H×D box hold a voxel, with its text form (layers bottom
//! first joined by `|`, each layer's rows joined by `/`, `#` a voxel and `.` an empty cell: row
//! `y`, character `x`) and named shapes.

use std::fmt;
use vsrlab_brain::Grid3Layout;
use vsrlab_field::FieldError;

/// Longest side of a 3D body (cells); 32³ voxels is far beyond any published study.
pub const MAX_SIDE: usize = 32;

/// The cells of a 3D body: x fastest, then y, then z (z up).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BodyGrid3 {
    extent: [usize; 3],
    filled: Vec<bool>,
}

/// Named shapes and their text forms.
const SHAPES: &[(&str, &str)] = &[
    // a 4×3×2 slab on four one-voxel legs: the walker of `--example walker3d` and bench/voxelyze
    ("quadruped", "#..#/..../#..#|####/####/####|####/####/####"),
    ("cube-2", "##/##|##/##"),
    ("worm", "######|######"),
    // the affordance study's three (thesis §5.1.3.1; Voxcraft-python's `_create_fixed_world`),
    // one layer each: a 5×5 square, a 9×9 plus of four limbs, a 6×6 double cross
    ("flatworm", "#####/#####/#####/#####/#####"),
    (
        "starfish",
        "....#..../....#..../....#..../....#..../#########/....#..../....#..../....#..../....#....",
    ),
    ("gecko", ".#..#./######/.#..#./.#..#./######/.#..#."),
];

impl BodyGrid3 {
    /// A grid from its text form, a named shape (`quadruped`, `cube-2`, `worm`, and the affordance
    /// study's `flatworm`, `starfish`, `gecko`) or a box
    /// `box-WxHxD`; the error says what is wrong (the caller names the field).
    pub fn parse(text: &str) -> Result<BodyGrid3, FieldError> {
        let text = text.trim();
        if let Some(&(_, form)) = SHAPES.iter().find(|(name, _)| *name == text) {
            return BodyGrid3::parse(form);
        }
        if let Some(size) = text.strip_prefix("box-") {
            return BodyGrid3::parse_box(size);
        }
        let layers: Vec<Vec<&str>> = text.split('|').map(|l| l.split('/').collect()).collect();
        let (d, h) = (layers.len(), layers[0].len());
        let w = layers[0][0].chars().count();
        let mut filled = Vec::with_capacity(w * h * d);
        for (z, layer) in layers.iter().enumerate() {
            if layer.len() != h {
                return Err(FieldError::message(format!(
                    "layer {z} has {} rows, layer 0 has {h}: every layer has as many rows",
                    layer.len()
                )));
            }
            for (y, row) in layer.iter().enumerate() {
                if row.chars().count() != w {
                    return Err(FieldError::message(format!(
                        "row {y} of layer {z} is {} cells wide, row 0 of layer 0 is {w}: every row is as wide",
                        row.chars().count()
                    )));
                }
                for c in row.chars() {
                    filled.push(match c {
                        '#' => true,
                        '.' => false,
                        other => {
                            return Err(FieldError::message(format!(
                                "'{other}' in row {y} of layer {z}: cells are '#' (voxel) or '.' (empty); layers are joined by '|', rows by '/'; or a shape: {}, box-WxHxD",
                                shape_names()
                            )))
                        }
                    });
                }
            }
        }
        BodyGrid3::new([w, h, d], filled)
    }

    fn parse_box(size: &str) -> Result<BodyGrid3, FieldError> {
        let sides: Vec<usize> = size
            .split('x')
            .map(|n| n.parse::<usize>())
            .collect::<Result<_, _>>()
            .map_err(|_| FieldError::message(format!("'box-{size}': expected box-WxHxD with three whole numbers")))?;
        let [w, h, d] = sides[..] else {
            return Err(FieldError::message(format!(
                "'box-{size}': expected box-WxHxD with three whole numbers"
            )));
        };
        BodyGrid3::new([w, h, d], vec![true; w * h * d])
    }

    /// A grid of `extent` with `filled` cells (x fastest); refuses an empty, oversized or
    /// disconnected body.
    pub fn new(extent: [usize; 3], filled: Vec<bool>) -> Result<BodyGrid3, FieldError> {
        if extent.iter().any(|&n| n == 0 || n > MAX_SIDE) {
            return Err(FieldError::message(format!(
                "a body is 1 to {MAX_SIDE} cells along each side, got {}×{}×{}",
                extent[0], extent[1], extent[2]
            )));
        }
        let grid = BodyGrid3 { extent, filled };
        let count = grid.voxel_count();
        if count == 0 {
            return Err(FieldError::message("the body has no voxel"));
        }
        if grid.connected_count() != count {
            return Err(FieldError::message(
                "the body is in pieces: every voxel must share a face with another (one piece)",
            ));
        }
        Ok(grid)
    }

    /// Cells along x, y, z.
    pub fn extent(&self) -> [usize; 3] {
        self.extent
    }

    /// Whether cell (x, y, z) holds a voxel (false outside the box).
    pub fn has(&self, x: isize, y: isize, z: isize) -> bool {
        let [w, h, d] = self.extent.map(|n| n as isize);
        (0..w).contains(&x) && (0..h).contains(&y) && (0..d).contains(&z) && self.filled[((z * h + y) * w + x) as usize]
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.filled.iter().filter(|&&f| f).count()
    }

    /// The voxels' cells, x fastest, then y, then z: the order of units of the brain.
    pub fn cells(&self) -> impl Iterator<Item = [usize; 3]> + '_ {
        let [w, h, _] = self.extent;
        self.filled
            .iter()
            .enumerate()
            .filter(|(_, &f)| f)
            .map(move |(i, _)| [i % w, (i / w) % h, i / (w * h)])
    }

    /// The brain's layout: units in [`BodyGrid3::cells`] order, six neighbours each.
    pub fn layout(&self) -> Grid3Layout {
        Grid3Layout::from_fn(self.extent, |x, y, z| self.has(x as isize, y as isize, z as isize))
    }

    /// Voxels reachable from the first through shared faces.
    fn connected_count(&self) -> usize {
        let Some(first) = self.cells().next() else {
            return 0;
        };
        let [w, h, _] = self.extent;
        let index = |c: [usize; 3]| (c[2] * h + c[1]) * w + c[0];
        let mut seen = vec![false; self.filled.len()];
        let mut stack = vec![first];
        seen[index(first)] = true;
        let mut count = 0;
        while let Some(c) = stack.pop() {
            count += 1;
            for d in [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] {
                let n = [c[0] as isize + d[0], c[1] as isize + d[1], c[2] as isize + d[2]];
                if self.has(n[0], n[1], n[2]) {
                    let n = n.map(|v| v as usize);
                    if !seen[index(n)] {
                        seen[index(n)] = true;
                        stack.push(n);
                    }
                }
            }
        }
        count
    }
}

impl fmt::Display for BodyGrid3 {
    /// The text form: layers bottom first joined by `|`, rows by `/`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [w, h, d] = self.extent;
        let layers: Vec<String> = (0..d)
            .map(|z| {
                (0..h)
                    .map(|y| {
                        (0..w)
                            .map(|x| {
                                if self.has(x as isize, y as isize, z as isize) {
                                    '#'
                                } else {
                                    '.'
                                }
                            })
                            .collect::<String>()
                    })
                    .collect::<Vec<_>>()
                    .join("/")
            })
            .collect();
        write!(f, "{}", layers.join("|"))
    }
}

/// The named shapes, for messages.
pub fn shape_names() -> String {
    SHAPES.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_brain::UnitLayout as _;

    #[test]
    fn text_forms_read_layers_bottom_first_and_write_back() {
        let g = BodyGrid3::parse("#..#/..../#..#|####/####/####").unwrap();
        assert_eq!(g.extent(), [4, 3, 2]);
        assert_eq!(g.voxel_count(), 16);
        assert!(g.has(0, 0, 0) && !g.has(1, 0, 0) && g.has(3, 2, 0) && g.has(1, 1, 1));
        assert!(!g.has(-1, 0, 0) && !g.has(0, 0, 2));
        assert_eq!(g.to_string(), "#..#/..../#..#|####/####/####");
        assert_eq!(g.cells().next(), Some([0, 0, 0]));
        assert_eq!(g.cells().nth(4), Some([0, 0, 1]));
        assert_eq!(BodyGrid3::parse("box-2x3x4").unwrap().voxel_count(), 24);
        assert_eq!(BodyGrid3::parse("quadruped").unwrap().voxel_count(), 28);
        assert_eq!(g.layout().units(), 16);
        let count = |name: &str| BodyGrid3::parse(name).unwrap().voxel_count();
        assert_eq!((count("flatworm"), count("starfish"), count("gecko")), (25, 17, 20));
    }

    #[test]
    fn bad_bodies_are_refused_saying_why() {
        let err = |t: &str| BodyGrid3::parse(t).unwrap_err().to_string();
        assert!(err("#.#").contains("in pieces"), "{}", err("#.#"));
        assert!(err("##/#|##/##").contains("row 1 of layer 0"), "{}", err("##/#|##/##"));
        assert!(err("##|##/##").contains("layer 1 has 2 rows"));
        assert!(err("#x").contains("'x' in row 0 of layer 0"));
        assert!(err("..").contains("no voxel"));
        assert!(err("box-2x2").contains("box-WxHxD"));
        assert!(err("box-40x1x1").contains("1 to 32"));
        assert!(err("").contains("1 to 32"));
    }
}
