//! Legends: a column of coloured squares and labels beside the plot.

use super::text::anchored;
use super::{err, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// A legend box of coloured squares and labels, stacked, in pixel coordinates of `area`.
pub(super) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    entries: &[(String, RGBColor)],
    top: i32,
) -> R {
    let mut y = top;
    if !title.is_empty() {
        area.draw(&Text::new(
            title.to_string(),
            (10, y),
            anchored(18, HPos::Left, VPos::Top),
        ))
        .map_err(err)?;
        y += 30;
    }
    for (label, color) in entries {
        area.draw(&Rectangle::new([(10, y + 2), (28, y + 20)], color.filled()))
            .map_err(err)?;
        area.draw(&Text::new(
            label.clone(),
            (36, y + 11),
            anchored(16, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
        y += 28;
    }
    Ok(())
}

/// Width of a legend column fitting the labels.
pub(super) fn legend_width(entries: &[(String, RGBColor)], title: &str) -> u32 {
    let longest = entries
        .iter()
        .map(|(l, _)| l.chars().count())
        .max()
        .unwrap_or(0)
        .max(title.chars().count());
    (50 + 9 * longest as u32).clamp(120, 420)
}
