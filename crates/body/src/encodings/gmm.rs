//! Gaussian-mixture (GMM) body encoding (thesis §3.3.5.1 "GMM", thesis-code-facts.md §3.3).
//!
//! **Genes.** n Gaussians × 5 genes, one block of 5 per Gaussian, in this order:
//! `[φ, μx, μy, σx, σy]` — genes `5i .. 5i+5` describe Gaussian `i` (weight/mixing coefficient,
//! mean x, mean y, standard deviation along x, standard deviation along y). The thesis uses
//! n = 5, so 25 genes. The original code initialises body genes in U[0, 1]. No gene is squashed;
//! the weight is used as it is (a negative weight subtracts from the mixture), the σ genes are
//! read according to [`GmmSigma`].
//!
//! **Value.** Cell (x, y) (y = 0 the bottom row) is evaluated at its corner, in coordinates set
//! by [`GmmCoords`] — by default (x/W, y/H) ∈ [0, 1)², as in the original code. The mixture value
//! there is
//!
//! f(x, y) = Σᵢ φᵢ · exp(−½((x−μx,ᵢ)²/σx,ᵢ² + (y−μy,ᵢ)²/σy,ᵢ²)) / (2π σx,ᵢ σy,ᵢ),
//!
//! and the cell holds a voxel iff f > threshold (0.5 in the original code, [`GMM_THRESHOLD`]).
//! The body is the largest 4-connected component of those cells (see
//! [`largest_component`](super::largest_component)).
//!
//! **Where the thesis text and the original code differ** (thesis-code-facts.md §3.3):
//! - The thesis clips the σ genes at 0; the code uses them unclipped, so a negative σx·σy product
//!   flips the sign of that Gaussian's contribution. Default here: [`GmmSigma::Clip`] (the
//!   textbook reading); [`GmmSigma::Signed`] reproduces the code.
//! - The thesis normalises coordinates to [−1, 1] (2x/W − 1) and thresholds at 0; the code uses
//!   x/W and 0.5, which is what the experiments ran (and threshold 0 would fill almost the whole
//!   grid). Defaults here follow the code; [`GmmCoords::Centred`] gives the thesis' coordinates
//!   and the threshold is a parameter.
//!
//! **Degenerate Gaussians.** A Gaussian with σx = 0 or σy = 0 (for instance a negative σ gene
//! clipped to 0) contributes nothing: it has no mass anywhere but on a line. The value is computed
//! so that extreme but finite genes never give NaN (log-space when 2πσxσy under- or overflows;
//! each contribution is clamped to the finite range).

use super::{check_genes, check_grid, finish, EncodingError, OnEmpty};
use crate::Morphology;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Genes per Gaussian: weight, μx, μy, σx, σy.
pub const GENES_PER_GAUSSIAN: usize = 5;

/// The threshold of the original code: a cell is a voxel iff the mixture value exceeds it.
pub const GMM_THRESHOLD: f64 = 0.5;

/// Most Gaussians a GMM body may have (the thesis uses 5).
pub const MAX_GAUSSIANS: usize = 100_000;

/// How the σ genes are turned into standard deviations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GmmSigma {
    /// σ = max(0, gene), as the thesis text says; a Gaussian with a zero σ contributes nothing.
    #[default]
    Clip,
    /// σ = gene, as the original code does: the exponent uses σ², so only the sign of the
    /// normaliser 2πσxσy is affected, and a negative σx·σy makes that Gaussian subtract.
    /// A σ of exactly 0 contributes nothing (the original would produce NaN there).
    Signed,
}

/// Which coordinates the cell corners are given to the Gaussians in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum GmmCoords {
    /// (x/W, y/H) ∈ [0, 1)², as in the original code (the default).
    #[default]
    Unit,
    /// (2x/W − 1, 2y/H − 1) ∈ [−1, 1)², as written in the thesis.
    Centred,
}

