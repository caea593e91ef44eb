//! Morphologies: which cells of a W×H grid hold a voxel. Cell (x, y) has y = 0 as the bottom row.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Why a morphology description was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MorphologyError {
    /// The name is not a known shape or is malformed.
    #[error("unknown or malformed body '{0}': expected one of worm-WxH, biped-WxH, comb-WxH, box-WxH, tripod-WxH, t-WxH, ball-D, or a text grid of '#' and '.'")]
    BadName(String),
    /// A named shape beyond the largest size.
    #[error("body '{0}' is too large: named shapes are at most 100 × 100 voxels (ball-100)")]
    TooLarge(String),
    /// A text grid beyond the largest size.
    #[error("the body grid is {width} × {height} cells: at most {MAX_SIDE} × {MAX_SIDE}, as the named shapes")]
    GridTooLarge {
        /// Cells per row.
        width: usize,
        /// Rows.
        height: usize,
    },
    /// The body has no voxel.
    #[error("the body is empty: it has no voxel")]
    Empty,
    /// The voxels do not form one 4-connected piece.
    #[error("the body is disconnected: {0} separate pieces (voxels must share sides)")]
    Disconnected(usize),
    /// A text grid has a bad character or ragged rows.
    #[error("body grid, row {row} (top row is 1), column {col}: {msg}")]
    BadGrid {
        /// 1-based row, top first.
        row: usize,
        /// 1-based column.
        col: usize,
        /// What is wrong.
        msg: String,
    },
}

/// Most cells along either side of a body grid (named or written out): 10,000 voxels at most,
/// already hundreds of times the thesis's bodies and minutes of simulation per episode.
pub const MAX_SIDE: usize = 100;

/// A grid of cells, each with or without a voxel; validated to be non-empty and connected.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "MorphologyText", into = "MorphologyText")]
pub struct Morphology {
    width: usize,
    height: usize,
    /// Row-major from the bottom row: index = y·width + x.
    cells: Vec<bool>,
}

/// Serialised form of a morphology: rows of '#' and '.', top row first.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(transparent)]
struct MorphologyText(Vec<String>);

impl TryFrom<MorphologyText> for Morphology {
    type Error = MorphologyError;
    fn try_from(t: MorphologyText) -> Result<Self, Self::Error> {
        Morphology::from_rows(&t.0)
    }
}

impl From<Morphology> for MorphologyText {
    fn from(m: Morphology) -> Self {
        MorphologyText(m.to_rows())
    }
}

impl Morphology {
    /// Builds and validates a morphology from a predicate over (x, y), y = 0 at the bottom.
    pub fn from_fn(
        width: usize,
        height: usize,
        f: impl Fn(usize, usize) -> bool,
    ) -> Result<Morphology, MorphologyError> {
        let mut cells = vec![false; width * height];
        for y in 0..height {
            for x in 0..width {
                cells[y * width + x] = f(x, y);
            }
        }
        Morphology::from_cells(width, height, cells)
    }

    /// Builds and validates a morphology from row-major cells (bottom row first).
    pub fn from_cells(width: usize, height: usize, cells: Vec<bool>) -> Result<Morphology, MorphologyError> {
        assert_eq!(cells.len(), width * height, "cells must have width·height entries");
        let m = Morphology { width, height, cells };
        let pieces = m.components();
        match pieces {
            0 => Err(MorphologyError::Empty),
            1 => Ok(m),
            n => Err(MorphologyError::Disconnected(n)),
        }
    }

    /// Parses a named shape (`biped-4x3`, `ball-5`, …) or a text grid (rows separated by newlines
    /// or '/', top row first, '#' = voxel, '.' = empty).
    pub fn parse(s: &str) -> Result<Morphology, MorphologyError> {
        let t = s.trim();
        if t.contains('\n') || t.contains('/') || t.contains('#') || t.chars().all(|c| c == '.') {
            let rows: Vec<String> = t.split(['\n', '/']).map(|r| r.trim().to_string()).collect();
            // an empty row inside the grid is a mistake (`###//#.#`), not a row to drop
            if let Some(i) = rows.iter().position(|r| r.is_empty()) {
                return Err(MorphologyError::BadGrid {
                    row: i + 1,
                    col: 1,
                    msg: "the row is empty: write a row of '.' for a row without voxels".into(),
                });
            }
            return Morphology::from_rows(&rows);
        }
        Morphology::named(t)
    }

