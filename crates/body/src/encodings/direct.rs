//! Direct body encoding (thesis §3.3.5.1 "Direct", thesis-code-facts.md §3.2).
//!
//! One gene per grid cell. Gene `c` (0-based, `c < W·H`) belongs to cell (x = c mod W,
//! y = c div W), with y = 0 the bottom row: the genes are row-major from the bottom row, the same
//! order as [`Morphology`]'s cells and as the original code. (The thesis writes k = x + (y−1)·l
//! with 1-based indices, which is the same order on the square grids it uses.) A cell holds a
//! voxel iff its gene is strictly greater than 0 (the original `DIRECT_THRESHOLD` is 0), and the
//! body is the largest 4-connected component of those cells.

use super::{check_genes, check_grid, finish, EncodingError, OnEmpty};
use crate::Morphology;

/// The Direct encoding of a W×H grid: W·H genes, one per cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DirectBody {
    /// Grid width W.
    pub width: usize,
    /// Grid height H.
    pub height: usize,
    /// What an all-empty grid gives (default: [`OnEmpty::Error`]).
    pub on_empty: OnEmpty,
}

impl DirectBody {
    /// A W×H Direct encoding that reports empty bodies as errors.
    pub fn new(width: usize, height: usize) -> DirectBody {
        DirectBody {
            width,
            height,
            on_empty: OnEmpty::Error,
        }
    }

    /// The same encoding with another empty-grid policy.
    pub fn with_on_empty(self, on_empty: OnEmpty) -> DirectBody {
        DirectBody { on_empty, ..self }
    }

    /// Number of genes, W·H (100 on the thesis' 10×10 grid); saturates on overflow, which
    /// [`validate`](Self::validate) reports.
    pub fn gene_count(&self) -> usize {
        self.width.saturating_mul(self.height)
    }

    /// Checks the grid size (both sides between 1 and [`MAX_SIDE`](super::MAX_SIDE)).
    pub fn validate(&self) -> Result<(), EncodingError> {
        check_grid(self.width, self.height).map(|_| ())
    }

    /// Decodes W·H finite genes into the largest connected piece of the cells whose gene is > 0.
    pub fn decode(&self, genes: &[f64]) -> Result<Morphology, EncodingError> {
        let cells = self.cells(genes)?;
        finish(self.width, self.height, cells, self.on_empty)
    }