/// One Gaussian of the mixture, with its σ's already read through a [`GmmSigma`] policy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Gaussian {
    /// Weight (mixing coefficient) φ.
    pub weight: f64,
    /// Mean along x.
    pub mean_x: f64,
    /// Mean along y.
    pub mean_y: f64,
    /// Standard deviation along x.
    pub sigma_x: f64,
    /// Standard deviation along y.
    pub sigma_y: f64,
}

impl Gaussian {
    /// Reads one block of 5 genes `[φ, μx, μy, σx, σy]`.
    pub fn from_genes(genes: [f64; GENES_PER_GAUSSIAN], sigma: GmmSigma) -> Gaussian {
        let [weight, mean_x, mean_y, sx, sy] = genes;
        let read = |s: f64| match sigma {
            GmmSigma::Clip => s.max(0.0),
            GmmSigma::Signed => s,
        };
        Gaussian {
            weight,
            mean_x,
            mean_y,
            sigma_x: read(sx),
            sigma_y: read(sy),
        }
    }

    /// φ · exp(−½((x−μx)²/σx² + (y−μy)²/σy²)) / (2π σx σy), or 0 when a σ or φ is 0.
    /// Finite for finite fields (clamped to ±`f64::MAX`).
    pub fn value(&self, x: f64, y: f64) -> f64 {
        let (w, sx, sy) = (self.weight, self.sigma_x, self.sigma_y);
        if w == 0.0 || sx == 0.0 || sy == 0.0 {
            return 0.0;
        }
        // (d/σ)² rather than d²/σ²: σ² may underflow to 0 while σ does not.
        let zx = (x - self.mean_x) / sx;
        let zy = (y - self.mean_y) / sy;
        let exponent = -0.5 * (zx * zx + zy * zy);
        let norm = 2.0 * PI * sx * sy;
        let v = if norm != 0.0 && norm.is_finite() {
            w * exponent.exp() / norm
        } else {
            // The normaliser under- or overflowed: work with logarithms and signs.
            let sign = w.signum() * sx.signum() * sy.signum();
            let ln = w.abs().ln() + exponent - (2.0 * PI).ln() - sx.abs().ln() - sy.abs().ln();
            sign * ln.exp()
        };
        v.clamp(-f64::MAX, f64::MAX)
    }
}

/// The GMM encoding of a W×H grid: 5 genes per Gaussian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GmmBody {
    /// Grid width W.
    pub width: usize,
    /// Grid height H.
    pub height: usize,
    /// Number of Gaussians n (5 in the thesis).
    pub components: usize,
    /// A cell is a voxel iff the mixture value there is greater than this ([`GMM_THRESHOLD`]).
    pub threshold: f64,
    /// How σ genes are read (default [`GmmSigma::Clip`]).
    pub sigma: GmmSigma,
    /// Cell coordinates (default [`GmmCoords::Unit`]).
    pub coords: GmmCoords,
    /// What an all-empty grid gives (default [`OnEmpty::Error`]).
    pub on_empty: OnEmpty,
}

impl GmmBody {
    /// W×H grid, n Gaussians, threshold 0.5, clipped σ, unit coordinates, empty = error.
    pub fn new(width: usize, height: usize, components: usize) -> GmmBody {
        GmmBody {
            width,
            height,
            components,
            threshold: GMM_THRESHOLD,
            sigma: GmmSigma::default(),
            coords: GmmCoords::default(),
            on_empty: OnEmpty::default(),
        }
    }

    /// The same encoding with another threshold.
    pub fn with_threshold(self, threshold: f64) -> GmmBody {
        GmmBody { threshold, ..self }
    }

    /// The same encoding with another σ policy.
    pub fn with_sigma(self, sigma: GmmSigma) -> GmmBody {
        GmmBody { sigma, ..self }
    }

    /// The same encoding with other cell coordinates.
    pub fn with_coords(self, coords: GmmCoords) -> GmmBody {
        GmmBody { coords, ..self }
    }

