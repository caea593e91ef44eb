//! Figures (PNG through plotters' bitmap backend, SVG through its SVG backend): median ± sd
//! bands, boxplots with pairwise p-values, species bubble plots and scatters.
//!
//! One file per concept: [`colors`] (setting colours, viridis), `text` (the bundled font and
//! text styles), [`axes`] (ranges and tick labels), `frame` (the titled chart with its axes and
//! grid, shared by every figure kind), `legend`, and one file per figure kind: [`band`],
//! [`boxplot`], [`bubble`], [`scatter`]. Every figure implements [`Figure`] and is
//! written by [`save`]. Text is drawn with DejaVu Sans, bundled in the crate, so no system font
//! is looked up. Settings get the colours of [`setting_color`] by their index, the same in every
//! figure.

pub mod axes;
pub mod band;
pub mod boxplot;
pub mod bubble;
pub mod colors;
mod frame;
mod legend;
pub mod scatter;
mod text;

pub use axes::{format_tick, format_tick_within};
pub use band::{BandChart, BandFigure, BandSeries};
pub use boxplot::{format_p, BoxFigure, BoxGroup};
pub use bubble::{Bubble, BubbleFigure, BubblePanel};
pub use colors::{setting_color, viridis};
pub use scatter::{ScatterFigure, ScatterPoint};

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use vsrlab_tasks::files::{write_atomic, TempPath};

/// Why a figure could not be written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// plotters could not draw the figure.
    #[error("figure {}: {source}", path.display())]
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// What failed.
        source: DrawError,
    },
    /// The drawn figure could not be written.
    #[error("figure {}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
}

/// A drawing operation failed (plotters reports its errors per backend type, so the report is
/// kept as text).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct DrawError {
    /// plotters' report.
    pub message: String,
}

/// The result of drawing.
type R = Result<(), DrawError>;

/// A plotters error as a [`DrawError`].
fn err<E: std::fmt::Display>(e: E) -> DrawError {
    DrawError { message: e.to_string() }
}

/// A figure that can be drawn on any plotters backend.
pub trait Figure {
    /// Size in pixels (PNG) or user units (SVG).
    fn size(&self) -> (u32, u32) {
        (1200, 800)
    }
    /// Draws the figure on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError>;
}

/// Writes `figure` as `<stem>.png` and `<stem>.svg` (each atomically: a failure leaves neither
/// a half-written file nor a temporary one); returns the two paths.
pub fn save(figure: &impl Figure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    text::register_font();
    let png = stem.with_extension("png");
    let svg = stem.with_extension("svg");
    save_png(figure, &png)?;
    save_svg(figure, &svg)?;
    Ok(vec![png, svg])
}