    /// The thresholded grid before the largest component is taken (row-major from the bottom
    /// row): cell `c` is set iff `genes[c] > 0`.
    pub fn cells(&self, genes: &[f64]) -> Result<Vec<bool>, EncodingError> {
        let n = check_grid(self.width, self.height)?;
        check_genes(genes, n)?;
        Ok(genes.iter().map(|&g| g > 0.0).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encodings::tests::check_decoding;
    use proptest::prelude::*;

    /// Genes from rows of '#' (gene 1) and '.' (gene −1), top row first, as a person draws them.
    fn genes_from_rows(rows: &[&str]) -> Vec<f64> {
        rows.iter()
            .rev()
            .flat_map(|r| r.chars().map(|c| if c == '#' { 1.0 } else { -1.0 }))
            .collect()
    }

    /// The rows of the body `body` decodes from genes drawn as `rows` ([`genes_from_rows`]).
    fn decoded_rows(body: &DirectBody, rows: &[&str]) -> Vec<String> {
        body.decode(&genes_from_rows(rows)).unwrap().to_rows()
    }

    #[test]
    fn gene_count_is_width_times_height() {
        assert_eq!(DirectBody::new(10, 10).gene_count(), 100);
        assert_eq!(DirectBody::new(5, 3).gene_count(), 15);
        assert_eq!(DirectBody::new(usize::MAX, 2).gene_count(), usize::MAX);
        assert!(DirectBody::new(usize::MAX, 2).validate().is_err());
        // every body grid is at most 100 × 100, encoded or written out
        assert!(DirectBody::new(100, 100).validate().is_ok());
        let e = DirectBody::new(1024, 1024).validate().unwrap_err().to_string();
        assert!(e.contains("between 1 and 100"), "{e}");
    }

    #[test]
    fn genes_are_row_major_from_the_bottom_row() {
        let body = DirectBody::new(3, 2);
        // Genes 0..3 are the bottom row, left to right; genes 3..6 the row above.
        let m = body.decode(&[1.0, 1.0, 1.0, 1.0, -1.0, -1.0]).unwrap();
        assert_eq!(m.to_rows(), ["#..", "###"]);
        let m = body.decode(&[-1.0, -1.0, 1.0, 1.0, 1.0, 1.0]).unwrap();
        assert_eq!(m.to_rows(), ["###", "..#"]);
        assert!(m.has(2, 0) && !m.has(0, 0));
    }

    #[test]
    fn known_grids_decode_to_known_bodies() {
        let body = DirectBody::new(5, 4);
        let connected = ["#####", "#.#.#", "#...#", "#...."];
        assert_eq!(decoded_rows(&body, &connected), connected);
        // The detached bottom-right cell and the top-left pair are dropped.
        assert_eq!(
            decoded_rows(&body, &["##...", "...##", ".###.", "#...#"]),
            [".....", "...##", ".###.", "....."]
        );
        // Diagonal neighbours are not connected: a checkerboard keeps a single voxel, the one
        // first in the column-major scan, (0, 0).
        let checkerboard = ["#.#", ".#.", "#.#"];
        assert_eq!(
            decoded_rows(&DirectBody::new(3, 3), &checkerboard),
            ["...", "...", "#.."]
        );
    }

    #[test]
    fn threshold_is_strictly_positive() {
        let body = DirectBody::new(3, 1);
        assert_eq!(body.decode(&[0.0, 1e-300, 0.0]).unwrap().to_rows(), [".#."]);
        assert_eq!(body.decode(&[-0.0, 0.0, 0.0]), Err(EncodingError::Empty));
        assert_eq!(body.cells(&[0.5, 0.0, -0.5]).unwrap(), [true, false, false]);
    }

    #[test]
    fn tie_rule_keeps_the_component_first_in_column_major_order() {
        // Two 3-voxel pieces. Row-major from the bottom would meet the right piece first
        // (it holds (3,0)); the original's column-major scan meets the left piece first ((0,1)).
        let two_pieces = ["##..", "#..#", "..##"];
        assert_eq!(
            decoded_rows(&DirectBody::new(4, 3), &two_pieces),
            ["##..", "#...", "...."]
        );
    }

    #[test]
    fn empty_grid_is_an_error_or_the_original_single_voxel() {
        let empty = ["....", "....", "...."];
        assert_eq!(
            DirectBody::new(4, 3).decode(&genes_from_rows(&empty)),
            Err(EncodingError::Empty)
        );
        let fallback = DirectBody::new(4, 3).with_on_empty(OnEmpty::SingleVoxel);
        assert_eq!(decoded_rows(&fallback, &empty), ["....", "....", "#..."]);
        // The fallback only applies to an empty grid.
        let corner = ["...#", "....", "...."];
        assert_eq!(decoded_rows(&fallback, &corner), corner);
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let body = DirectBody::new(10, 10);
        assert_eq!(
            body.decode(&[1.0; 99]),
            Err(EncodingError::GeneCount {
                expected: 100,
                actual: 99
            })
        );
        assert_eq!(
            body.decode(&[]),
            Err(EncodingError::GeneCount {
                expected: 100,
                actual: 0
            })
        );
        let mut genes = vec![1.0; 100];
        genes[42] = f64::NAN;
        assert!(matches!(
            body.decode(&genes),
            Err(EncodingError::NonFiniteGene { index: 42, .. })
        ));
        genes[42] = f64::NEG_INFINITY;
        assert!(matches!(
            body.decode(&genes),
            Err(EncodingError::NonFiniteGene { index: 42, .. })
        ));
        assert!(matches!(
            DirectBody::new(0, 5).decode(&[]),
            Err(EncodingError::InvalidConfig(_))
        ));
        assert!(matches!(
            DirectBody::new(2000, 1).decode(&[1.0; 2000]),
            Err(EncodingError::InvalidConfig(_))
        ));
    }

    fn grid_and_genes() -> impl Strategy<Value = (usize, usize, Vec<f64>)> {
        (1usize..=10, 1usize..=10)
            .prop_flat_map(|(w, h)| (Just(w), Just(h), proptest::collection::vec(-1.0f64..1.0, w * h)))
    }

    proptest! {
        #[test]
        fn decoded_body_is_connected_in_grid_and_deterministic((w, h, genes) in grid_and_genes()) {
            let body = DirectBody::new(w, h);
            check_decoding(&body.into(), &genes, &body.cells(&genes).unwrap())?;
        }

        #[test]
        fn a_single_positive_gene_gives_exactly_that_voxel(
            (w, h, k, neg) in (1usize..=10, 1usize..=10).prop_flat_map(|(w, h)| {
                (Just(w), Just(h), 0..w * h, proptest::collection::vec(-5.0f64..=0.0, w * h))
            }),
            pos in 1e-9f64..5.0,
        ) {
            let mut genes = neg;
            genes[k] = pos;
            let m = DirectBody::new(w, h).decode(&genes).unwrap();
            prop_assert_eq!(m.voxel_count(), 1);
            prop_assert!(m.has(k % w, k / w));
        }

        #[test]
        fn all_positive_genes_give_the_full_grid((w, h, genes) in grid_and_genes()) {
            let genes: Vec<f64> = genes.iter().map(|g| g.abs() + 1e-6).collect();
            prop_assert_eq!(DirectBody::new(w, h).decode(&genes).unwrap().voxel_count(), w * h);
        }
    }
}