    /// The same encoding with another empty-grid policy.
    pub fn with_on_empty(self, on_empty: OnEmpty) -> GmmBody {
        GmmBody { on_empty, ..self }
    }

    /// Number of genes, 5·n (25 with the thesis' n = 5); saturates on overflow, which
    /// [`validate`](Self::validate) reports.
    pub fn gene_count(&self) -> usize {
        self.components.saturating_mul(GENES_PER_GAUSSIAN)
    }

    /// Checks the grid size, that n ≥ 1 and 5·n fits, and that the threshold is finite.
    pub fn validate(&self) -> Result<(), EncodingError> {
        check_grid(self.width, self.height)?;
        if self.components == 0 || self.components > MAX_GAUSSIANS {
            return Err(EncodingError::InvalidConfig(format!(
                "a GMM body needs 1 to {MAX_GAUSSIANS} Gaussians (components), got {}",
                self.components
            )));
        }
        if !self.threshold.is_finite() {
            return Err(EncodingError::InvalidConfig(format!(
                "the GMM threshold must be finite, got {}",
                self.threshold
            )));
        }
        Ok(())
    }

    /// The Gaussians a genotype describes (checks the config, gene count and finiteness).
    pub fn gaussians(&self, genes: &[f64]) -> Result<Vec<Gaussian>, EncodingError> {
        self.validate()?;
        check_genes(genes, self.gene_count())?;
        Ok(genes
            .chunks_exact(GENES_PER_GAUSSIAN)
            .map(|c| Gaussian::from_genes([c[0], c[1], c[2], c[3], c[4]], self.sigma))
            .collect())
    }

    /// The coordinates cell (x, y) is evaluated at (its corner; see [`GmmCoords`]).
    pub fn cell_coords(&self, x: usize, y: usize) -> (f64, f64) {
        let (u, v) = (x as f64 / self.width as f64, y as f64 / self.height as f64);
        match self.coords {
            GmmCoords::Unit => (u, v),
            GmmCoords::Centred => (2.0 * u - 1.0, 2.0 * v - 1.0),
        }
    }

    /// The mixture value at every cell, row-major from the bottom row. Never NaN.
    pub fn values(&self, genes: &[f64]) -> Result<Vec<f64>, EncodingError> {
        let gaussians = self.gaussians(genes)?;
        let mut values = Vec::with_capacity(self.width * self.height);
        for y in 0..self.height {
            for x in 0..self.width {
                let (cx, cy) = self.cell_coords(x, y);
                values.push(gaussians.iter().map(|g| g.value(cx, cy)).sum());
            }
        }
        Ok(values)
    }

    /// The thresholded grid before the largest component is taken (row-major from the bottom
    /// row): a cell is set iff its mixture value is greater than the threshold.
    pub fn cells(&self, genes: &[f64]) -> Result<Vec<bool>, EncodingError> {
        Ok(self.values(genes)?.into_iter().map(|v| v > self.threshold).collect())
    }

    /// Decodes 5·n finite genes into the largest connected piece of the cells above threshold.
    pub fn decode(&self, genes: &[f64]) -> Result<Morphology, EncodingError> {
        let cells = self.cells(genes)?;
        finish(self.width, self.height, cells, self.on_empty)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encodings::tests::check_decoding;
    use proptest::prelude::*;

    const CENTRED_BLOB: [&str; 10] = [
        "..........",
        "...####...",
        "..######..",
        ".########.",
        ".########.",
        ".########.",
        ".########.",
        "..######..",
        "...####...",
        "..........",
    ];

    #[test]
    fn gene_count_is_five_per_gaussian() {
        assert_eq!(GmmBody::new(10, 10, 5).gene_count(), 25);
        assert_eq!(GmmBody::new(3, 7, 1).gene_count(), 5);
        assert_eq!(GmmBody::new(10, 10, usize::MAX).gene_count(), usize::MAX);
        assert!(GmmBody::new(10, 10, usize::MAX).validate().is_err());
    }

    #[test]
    fn genes_are_one_block_of_five_per_gaussian() {
        let body = GmmBody::new(4, 4, 2);
        let g = body
            .gaussians(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, -9.0, 10.0])
            .unwrap();
        assert_eq!(
            g[0],
            Gaussian {
                weight: 1.0,
                mean_x: 2.0,
                mean_y: 3.0,
                sigma_x: 4.0,
                sigma_y: 5.0
            }
        );
        assert_eq!(
            g[1],
            Gaussian {
                weight: 6.0,
                mean_x: 7.0,
                mean_y: 8.0,
                sigma_x: 0.0,
                sigma_y: 10.0
            }
        );
        let g = body
            .with_sigma(GmmSigma::Signed)
            .gaussians(&[0.0, 0.0, 0.0, 0.0, 0.0, 6.0, 7.0, 8.0, -9.0, 10.0]);
        assert_eq!(g.unwrap()[1].sigma_x, -9.0);
    }