/// Draws `figure` into a temporary PNG beside `path` (the bitmap backend encodes by file name),
/// then renames it onto `path`.
fn save_png(figure: &impl Figure, path: &Path) -> Result<(), PlotError> {
    let draw_error = |source| PlotError::Draw {
        path: path.to_path_buf(),
        source,
    };
    let tmp = TempPath::beside(path);
    {
        let root = BitMapBackend::new(tmp.path(), figure.size()).into_drawing_area();
        figure.draw(&root).map_err(draw_error)?;
        root.present().map_err(|e| draw_error(err(e)))?;
    }
    tmp.commit().map_err(|source| PlotError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Draws `figure` as an SVG document in memory and writes it to `path`.
fn save_svg(figure: &impl Figure, path: &Path) -> Result<(), PlotError> {
    let draw_error = |source| PlotError::Draw {
        path: path.to_path_buf(),
        source,
    };
    let mut document = String::new();
    {
        let root = SVGBackend::with_string(&mut document, figure.size()).into_drawing_area();
        figure.draw(&root).map_err(draw_error)?;
        root.present().map_err(|e| draw_error(err(e)))?;
    }
    write_atomic(path, document.as_bytes()).map_err(|source| PlotError::Io {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_figure_writes_png_and_svg() {
        let tmp = tempfile::tempdir().unwrap();
        // VSRLAB_FIGURE_DIR=… keeps the sample figures for a look.
        let keep = std::env::var_os("VSRLAB_FIGURE_DIR").map(PathBuf::from);
        let dir: &Path = keep.as_deref().unwrap_or(tmp.path());
        std::fs::create_dir_all(dir).unwrap();
        let series = |label: &str, color: usize, slope: f64| BandSeries {
            label: label.into(),
            color,
            x: (0..50).map(|i| i as f64 * 100.0).collect(),
            center: (0..50).map(|i| slope * (i as f64).sqrt()).collect(),
            spread: (0..50).map(|i| 0.1 * slope * (1.0 + i as f64).ln()).collect(),
        };
        let band = BandFigure {
            title: "Fitness".into(),
            legend_title: "setting".into(),
            note: band::median_sd_note(),
            panels: vec![
                BandChart {
                    title: "best".into(),
                    x_label: "evaluations".into(),
                    y_label: "velocity".into(),
                    series: vec![series("ga", 0, 1.0), series("es", 1, 0.7)],
                },
                BandChart {
                    title: "median".into(),
                    x_label: "evaluations".into(),
                    y_label: "velocity".into(),
                    series: vec![series("ga", 0, 0.5), series("es", 1, 0.3)],
                },
            ],
        };
        let boxes = BoxFigure {
            title: "Best velocity".into(),
            y_label: "velocity".into(),
            groups: vec![
                BoxGroup {
                    label: "ga".into(),
                    color: 0,
                    values: vec![1.0, 1.2, 0.9, 1.5, 1.1],
                },
                BoxGroup {
                    label: "es".into(),
                    color: 1,
                    values: vec![0.7, 0.8, 0.75, 0.9, 2.0],
                },
            ],
            pvalues: vec![(0, 1, 0.0317)],
            max_brackets: 6,
        };
        let bubbles = BubbleFigure {
            title: "Species".into(),
            x_classes: vec!["blob".into(), "limbed".into()],
            y_classes: vec!["jumping".into(), "walking".into()],
            x_label: "morphology".into(),
            y_label: "behaviour".into(),
            value_label: "best velocity".into(),
            panels: vec![BubblePanel {
                title: "ga".into(),
                bubbles: vec![
                    Bubble {
                        x: 0,
                        y: 1,
                        share: 0.7,
                        value: 1.0,
                    },
                    Bubble {
                        x: 1,
                        y: 0,
                        share: 0.3,
                        value: 2.0,
                    },
                ],
            }],
        };
        let scatter = ScatterFigure {
            title: "Descriptors".into(),
            x_label: "elongation".into(),
            y_label: "compactness".into(),
            groups: vec!["ga".into(), "es".into()],
            legend_title: "setting".into(),
            points: vec![
                ScatterPoint {
                    x: 0.2,
                    y: 0.9,
                    radius: 8.0,
                    group: 0,
                },
                ScatterPoint {
                    x: 0.7,
                    y: 0.5,
                    radius: 14.0,
                    group: 1,
                },
            ],
            x_range: Some((0.0, 1.0)),
            y_range: Some((0.0, 1.0)),
            size_legend: Some(("voxels".into(), vec![("10".into(), 6.0), ("50".into(), 14.0)])),
        };
        for (name, paths) in [
            ("band", save(&band, &dir.join("band")).unwrap()),
            ("box", save(&boxes, &dir.join("box")).unwrap()),
            ("bubble", save(&bubbles, &dir.join("bubble")).unwrap()),
            ("scatter", save(&scatter, &dir.join("scatter")).unwrap()),
        ] {
            assert_eq!(paths.len(), 2, "{name}");
            let png = std::fs::read(&paths[0]).unwrap();
            assert_eq!(&png[1..4], b"PNG", "{name}");
            let svg = std::fs::read_to_string(&paths[1]).unwrap();
            assert!(svg.contains("<svg") && svg.contains("<text"), "{name}");
        }
        if keep.is_none() {
            let mut names: Vec<String> = std::fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            names.sort();
            assert_eq!(names.len(), 8, "temporary files left behind: {names:?}");
        }
    }
}
