//! Body encodings: from a real-valued genotype to a [`Morphology`] (thesis §3.3.5.1,
//! thesis-code-facts.md §3.2–§3.3).
//!
//! Two encodings are offered, both of which first build a boolean W×H grid, then keep its largest
//! 4-connected component ([`largest_component`], tie rule documented there):
//!
//! - [`DirectBody`]: one gene per cell, a voxel iff the gene is `> 0`.
//! - [`GmmBody`]: a mixture of axis-aligned 2-D Gaussians, 5 genes each; a voxel iff the mixture
//!   value at the cell is `> threshold` (0.5 in the original code).
//!
//! In a full genotype the body genes come first and the controller genes follow
//! (thesis-code-facts.md §3.1): split it with `genes.split_at(encoding.gene_count())`.
//!
//! **Empty grids.** When no cell is set, the original code puts a single voxel at (0, 0) (the
//! bottom-left cell). Here the default is to report [`EncodingError::Empty`]; the original
//! behaviour is available as [`OnEmpty::SingleVoxel`] (`on_empty: "single-voxel"` in configs).
//!
//! **Errors, never panics.** A wrong gene count, a non-finite gene and a bad configuration (zero or
//! too large grid, no Gaussians, non-finite threshold) are all reported as [`EncodingError`].

mod direct;
mod gmm;
mod largest_component;

pub use direct::DirectBody;
pub use gmm::{Gaussian, GmmBody, GmmCoords, GmmSigma, GENES_PER_GAUSSIAN, GMM_THRESHOLD};
pub use largest_component::largest_component;

use crate::{Morphology, MorphologyError};
use serde::{Deserialize, Serialize};

/// Largest accepted grid side (width or height), in cells: that of every body
/// ([`crate::morphology::MAX_SIDE`]).
pub use crate::morphology::MAX_SIDE;

/// Why a genotype could not be decoded into a body.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum EncodingError {
    /// The genotype does not have the number of genes the encoding needs.
    #[error("wrong number of body genes: expected {expected}, got {actual}")]
    GeneCount {
        /// Genes the encoding needs.
        expected: usize,
        /// Genes given.
        actual: usize,
    },
    /// A gene is NaN or infinite.
    #[error("body gene {index} is not finite ({value})")]
    NonFiniteGene {
        /// 0-based position of the gene.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// No cell of the grid was set, so there is no body (see [`OnEmpty`]).
    #[error("the decoded body is empty: no grid cell passed the threshold")]
    Empty,
    /// The encoding's parameters are not usable.
    #[error("invalid body encoding: {0}")]
    InvalidConfig(String),
    /// A cell grid does not have width·height cells.
    #[error("a {width}×{height} grid needs width·height cells, got {len}")]
    GridSize {
        /// Grid width.
        width: usize,
        /// Grid height.
        height: usize,
        /// Cells given.
        len: usize,
    },
    /// The decoded cells were rejected as a morphology (not expected to happen: the largest
    /// component is always one connected, non-empty piece).
    #[error(transparent)]
    Morphology(#[from] MorphologyError),
}

/// What to do when the decoded grid has no set cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OnEmpty {
    /// Report [`EncodingError::Empty`] (the default).
    #[default]
    Error,
    /// Put one voxel at cell (0, 0), the bottom-left corner, as the original code does
    /// (thesis-code-facts.md §3.2).
    SingleVoxel,
}

/// A body encoding as written in configs: `{"kind": "direct", "width": 10, "height": 10}` or
/// `{"kind": "gmm", "width": 10, "height": 10, "components": 5, "threshold": 0.5}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum BodyEncoding {
    /// One gene per cell; see [`DirectBody`].
    Direct {
        /// Grid width W.
        width: usize,
        /// Grid height H.
        height: usize,
        /// What an all-empty grid gives (default: an error).
        #[serde(default)]
        on_empty: OnEmpty,
    },
    /// Gaussian mixture; see [`GmmBody`].
    Gmm {
        /// Grid width W.
        width: usize,
        /// Grid height H.
        height: usize,
        /// Number of Gaussians n (5 in the thesis).
        components: usize,
        /// A cell is a voxel iff the mixture value there is greater than this (default 0.5).
        #[serde(default = "default_threshold")]
        threshold: f64,
        /// How the σ genes are read (default: clipped at 0, as the thesis text says).
        #[serde(default)]
        sigma: GmmSigma,
        /// Cell coordinates fed to the Gaussians (default: x/W, y/H as in the original code).
        #[serde(default)]
        coords: GmmCoords,
        /// What an all-empty grid gives (default: an error).
        #[serde(default)]
        on_empty: OnEmpty,
    },
}

fn default_threshold() -> f64 {
    GMM_THRESHOLD
}

/// A config resolved to its encoding.
enum Resolved {
    Direct(DirectBody),
    Gmm(GmmBody),
}