    #[test]
    fn value_matches_the_formula() {
        let g = Gaussian {
            weight: 0.7,
            mean_x: 0.3,
            mean_y: 0.6,
            sigma_x: 0.2,
            sigma_y: 0.4,
        };
        let expected = 0.7 * (-0.5f64 * (0.2f64.powi(2) / 0.04 + 0.3f64.powi(2) / 0.16)).exp() / (2.0 * PI * 0.08);
        assert!((g.value(0.5, 0.3) - expected).abs() < 1e-12);
        let peak = Gaussian {
            weight: 1.0,
            mean_x: 0.0,
            mean_y: 0.0,
            sigma_x: 1.0,
            sigma_y: 1.0,
        };
        assert!((peak.value(0.0, 0.0) - 1.0 / (2.0 * PI)).abs() < 1e-15);
    }

    #[test]
    fn single_centred_gaussian_gives_a_round_blob() {
        // Mean at the corner of cell (4.5, 4.5) in cell units: the centre of the 10×10 grid.
        let body = GmmBody::new(10, 10, 1);
        let m = body.decode(&[1.0, 0.45, 0.45, 0.2, 0.2]).unwrap();
        assert_eq!(m.to_rows(), CENTRED_BLOB);
        assert_eq!(m.voxel_count(), 52);
        // Symmetric under both mirrorings and the transpose, and about as wide as tall.
        for (x, y) in m.voxels() {
            assert!(m.has(9 - x, y) && m.has(x, 9 - y) && m.has(y, x));
        }
        // The mixture peaks at the cells next to the mean and falls off with distance.
        let v = body.values(&[1.0, 0.45, 0.45, 0.2, 0.2]).unwrap();
        assert!(v[44] > v[42] && v[42] > v[40], "{v:?}");
    }

    #[test]
    fn centred_coordinates_are_the_thesis_rescaling() {
        // x' = 2u − 1 halves the lengths: Centred(4φ, 2μ − 1, 2μ − 1, 2σ, 2σ) = Unit(φ, μ, μ, σ, σ).
        let unit = GmmBody::new(10, 10, 1).decode(&[1.0, 0.45, 0.45, 0.2, 0.2]).unwrap();
        let centred = GmmBody::new(10, 10, 1)
            .with_coords(GmmCoords::Centred)
            .decode(&[4.0, -0.1, -0.1, 0.4, 0.4])
            .unwrap();
        assert_eq!(centred, unit);
        assert_eq!(
            GmmBody::new(10, 10, 1)
                .with_coords(GmmCoords::Centred)
                .cell_coords(0, 5),
            (-1.0, 0.0)
        );
    }

    #[test]
    fn wider_gaussians_along_x_give_wider_bodies() {
        let m = GmmBody::new(10, 6, 1).decode(&[1.0, 0.45, 0.4, 0.4, 0.1]).unwrap();
        assert_eq!(
            m.to_rows(),
            [
                "..........",
                "..........",
                "##########",
                "##########",
                "..........",
                ".........."
            ]
        );
    }