    /// A named shape (vsr-model.md §3.4).
    pub fn named(name: &str) -> Result<Morphology, MorphologyError> {
        let bad = || MorphologyError::BadName(name.to_string());
        let (kind, dims) = name.split_once('-').ok_or_else(bad)?;
        if kind == "ball" {
            let d: usize = dims.parse().map_err(|_| bad())?;
            if d > MAX_SIDE {
                return Err(MorphologyError::TooLarge(name.to_string()));
            }
            if d == 0 {
                return Err(bad());
            }
            let r = d as f64 / 2.0;
            return Morphology::from_fn(d, d, |x, y| {
                let (dx, dy) = (x as f64 + 0.5 - r, y as f64 + 0.5 - r);
                dx * dx + dy * dy <= r * r
            });
        }
        let (w, h) = dims.split_once('x').ok_or_else(bad)?;
        let (w, h): (usize, usize) = (w.parse().map_err(|_| bad())?, h.parse().map_err(|_| bad())?);
        if w > MAX_SIDE || h > MAX_SIDE {
            return Err(MorphologyError::TooLarge(name.to_string()));
        }
        if w == 0 || h == 0 {
            return Err(bad());
        }
        match kind {
            "box" | "worm" => Morphology::from_fn(w, h, |_, _| true),
            "biped" => Morphology::from_fn(w, h, |x, y| !(y < h / 2 && x >= w / 4 && x < 3 * w / 4)),
            "comb" => Morphology::from_fn(w, h, |x, y| y >= h / 2 || x % 2 == 0),
            "tripod" => Morphology::from_fn(w, h, |x, y| y >= h / 2 || x == 0 || x == w - 1 || x == w / 2),
            "t" => Morphology::from_fn(w, h, |x, y| y == h - 1 || (x >= w / 3 && x < w - w / 3)),
            _ => Err(bad()),
        }
    }

    /// Parses rows of '#' and '.', top row first.
    pub fn from_rows<S: AsRef<str>>(rows: &[S]) -> Result<Morphology, MorphologyError> {
        if rows.is_empty() {
            return Err(MorphologyError::Empty);
        }
        let width = rows[0].as_ref().chars().count();
        let height = rows.len();
        if width > MAX_SIDE || height > MAX_SIDE {
            return Err(MorphologyError::GridTooLarge { width, height });
        }
        let mut cells = vec![false; width * height];
        for (r, row) in rows.iter().enumerate() {
            let row = row.as_ref();
            if row.chars().count() != width {
                return Err(MorphologyError::BadGrid {
                    row: r + 1,
                    col: row.chars().count().min(width) + 1,
                    msg: format!("has {} cells but the first row has {width}", row.chars().count()),
                });
            }
            let y = height - 1 - r;
            for (x, c) in row.chars().enumerate() {
                cells[y * width + x] = match c {
                    '#' => true,
                    '.' => false,
                    other => {
                        return Err(MorphologyError::BadGrid {
                            row: r + 1,
                            col: x + 1,
                            msg: format!("unexpected character '{other}' (use '#' for a voxel, '.' for empty)"),
                        })
                    }
                };
            }
        }
        Morphology::from_cells(width, height, cells)
    }

    /// Rows of '#' and '.', top row first.
    pub fn to_rows(&self) -> Vec<String> {
        (0..self.height)
            .rev()
            .map(|y| {
                (0..self.width)
                    .map(|x| if self.has(x, y) { '#' } else { '.' })
                    .collect()
            })
            .collect()
    }

    /// Grid width W.
    pub fn width(&self) -> usize {
        self.width
    }
    /// Grid height H.
    pub fn height(&self) -> usize {
        self.height
    }
    /// Whether cell (x, y) holds a voxel (false outside the grid).
    pub fn has(&self, x: usize, y: usize) -> bool {
        x < self.width && y < self.height && self.cells[y * self.width + x]
    }
    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.cells.iter().filter(|&&c| c).count()
    }
    /// Voxel cells in grid order (row-major from the bottom row).
    pub fn voxels(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.height).flat_map(move |y| (0..self.width).filter(move |&x| self.has(x, y)).map(move |x| (x, y)))
    }

    /// Number of 4-connected pieces.
    fn components(&self) -> usize {
        let mut seen = vec![false; self.cells.len()];
        let mut pieces = 0;
        let mut stack = Vec::new();
        for start in 0..self.cells.len() {
            if !self.cells[start] || seen[start] {
                continue;
            }
            pieces += 1;
            seen[start] = true;
            stack.push(start);
            while let Some(i) = stack.pop() {
                let (x, y) = (i % self.width, i / self.width);
                let mut visit = |nx: usize, ny: usize| {
                    let j = ny * self.width + nx;
                    if self.cells[j] && !seen[j] {
                        seen[j] = true;
                        stack.push(j);
                    }
                };
                if x > 0 {
                    visit(x - 1, y);
                }
                if x + 1 < self.width {
                    visit(x + 1, y);
                }
                if y > 0 {
                    visit(x, y - 1);
                }
                if y + 1 < self.height {
                    visit(x, y + 1);
                }
            }
        }
        pieces
    }
}

