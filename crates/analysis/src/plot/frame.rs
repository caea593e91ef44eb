//! Chart frames: the titled cartesian chart every figure kind draws its data in, with its axes
//! (numbers or class names), their labels and the grid.

use super::axes::{class_tick, format_tick_within};
use super::text::text_style;
use super::{err, DrawError};
use plotters::coord::cartesian::Cartesian2d;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;

/// A chart with values along both axes.
pub(super) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// One axis of a chart.
pub(super) struct Axis<'a> {
    /// The values shown.
    range: Range<f64>,
    /// The axis label (None: none).
    label: Option<&'a str>,
    /// Class names at integer positions, or None for numbers.
    classes: Option<&'a [String]>,
}

impl<'a> Axis<'a> {
    /// A numeric axis over `range`, labelled `label`, ticks by [`format_tick_within`].
    pub(super) fn numbers(range: Range<f64>, label: &'a str) -> Axis<'a> {
        Axis {
            range,
            label: Some(label),
            classes: None,
        }
    }

    /// A categorical axis over `range`: class `i` at position `i`, labelled `label` (if any).
    pub(super) fn classes(range: Range<f64>, classes: &'a [String], label: Option<&'a str>) -> Axis<'a> {
        Axis {
            range,
            label,
            classes: Some(classes),
        }
    }

    /// The tick label at `v`.
    fn tick(&self, v: f64) -> String {
        match self.classes {
            Some(classes) => class_tick(v, classes),
            None => format_tick_within(v, self.range.end - self.range.start),
        }
    }

    /// How many tick labels plotters is asked for: one per class and one between classes (left
    /// blank), or plotters' default for numbers.
    fn tick_count(&self) -> Option<usize> {
        self.classes.map(|c| c.len() * 2 + 1)
    }
}

/// How a chart frame looks.
pub(super) struct FrameStyle {
    /// Text size of the caption.
    pub caption: u32,
    /// Margin around the chart, in pixels.
    pub margin: u32,
    /// Height of the x label area and width of the y label area, in pixels.
    pub label_areas: (u32, u32),
    /// Text sizes of the tick labels and of the axis labels.
    pub text: (u32, u32),
    /// Colours of the light and the bold grid lines.
    pub grid: (RGBColor, RGBColor),
    /// Most light grid lines between two bold ones.
    pub max_light_lines: usize,
    /// Whether grid lines cross the x axis (vertical lines).
    pub x_grid: bool,
}

impl Default for FrameStyle {
    /// The frame of the single-chart figures (boxplots, scatters).
    fn default() -> FrameStyle {
        FrameStyle {
            caption: 24,
            margin: 15,
            label_areas: (60, 85),
            text: (15, 18),
            grid: (RGBColor(244, 244, 244), RGBColor(220, 220, 220)),
            max_light_lines: 2,
            x_grid: true,
        }
    }
}

/// A chart on `area` captioned `title`, with axes `x` and `y` and their grid drawn.
pub(super) fn chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    style: &FrameStyle,
    x: Axis<'_>,
    y: Axis<'_>,
) -> Result<Chart<'a, DB>, DrawError> {
    let mut chart = ChartBuilder::on(area)
        .caption(title, text_style(style.caption))
        .margin(style.margin)
        .x_label_area_size(style.label_areas.0)
        .y_label_area_size(style.label_areas.1)
        .build_cartesian_2d(x.range.clone(), y.range.clone())
        .map_err(err)?;
    let x_tick = |v: &f64| x.tick(*v);
    let y_tick = |v: &f64| y.tick(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .label_style(text_style(style.text.0))
        .axis_desc_style(text_style(style.text.1))
        .max_light_lines(style.max_light_lines)
        .light_line_style(style.grid.0)
        .bold_line_style(style.grid.1);
    if !style.x_grid {
        mesh.disable_x_mesh();
    }
    if let Some(n) = x.tick_count() {
        mesh.x_labels(n);
    }
    if let Some(n) = y.tick_count() {
        mesh.y_labels(n);
    }
    if let Some(label) = x.label {
        mesh.x_desc(label);
    }
    if let Some(label) = y.label {
        mesh.y_desc(label);
    }
    mesh.draw().map_err(err)?;
    Ok(chart)
}