    #[test]
    fn negative_weight_carves_a_hole() {
        let genes = [1.0, 0.45, 0.45, 0.2, 0.2, -0.2, 0.45, 0.45, 0.08, 0.08];
        let m = GmmBody::new(10, 10, 2).decode(&genes).unwrap();
        assert_eq!(
            m.to_rows(),
            [
                "..........",
                "...####...",
                "..######..",
                ".########.",
                ".###..###.",
                ".###..###.",
                ".########.",
                "..######..",
                "...####...",
                "..........",
            ]
        );
    }

    #[test]
    fn sigma_policy_clip_drops_negative_sigmas_signed_flips_the_sign() {
        // Gaussian 2 equals Gaussian 1 except for a negative σx.
        let genes = [1.0, 0.45, 0.45, 0.2, 0.2, 1.0, 0.45, 0.45, -0.2, 0.2];
        let clip = GmmBody::new(10, 10, 2).decode(&genes).unwrap();
        assert_eq!(clip.to_rows(), CENTRED_BLOB);
        let signed = GmmBody::new(10, 10, 2).with_sigma(GmmSigma::Signed);
        assert!(signed.values(&genes).unwrap().iter().all(|v| v.abs() < 1e-12));
        assert_eq!(signed.decode(&genes), Err(EncodingError::Empty));
        // Two negative σ's cancel out: the original code reads that Gaussian as a positive one.
        let both_negative = [1.0, 0.45, 0.45, -0.2, -0.2];
        assert_eq!(
            GmmBody::new(10, 10, 1)
                .with_sigma(GmmSigma::Signed)
                .decode(&both_negative)
                .unwrap()
                .to_rows(),
            CENTRED_BLOB
        );
        assert_eq!(
            GmmBody::new(10, 10, 1).decode(&both_negative),
            Err(EncodingError::Empty)
        );
    }

    #[test]
    fn threshold_is_a_parameter() {
        let genes = [1.0, 0.45, 0.45, 0.2, 0.2];
        let low = GmmBody::new(10, 10, 1).with_threshold(0.01).decode(&genes).unwrap();
        let high = GmmBody::new(10, 10, 1).with_threshold(3.0).decode(&genes).unwrap();
        assert!(low.voxel_count() > 52 && high.voxel_count() < 52 && high.voxel_count() > 0);
        assert_eq!(high.to_rows()[4..6], ["....##....", "....##...."]);
        assert_eq!(
            GmmBody::new(10, 10, 1).with_threshold(4.0).decode(&genes),
            Err(EncodingError::Empty)
        );
    }

    #[test]
    fn far_away_means_give_an_empty_error_or_the_single_voxel_fallback() {
        let genes = [1.0, 50.0, -40.0, 0.2, 0.2, 1.0, -30.0, 80.0, 0.3, 0.3];
        let body = GmmBody::new(10, 10, 2);
        assert_eq!(body.decode(&genes), Err(EncodingError::Empty));
        let m = body.with_on_empty(OnEmpty::SingleVoxel).decode(&genes).unwrap();
        assert_eq!(m.voxel_count(), 1);
        assert!(m.has(0, 0));
    }