impl BodyEncoding {
    fn resolve(&self) -> Resolved {
        match *self {
            BodyEncoding::Direct {
                width,
                height,
                on_empty,
            } => Resolved::Direct(DirectBody {
                width,
                height,
                on_empty,
            }),
            BodyEncoding::Gmm {
                width,
                height,
                components,
                threshold,
                sigma,
                coords,
                on_empty,
            } => Resolved::Gmm(GmmBody {
                width,
                height,
                components,
                threshold,
                sigma,
                coords,
                on_empty,
            }),
        }
    }

    /// Number of body genes: W·H for Direct, 5·n for GMM (saturating on overflow, which
    /// [`validate`](Self::validate) reports).
    pub fn gene_count(&self) -> usize {
        match self.resolve() {
            Resolved::Direct(d) => d.gene_count(),
            Resolved::Gmm(g) => g.gene_count(),
        }
    }

    /// Checks the parameters (grid size, number of Gaussians, threshold).
    pub fn validate(&self) -> Result<(), EncodingError> {
        match self.resolve() {
            Resolved::Direct(d) => d.validate(),
            Resolved::Gmm(g) => g.validate(),
        }
    }

    /// Decodes exactly [`gene_count`](Self::gene_count) body genes into a morphology.
    pub fn decode(&self, genes: &[f64]) -> Result<Morphology, EncodingError> {
        match self.resolve() {
            Resolved::Direct(d) => d.decode(genes),
            Resolved::Gmm(g) => g.decode(genes),
        }
    }

    /// Grid width W.
    pub fn width(&self) -> usize {
        match *self {
            BodyEncoding::Direct { width, .. } | BodyEncoding::Gmm { width, .. } => width,
        }
    }

    /// Grid height H.
    pub fn height(&self) -> usize {
        match *self {
            BodyEncoding::Direct { height, .. } | BodyEncoding::Gmm { height, .. } => height,
        }
    }

    /// The Direct encoding this describes, if it is one.
    pub fn as_direct(&self) -> Option<DirectBody> {
        match self.resolve() {
            Resolved::Direct(d) => Some(d),
            Resolved::Gmm(_) => None,
        }
    }

    /// The GMM encoding this describes, if it is one.
    pub fn as_gmm(&self) -> Option<GmmBody> {
        match self.resolve() {
            Resolved::Gmm(g) => Some(g),
            Resolved::Direct(_) => None,
        }
    }
}

impl From<DirectBody> for BodyEncoding {
    fn from(d: DirectBody) -> Self {
        BodyEncoding::Direct {
            width: d.width,
            height: d.height,
            on_empty: d.on_empty,
        }
    }
}

impl From<GmmBody> for BodyEncoding {
    fn from(g: GmmBody) -> Self {
        BodyEncoding::Gmm {
            width: g.width,
            height: g.height,
            components: g.components,
            threshold: g.threshold,
            sigma: g.sigma,
            coords: g.coords,
            on_empty: g.on_empty,
        }
    }
}

/// Checks a grid size: both sides in 1..=[`MAX_SIDE`]. Returns the number of cells.
fn check_grid(width: usize, height: usize) -> Result<usize, EncodingError> {
    if width == 0 || height == 0 || width > MAX_SIDE || height > MAX_SIDE {
        return Err(EncodingError::InvalidConfig(format!(
            "grid {width}×{height}: width and height must be between 1 and {MAX_SIDE}"
        )));
    }
    Ok(width * height)
}

/// Checks the gene count and that every gene is finite.
fn check_genes(genes: &[f64], expected: usize) -> Result<(), EncodingError> {
    if genes.len() != expected {
        return Err(EncodingError::GeneCount {
            expected,
            actual: genes.len(),
        });
    }
    match genes.iter().position(|g| !g.is_finite()) {
        Some(index) => Err(EncodingError::NonFiniteGene {
            index,
            value: genes[index],
        }),
        None => Ok(()),
    }
}

