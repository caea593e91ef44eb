//! Curves: median ± sd bands across runs, side-by-side panels with one shared legend.

use super::axes::{data_range, nice_range};
use super::colors::setting_color;
use super::frame::{chart, Axis, FrameStyle};
use super::legend::{draw_legend, draw_text_line, legend_bottom, split_legend};
use super::text::text_style;
use super::{err, Figure, R};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One setting's curve: centre line and ± spread band over x.
#[derive(Debug, Clone, PartialEq)]
pub struct BandSeries {
    /// Legend label.
    pub label: String,
    /// Colour index ([`setting_color`]).
    pub color: usize,
    /// x values.
    pub x: Vec<f64>,
    /// Centre (e.g. median across runs); NaN points are skipped.
    pub center: Vec<f64>,
    /// Half-width of the band (e.g. sd across runs).
    pub spread: Vec<f64>,
}

/// One panel of curves.
#[derive(Debug, Clone, PartialEq)]
pub struct BandChart {
    /// Panel title.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// The curves.
    pub series: Vec<BandSeries>,
}

/// Side-by-side panels of median ± sd curves with one shared legend.
#[derive(Debug, Clone, PartialEq)]
pub struct BandFigure {
    /// Figure title.
    pub title: String,
    /// Panels, left to right.
    pub panels: Vec<BandChart>,
    /// Legend title (e.g. "setting").
    pub legend_title: String,
    /// Lines under the legend saying what lines and bands show ([`median_sd_note`] for curves
    /// across runs).
    pub note: Vec<String>,
}

/// The note of median ± sd curves across runs.
pub fn median_sd_note() -> Vec<String> {
    ["line: median", "band: ± sd", "(across runs)"]
        .map(String::from)
        .to_vec()
}

impl BandSeries {
    /// The drawn points: (x, centre, spread) where x and the centre are finite, a non-finite
    /// spread read as 0.
    fn points(&self) -> impl Iterator<Item = (f64, f64, f64)> + '_ {
        self.x
            .iter()
            .zip(&self.center)
            .zip(&self.spread)
            .filter(|((x, c), _)| x.is_finite() && c.is_finite())
            .map(|((x, c), sd)| (*x, *c, if sd.is_finite() { *sd } else { 0.0 }))
    }
}

impl BandChart {
    fn draw_on<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> R {
        let pts = || self.series.iter().flat_map(BandSeries::points);
        let (x0, x1) = data_range(pts().map(|(x, _, _)| x));
        let (y0, y1) = pts().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (_, c, s)| {
            (a.min(c - s), b.max(c + s))
        });
        let (y0, y1) = nice_range(y0, y1, 0.05);
        let style = FrameStyle {
            caption: 22,
            margin: 12,
            label_areas: (55, 80),
            grid: (RGBColor(242, 242, 242), RGBColor(215, 215, 215)),
            ..FrameStyle::default()
        };
        let x = Axis::numbers(x0..x1, &self.x_label);
        let mut chart = chart(area, &self.title, &style, x, Axis::numbers(y0..y1, &self.y_label))?;
        for s in &self.series {
            let color = setting_color(s.color);
            let ok: Vec<(f64, f64, f64)> = s.points().collect();
            if ok.is_empty() {
                continue;
            }
            let mut band: Vec<(f64, f64)> = ok.iter().map(|&(x, c, s)| (x, c + s)).collect();
            band.extend(ok.iter().rev().map(|&(x, c, s)| (x, c - s)));
            chart
                .draw_series(std::iter::once(Polygon::new(band, color.mix(0.18))))
                .map_err(err)?;
            chart
                .draw_series(LineSeries::new(
                    ok.iter().map(|&(x, c, _)| (x, c)),
                    color.stroke_width(3),
                ))
                .map_err(err)?;
        }
        Ok(())
    }
}

impl Figure for BandFigure {
    fn size(&self) -> (u32, u32) {
        let per_panel = if self.panels.len() >= 3 { 560 } else { 700 };
        (per_panel * self.panels.len().max(1) as u32 + 240, 620)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> R {
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, text_style(26)).map_err(err)?;
        let mut entries: Vec<(String, RGBColor)> = Vec::new();
        for p in &self.panels {
            for s in &p.series {
                if !entries.iter().any(|(l, _)| l == &s.label) {
                    entries.push((s.label.clone(), setting_color(s.color)));
                }
            }
        }
        let (plots, legend) = split_legend(&root, &entries, &self.legend_title);
        let n = self.panels.len().max(1);
        let w = plots.dim_in_pixel().0 as usize / n;
        let breaks: Vec<i32> = (1..n).map(|i| (i * w) as i32).collect();
        for (panel, area) in self
            .panels
            .iter()
            .zip(plots.split_by_breakpoints(breaks, Vec::<i32>::new()))
        {
            panel.draw_on(&area)?;
        }
        draw_legend(&legend, &self.legend_title, &entries)?;
        let y = legend_bottom(&entries) + 10;
        for (k, line) in self.note.iter().enumerate() {
            draw_text_line(&legend, line, 13, y + 18 * k as i32)?;
        }
        Ok(())
    }
}
