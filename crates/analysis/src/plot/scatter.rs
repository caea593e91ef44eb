//! Scatter plots: points coloured by setting, marker size as a third variable.

use super::axes::{extent, nice_range};
use super::colors::setting_color;
use super::frame::{chart, Axis, FrameStyle};
use super::legend::{draw_legend, draw_size_legend, legend_bottom, split_legend};
use super::{err, Figure, R};
use plotters::coord::Shift;
use plotters::prelude::*;

/// One point of a scatter.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatterPoint {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// Marker radius in pixels.
    pub radius: f64,
    /// Group (setting) index ([`setting_color`] and legend order).
    pub group: usize,
}

/// Scatter plot coloured by group, optionally with a marker-size legend.
#[derive(Debug, Clone, PartialEq)]
pub struct ScatterFigure {
    /// Title.
    pub title: String,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// Group labels, by group index.
    pub groups: Vec<String>,
    /// Legend title.
    pub legend_title: String,
    /// The points.
    pub points: Vec<ScatterPoint>,
    /// Fixed axis ranges (None: fitted to the data).
    pub x_range: Option<(f64, f64)>,
    /// Fixed axis ranges (None: fitted to the data).
    pub y_range: Option<(f64, f64)>,
    /// Marker-size legend: title and (label, radius) entries.
    pub size_legend: Option<(String, Vec<(String, f64)>)>,
}

impl Figure for ScatterFigure {
    fn size(&self) -> (u32, u32) {
        (1100, 800)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> R {
        root.fill(&WHITE).map_err(err)?;
        let entries: Vec<(String, RGBColor)> = self
            .groups
            .iter()
            .enumerate()
            .map(|(i, g)| (g.clone(), setting_color(i)))
            .collect();
        let (plot, legend) = split_legend(root, &entries, &self.legend_title);
        let fit = |f: &dyn Fn(&ScatterPoint) -> f64| {
            let (a, b) = extent(self.points.iter().map(f).filter(|v| v.is_finite()));
            nice_range(a, b, 0.08)
        };
        let (x0, x1) = self.x_range.unwrap_or_else(|| fit(&|p| p.x));
        let (y0, y1) = self.y_range.unwrap_or_else(|| fit(&|p| p.y));
        let x = Axis::numbers(x0..x1, &self.x_label);
        let y = Axis::numbers(y0..y1, &self.y_label);
        let mut chart = chart(&plot, &self.title, &FrameStyle::default(), x, y)?;
        // Larger markers first so small ones stay visible; fills are 30 % opaque so markers of
        // several settings at one place blend instead of hiding each other.
        let mut order: Vec<&ScatterPoint> = self
            .points
            .iter()
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .collect();
        order.sort_by(|a, b| b.radius.total_cmp(&a.radius));
        for p in order {
            let c = setting_color(p.group);
            let r = p.radius.max(2.0) as i32;
            chart
                .draw_series([
                    Circle::new((p.x, p.y), r, c.mix(0.3).filled()),
                    Circle::new((p.x, p.y), r, c.stroke_width(2)),
                ])
                .map_err(err)?;
        }
        draw_legend(&legend, &self.legend_title, &entries)?;
        match &self.size_legend {
            Some((title, sizes)) => draw_size_legend(&legend, title, sizes, legend_bottom(&entries) + 30),
            None => Ok(()),
        }
    }
}