/// Common tail of both decoders: empty check (with the optional fallback), then the largest
/// component, then a validated morphology.
fn finish(width: usize, height: usize, mut cells: Vec<bool>, on_empty: OnEmpty) -> Result<Morphology, EncodingError> {
    if !cells.iter().any(|&c| c) {
        match on_empty {
            OnEmpty::Error => return Err(EncodingError::Empty),
            OnEmpty::SingleVoxel => cells[0] = true,
        }
    }
    let kept = largest_component(width, height, &cells)?;
    Ok(Morphology::from_cells(width, height, kept)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Checks what every encoding guarantees when it decodes `genes`, whose set grid cells
    /// (row-major from the bottom) are `cells`: a body in the W×H grid, connected (it validates as a
    /// morphology), made of set cells only and the same at every decoding; or, when no cell is set,
    /// [`EncodingError::Empty`], and with [`OnEmpty::SingleVoxel`] the one voxel at (0, 0).
    pub(super) fn check_decoding(encoding: &BodyEncoding, genes: &[f64], cells: &[bool]) -> Result<(), TestCaseError> {
        let (w, h) = (encoding.width(), encoding.height());
        match encoding.decode(genes) {
            Ok(m) => {
                prop_assert_eq!((m.width(), m.height()), (w, h));
                let kept: Vec<bool> = (0..w * h).map(|i| m.has(i % w, i / w)).collect();
                prop_assert!(Morphology::from_cells(w, h, kept).is_ok());
                for (x, y) in m.voxels() {
                    prop_assert!(cells[y * w + x]);
                }
                prop_assert_eq!(encoding.decode(genes).unwrap(), m);
            }
            Err(e) => {
                prop_assert_eq!(e, EncodingError::Empty);
                prop_assert!(cells.iter().all(|&c| !c));
                let mut fallback = encoding.clone();
                let (BodyEncoding::Direct { on_empty, .. } | BodyEncoding::Gmm { on_empty, .. }) = &mut fallback;
                *on_empty = OnEmpty::SingleVoxel;
                let m = fallback.decode(genes).unwrap();
                prop_assert_eq!(m.voxels().collect::<Vec<_>>(), vec![(0, 0)]);
            }
        }
        Ok(())
    }

    #[test]
    fn configs_round_trip_and_fill_defaults() {
        let d: BodyEncoding = serde_json::from_str(r#"{"kind":"direct","width":10,"height":10}"#).unwrap();
        assert_eq!(d, BodyEncoding::from(DirectBody::new(10, 10)));
        assert_eq!(d.gene_count(), 100);
        let g: BodyEncoding = serde_json::from_str(r#"{"kind":"gmm","width":10,"height":10,"components":5}"#).unwrap();
        assert_eq!(g, BodyEncoding::from(GmmBody::new(10, 10, 5)));
        assert_eq!(g.gene_count(), 25);
        assert_eq!((g.width(), g.height()), (10, 10));
        let full = BodyEncoding::Gmm {
            width: 4,
            height: 3,
            components: 2,
            threshold: 0.25,
            sigma: GmmSigma::Signed,
            coords: GmmCoords::Centred,
            on_empty: OnEmpty::SingleVoxel,
        };
        let json = serde_json::to_string(&full).unwrap();
        assert!(
            json.contains(r#""kind":"gmm""#) && json.contains(r#""on_empty":"single-voxel""#),
            "{json}"
        );
        assert!(
            json.contains(r#""sigma":"signed""#) && json.contains(r#""coords":"centred""#),
            "{json}"
        );
        assert_eq!(serde_json::from_str::<BodyEncoding>(&json).unwrap(), full);
        let direct = BodyEncoding::Direct {
            width: 3,
            height: 2,
            on_empty: OnEmpty::SingleVoxel,
        };
        let json = serde_json::to_string(&direct).unwrap();
        assert_eq!(serde_json::from_str::<BodyEncoding>(&json).unwrap(), direct);
    }

    #[test]
    fn configs_reject_unknown_fields_and_kinds() {
        assert!(serde_json::from_str::<BodyEncoding>(r#"{"kind":"direct","width":2,"height":2,"depth":1}"#).is_err());
        assert!(serde_json::from_str::<BodyEncoding>(r#"{"kind":"cppn","width":2,"height":2}"#).is_err());
        assert!(serde_json::from_str::<BodyEncoding>(r#"{"kind":"gmm","width":2,"height":2}"#).is_err());
        assert!(
            serde_json::from_str::<BodyEncoding>(r#"{"kind":"direct","width":2,"height":2,"on_empty":"x"}"#).is_err()
        );
    }

    #[test]
    fn enum_decode_dispatches_to_the_encoding() {
        let d = BodyEncoding::Direct {
            width: 2,
            height: 2,
            on_empty: OnEmpty::Error,
        };
        assert_eq!(d.decode(&[1.0, -1.0, 1.0, -1.0]).unwrap().to_rows(), ["#.", "#."]);
        assert_eq!(
            d.decode(&[1.0]),
            Err(EncodingError::GeneCount { expected: 4, actual: 1 })
        );
        let g = BodyEncoding::from(GmmBody::new(4, 4, 1));
        let genes = [1.0, 0.5, 0.5, 0.2, 0.2];
        assert_eq!(g.decode(&genes), GmmBody::new(4, 4, 1).decode(&genes));
        assert!(g.as_gmm().is_some() && g.as_direct().is_none() && d.as_direct().is_some());
        assert!(g.validate().is_ok() && d.validate().is_ok());
        assert!(BodyEncoding::Direct {
            width: 0,
            height: 2,
            on_empty: OnEmpty::Error
        }
        .validate()
        .is_err());
    }

    #[test]
    fn errors_name_expected_and_actual_counts() {
        let e = EncodingError::GeneCount {
            expected: 25,
            actual: 24,
        };
        assert_eq!(e.to_string(), "wrong number of body genes: expected 25, got 24");
    }
}
