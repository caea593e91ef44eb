//! Largest 4-connected component of a boolean grid (thesis-code-facts.md §1.5).
//!
//! The grid is stored row-major from the bottom row (index = y·width + x, y = 0 is the bottom
//! row), the same layout as [`Morphology`](crate::Morphology).
//!
//! **Tie rule** (as in the original `gridLargestConnected`): components are labelled in a
//! column-major scan — x outer, y inner, i.e. (0,0), (0,1), …, (0,H−1), (1,0), … — and only a
//! *strictly* larger component replaces the current best, so among equally large components the
//! one labelled first wins: the one holding the set cell that comes first in that scan (smallest x,
//! then smallest y).

use super::EncodingError;

/// Keeps only the largest 4-connected component of `cells` (row-major from the bottom row, length
/// `width·height`); every other cell is cleared. Ties follow the module-level rule.
///
/// Returns an all-false grid when no cell is set, and [`EncodingError::GridSize`] when
/// `cells.len() != width·height`.
pub fn largest_component(width: usize, height: usize, cells: &[bool]) -> Result<Vec<bool>, EncodingError> {
    if width.checked_mul(height) != Some(cells.len()) {
        return Err(EncodingError::GridSize {
            width,
            height,
            len: cells.len(),
        });
    }
    let labels = label_components(width, height, cells);
    // Label 0 = unset cell; components are labelled 1, 2, … in scan order.
    let count = labels.iter().copied().max().unwrap_or(0);
    if count == 0 {
        return Ok(vec![false; cells.len()]);
    }
    let mut sizes = vec![0usize; count + 1];
    for &l in &labels {
        sizes[l] += 1;
    }
    let mut best = 1;
    for label in 2..=count {
        if sizes[label] > sizes[best] {
            best = label;
        }
    }
    Ok(labels.iter().map(|&l| l == best).collect())
}

/// Labels the 4-connected components of `cells`: 0 for unset cells, 1.. for components in the
/// order of the column-major scan (x outer, y inner). `cells.len()` must be `width·height`.
fn label_components(width: usize, height: usize, cells: &[bool]) -> Vec<usize> {
    let mut labels = vec![0usize; cells.len()];
    let mut next = 0;
    let mut stack = Vec::new();
    for x in 0..width {
        for y in 0..height {
            let start = y * width + x;
            if !cells[start] || labels[start] != 0 {
                continue;
            }
            next += 1;
            labels[start] = next;
            stack.push((x, y));
            while let Some((cx, cy)) = stack.pop() {
                let neighbours = [
                    (cx > 0).then(|| (cx - 1, cy)),
                    (cx + 1 < width).then_some((cx + 1, cy)),
                    (cy > 0).then(|| (cx, cy - 1)),
                    (cy + 1 < height).then_some((cx, cy + 1)),
                ];
                for (nx, ny) in neighbours.into_iter().flatten() {
                    let j = ny * width + nx;
                    if cells[j] && labels[j] == 0 {
                        labels[j] = next;
                        stack.push((nx, ny));
                    }
                }
            }
        }
    }
    labels
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Morphology;
    use proptest::prelude::*;

    /// Parses rows of '#'/'.' (top row first) into (width, height, cells bottom-row first).
    fn grid(rows: &[&str]) -> (usize, usize, Vec<bool>) {
        let (w, h) = (rows[0].len(), rows.len());
        let mut cells = vec![false; w * h];
        for (r, row) in rows.iter().enumerate() {
            for (x, c) in row.chars().enumerate() {
                cells[(h - 1 - r) * w + x] = c == '#';
            }
        }
        (w, h, cells)
    }

    fn rows_of(w: usize, h: usize, cells: &[bool]) -> Vec<String> {
        (0..h)
            .rev()
            .map(|y| (0..w).map(|x| if cells[y * w + x] { '#' } else { '.' }).collect())
            .collect()
    }

    fn keep(rows: &[&str]) -> Vec<String> {
        let (w, h, cells) = grid(rows);
        rows_of(w, h, &largest_component(w, h, &cells).unwrap())
    }

    #[test]
    fn keeps_the_strictly_largest_component() {
        assert_eq!(keep(&["#..##", "#...#", "..###"]), ["...##", "....#", "..###"]);
    }

    #[test]
    fn diagonal_contact_does_not_connect() {
        assert_eq!(keep(&["#.", ".#"]), ["#.", ".."]);
    }

    #[test]
    fn tie_goes_to_the_component_first_in_column_major_scan() {
        // Two 2-cell pieces: the right one holds the bottom row, but the left one has smaller x
        // and is scanned first (x outer, y inner), so it wins.
        assert_eq!(keep(&["#..", "#..", "..#", "..#"]), ["#..", "#..", "...", "..."]);
        // Same column: the lower piece (smaller y) is scanned first.
        assert_eq!(keep(&["#", "#", ".", "#", "#"]), [".", ".", ".", "#", "#"]);
        // Column-major, not row-major: the left piece starts at (0,1), the right one at (2,0);
        // row-major from the bottom would pick the right one, the original's scan picks the left.
        assert_eq!(keep(&["#..", "#.#", "..#"]), ["#..", "#..", "..."]);
        // Three equal single cells: (0, 2) has the smallest x.
        assert_eq!(keep(&["#..", "...", "..#", ".#."]), ["#..", "...", "...", "..."]);
    }

    #[test]
    fn empty_grid_stays_empty_and_bad_length_is_an_error() {
        assert_eq!(largest_component(2, 2, &[false; 4]).unwrap(), vec![false; 4]);
        assert_eq!(largest_component(0, 3, &[]).unwrap(), Vec::<bool>::new());
        assert!(matches!(
            largest_component(2, 2, &[true; 3]),
            Err(EncodingError::GridSize {
                width: 2,
                height: 2,
                len: 3
            })
        ));
        assert!(largest_component(usize::MAX, 2, &[true]).is_err());
    }

    proptest! {
        #[test]
        fn result_is_one_connected_subset_no_smaller_than_any_component(
            (w, h, cells) in (1usize..9, 1usize..9)
                .prop_flat_map(|(w, h)| (Just(w), Just(h), proptest::collection::vec(any::<bool>(), w * h)))
        ) {
            let kept = largest_component(w, h, &cells).unwrap();
            prop_assert_eq!(kept.len(), cells.len());
            prop_assert!(kept.iter().zip(&cells).all(|(&k, &c)| !k || c), "kept cells must be set cells");
            let labels = label_components(w, h, &cells);
            let n = labels.iter().copied().max().unwrap_or(0);
            if n == 0 {
                prop_assert!(kept.iter().all(|&k| !k));
            } else {
                prop_assert!(Morphology::from_cells(w, h, kept.clone()).is_ok());
                let size = kept.iter().filter(|&&k| k).count();
                for l in 1..=n {
                    prop_assert!(labels.iter().filter(|&&x| x == l).count() <= size);
                }
                // The kept piece is a whole component, not part of one.
                let first = kept.iter().position(|&k| k).unwrap();
                let kept_label = labels[first];
                prop_assert!(labels.iter().zip(&kept).all(|(&l, &k)| k == (l == kept_label)));
                // Deterministic.
                prop_assert_eq!(largest_component(w, h, &cells).unwrap(), kept);
            }
        }
    }
}
