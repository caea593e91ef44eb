//! Scatter plots: points coloured by setting, marker size as a third variable.

use super::axes::{format_tick, nice_range};
use super::colors::setting_color;
use super::legend::{draw_legend, legend_width};
use super::text::{anchored, text_style};
use super::{err, Figure, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

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
        let lw = legend_width(&entries, &self.legend_title);
        let (plot, legend) = root.split_horizontally(root.dim_in_pixel().0.saturating_sub(lw));
        let fit = |f: &dyn Fn(&ScatterPoint) -> f64| {
            let (a, b) = self
                .points
                .iter()
                .map(f)
                .filter(|v| v.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
            nice_range(a, b, 0.08)
        };
        let (x0, x1) = self.x_range.unwrap_or_else(|| fit(&|p| p.x));
        let (y0, y1) = self.y_range.unwrap_or_else(|| fit(&|p| p.y));
        let mut chart = ChartBuilder::on(&plot)
            .caption(&self.title, text_style(24))
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(85)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style(text_style(15))
            .axis_desc_style(text_style(18))
            .max_light_lines(2)
            .light_line_style(RGBColor(244, 244, 244))
            .bold_line_style(RGBColor(220, 220, 220))
            .x_label_formatter(&|v| format_tick(*v))
            .y_label_formatter(&|v| format_tick(*v))
            .draw()
            .map_err(err)?;
        // Larger markers first so small ones stay visible.
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
                    Circle::new((p.x, p.y), r, c.mix(0.6).filled()),
                    Circle::new((p.x, p.y), r, c.stroke_width(2)),
                ])
                .map_err(err)?;
        }
        draw_legend(&legend, &self.legend_title, &entries, 40)?;
        match &self.size_legend {
            Some((title, sizes)) => draw_size_legend(&legend, title, sizes, 40 + 30 + 28 * entries.len() as i32 + 30),
            None => Ok(()),
        }
    }
}

/// The marker-size legend: a title and one circle per (label, radius) entry, from `top` down.
fn draw_size_legend<DB: DrawingBackend>(
    legend: &DrawingArea<DB, Shift>,
    title: &str,
    sizes: &[(String, f64)],
    top: i32,
) -> R {
    let mut y = top;
    legend
        .draw(&Text::new(
            title.to_string(),
            (10, y),
            anchored(16, HPos::Left, VPos::Top),
        ))
        .map_err(err)?;
    y += 30;
    for (label, r) in sizes {
        let r = r.max(2.0) as i32;
        legend
            .draw(&Circle::new(
                (10 + 20, y + r),
                r,
                RGBColor(120, 120, 120).stroke_width(2),
            ))
            .map_err(err)?;
        legend
            .draw(&Text::new(
                label.clone(),
                (60, y + r),
                anchored(14, HPos::Left, VPos::Center),
            ))
            .map_err(err)?;
        y += 2 * r + 12;
    }
    Ok(())
}
