//! Legends: a column beside the plot with coloured squares and labels (settings), marker sizes,
//! and notes.

use super::text::anchored;
use super::{err, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// Where the first legend starts in its column, in pixels from the top.
pub(super) const LEGEND_TOP: i32 = 40;

/// `area` split into the plot on the left and, on the right, a legend column wide enough for
/// `entries` and `title`.
pub(super) fn split_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, RGBColor)],
    title: &str,
) -> (DrawingArea<DB, Shift>, DrawingArea<DB, Shift>) {
    let width = legend_width(entries, title);
    area.split_horizontally(area.dim_in_pixel().0.saturating_sub(width))
}

/// The y just under a legend of `entries` drawn at [`LEGEND_TOP`] (room for a title included).
pub(super) fn legend_bottom(entries: &[(String, RGBColor)]) -> i32 {
    LEGEND_TOP + 30 + 28 * entries.len() as i32
}

/// A legend box of coloured squares and labels, stacked from [`LEGEND_TOP`] down, in pixel
/// coordinates of `area`.
pub(super) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    entries: &[(String, RGBColor)],
) -> R {
    let mut y = LEGEND_TOP;
    if !title.is_empty() {
        draw_text_line(area, title, 18, y)?;
        y += 30;
    }
    for (label, color) in entries {
        area.draw(&Rectangle::new([(10, y + 2), (28, y + 20)], color.filled()))
            .map_err(err)?;
        draw_label(area, label, 16, (36, y + 11))?;
        y += 28;
    }
    Ok(())
}

/// The marker-size legend: a title and one grey circle per (label, radius) entry, from `top`
/// down.
pub(super) fn draw_size_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    sizes: &[(String, f64)],
    top: i32,
) -> R {
    let mut y = top;
    draw_text_line(area, title, 16, y)?;
    y += 30;
    for (label, r) in sizes {
        let r = r.max(2.0) as i32;
        area.draw(&Circle::new(
            (10 + 20, y + r),
            r,
            RGBColor(120, 120, 120).stroke_width(2),
        ))
        .map_err(err)?;
        draw_label(area, label, 14, (60, y + r))?;
        y += 2 * r + 12;
    }
    Ok(())
}

/// A line of text in the legend column (`size` pixels, its top at `y`), from the left edge.
pub(super) fn draw_text_line<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, text: &str, size: u32, y: i32) -> R {
    area.draw(&Text::new(
        text.to_string(),
        (10, y),
        anchored(size, HPos::Left, VPos::Top),
    ))
    .map_err(err)
}

/// An entry's label (`size` pixels), its left edge and vertical centre at `at`.
fn draw_label<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, label: &str, size: u32, at: (i32, i32)) -> R {
    area.draw(&Text::new(
        label.to_string(),
        at,
        anchored(size, HPos::Left, VPos::Center),
    ))
    .map_err(err)
}

/// Width of a legend column fitting the labels.
fn legend_width(entries: &[(String, RGBColor)], title: &str) -> u32 {
    let longest = entries
        .iter()
        .map(|(l, _)| l.chars().count())
        .max()
        .unwrap_or(0)
        .max(title.chars().count());
    (50 + 9 * longest as u32).clamp(120, 420)
}