impl fmt::Display for Morphology {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_rows().join("\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn biped_4x3_has_ten_voxels_and_two_legs() {
        let m = Morphology::named("biped-4x3").unwrap();
        assert_eq!(m.voxel_count(), 10);
        assert_eq!(m.to_rows(), vec!["####", "####", "#..#"]);
    }

    #[test]
    fn named_shapes_have_expected_counts() {
        assert_eq!(Morphology::named("worm-10x4").unwrap().voxel_count(), 40);
        assert_eq!(Morphology::named("box-5x5").unwrap().voxel_count(), 25);
        assert_eq!(Morphology::named("comb-7x2").unwrap().voxel_count(), 11);
        let ball = Morphology::named("ball-5").unwrap();
        assert!(ball.voxel_count() > 12 && ball.voxel_count() < 25);
        assert!(Morphology::named("tripod-5x3").is_ok());
        assert!(Morphology::named("t-5x4").is_ok());
    }

    #[test]
    fn text_grid_top_row_first() {
        let m = Morphology::parse("###\n#.#").unwrap();
        assert!(m.has(0, 0) && !m.has(1, 0) && m.has(1, 1));
        assert_eq!(Morphology::parse("###/#.#").unwrap(), m);
    }

    #[test]
    fn empty_disconnected_and_malformed_bodies_are_rejected() {
        assert_eq!(Morphology::parse("...\n..."), Err(MorphologyError::Empty));
        assert_eq!(Morphology::parse("#.#"), Err(MorphologyError::Disconnected(2)));
        assert!(matches!(
            Morphology::parse("#x#"),
            Err(MorphologyError::BadGrid { row: 1, col: 2, .. })
        ));
        assert!(matches!(
            Morphology::parse("##\n#"),
            Err(MorphologyError::BadGrid { row: 2, .. })
        ));
        assert!(matches!(
            Morphology::parse("snake-3x3"),
            Err(MorphologyError::BadName(_))
        ));
        assert!(matches!(Morphology::parse("box-0x3"), Err(MorphologyError::BadName(_))));
        // too large is said so, not "unknown or malformed"
        let wide = vec!["#".repeat(MAX_SIDE + 1)];
        assert_eq!(
            Morphology::from_rows(&wide),
            Err(MorphologyError::GridTooLarge {
                width: MAX_SIDE + 1,
                height: 1
            })
        );
        assert!(Morphology::from_rows(&vec!["#"; MAX_SIDE]).is_ok());
        for big in ["worm-100000x1", "box-3x101", "ball-1000"] {
            let e = Morphology::parse(big).unwrap_err();
            assert_eq!(e, MorphologyError::TooLarge(big.into()));
            assert!(e.to_string().contains("too large"), "{e}");
        }
        // an empty row inside a grid is refused, not dropped
        assert!(matches!(
            Morphology::parse("###//#.#"),
            Err(MorphologyError::BadGrid { row: 2, col: 1, .. })
        ));
        assert!(matches!(
            Morphology::parse("###\n\n###"),
            Err(MorphologyError::BadGrid { row: 2, .. })
        ));
        assert!(
            Morphology::parse("\n###\n###\n").is_ok(),
            "blank lines around the grid are fine"
        );
        // diagonal contact is not a connection
        assert_eq!(Morphology::parse("#.\n.#"), Err(MorphologyError::Disconnected(2)));
    }

    #[test]
    fn serde_round_trip_uses_text_rows() {
        let m = Morphology::named("biped-4x3").unwrap();
        let json = serde_json::to_string(&m).unwrap();
        assert_eq!(json, "[\"####\",\"####\",\"#..#\"]");
        let back: Morphology = serde_json::from_str(&json).unwrap();
        assert_eq!(back, m);
    }
}