    #[test]
    fn two_separate_blobs_keep_the_larger() {
        // A large blob at the bottom-right and a smaller one at the top-left.
        let genes = [1.0, 0.7, 0.25, 0.15, 0.15, 0.5, 0.15, 0.8, 0.1, 0.1];
        let m = GmmBody::new(10, 10, 2).decode(&genes).unwrap();
        let cells = GmmBody::new(10, 10, 2).cells(&genes).unwrap();
        assert!(cells.iter().filter(|&&c| c).count() > m.voxel_count());
        assert!(m.voxels().all(|(x, y)| x >= 4 && y <= 5), "{m}");
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let body = GmmBody::new(10, 10, 5);
        assert_eq!(
            body.decode(&[0.5; 24]),
            Err(EncodingError::GeneCount {
                expected: 25,
                actual: 24
            })
        );
        let mut genes = [0.5; 25];
        genes[7] = f64::INFINITY;
        assert!(matches!(
            body.decode(&genes),
            Err(EncodingError::NonFiniteGene { index: 7, .. })
        ));
        assert!(matches!(
            GmmBody::new(10, 10, 0).decode(&[]),
            Err(EncodingError::InvalidConfig(_))
        ));
        assert!(matches!(
            GmmBody::new(10, 10, 1).with_threshold(f64::NAN).decode(&[0.5; 5]),
            Err(EncodingError::InvalidConfig(_))
        ));
        assert!(matches!(
            GmmBody::new(10, 0, 1).decode(&[0.5; 5]),
            Err(EncodingError::InvalidConfig(_))
        ));
    }

    #[test]
    fn extreme_finite_genes_never_give_nan() {
        let body = GmmBody::new(6, 6, 3).with_sigma(GmmSigma::Signed);
        let genes = [
            f64::MAX,
            0.5,
            0.5,
            1e-300,
            1e-300, // normaliser underflows: log-space path
            -f64::MAX,
            0.5,
            0.5,
            -1e-300,
            1e-300, // the same, negated
            1.0,
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            f64::MAX,
        ];
        let values = body.values(&genes).unwrap();
        assert!(values.iter().all(|v| !v.is_nan()), "{values:?}");
        let _ = body.decode(&genes);
        let tiny = [
            1.0, 0.5, 0.5, 1e-200, 1e-200, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        ];
        // A needle exactly on cell (3, 3): one voxel, everything else 0.
        assert_eq!(body.decode(&tiny).unwrap().voxels().collect::<Vec<_>>(), [(3, 3)]);
    }

    fn config_and_genes() -> impl Strategy<Value = (GmmBody, Vec<f64>)> {
        (1usize..=10, 1usize..=10, 1usize..=5, any::<bool>(), any::<bool>()).prop_flat_map(
            |(w, h, n, signed, centred)| {
                let body = GmmBody::new(w, h, n)
                    .with_sigma(if signed { GmmSigma::Signed } else { GmmSigma::Clip })
                    .with_coords(if centred { GmmCoords::Centred } else { GmmCoords::Unit });
                (
                    Just(body),
                    proptest::collection::vec(-1.0f64..1.5, n * GENES_PER_GAUSSIAN),
                )
            },
        )
    }

    proptest! {
        #[test]
        fn decoded_body_is_connected_in_grid_and_deterministic((body, genes) in config_and_genes()) {
            check_decoding(&body.into(), &genes, &body.cells(&genes).unwrap())?;
        }

        #[test]
        fn any_finite_genes_decode_without_panic_or_nan(
            genes in proptest::collection::vec(
                prop_oneof![
                    proptest::num::f64::NORMAL | proptest::num::f64::SUBNORMAL | proptest::num::f64::ZERO,
                    -2.0f64..2.0,
                ],
                10,
            ),
            signed in any::<bool>(),
        ) {
            let sigma = if signed { GmmSigma::Signed } else { GmmSigma::Clip };
            let body = GmmBody::new(7, 5, 2).with_sigma(sigma);
            prop_assert!(body.values(&genes).unwrap().iter().all(|v| !v.is_nan()));
            match body.decode(&genes) {
                Ok(m) => prop_assert!(m.voxel_count() >= 1),
                Err(e) => prop_assert_eq!(e, EncodingError::Empty),
            }
        }

        #[test]
        fn raising_the_threshold_never_adds_cells((body, genes) in config_and_genes(), t in 0.0f64..3.0) {
            let low = body.with_threshold(t).cells(&genes).unwrap();
            let high = body.with_threshold(t + 0.5).cells(&genes).unwrap();
            prop_assert!(low.iter().zip(&high).all(|(&l, &h)| l || !h));
        }
    }
}
