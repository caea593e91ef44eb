//! Boxplots: one box per setting, every run as a dot, pairwise p-values as brackets.

use super::axes::{extent, nice_range};
use super::colors::setting_color;
use super::frame::{chart, Axis, Chart, FrameStyle};
use super::text::anchored;
use super::{err, DrawError, Figure, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// One box of a boxplot.
#[derive(Debug, Clone, PartialEq)]
pub struct BoxGroup {
    /// Tick label.
    pub label: String,
    /// Colour index ([`setting_color`]).
    pub color: usize,
    /// The values (one per run).
    pub values: Vec<f64>,
}

/// Boxplots per setting, every value drawn as a dot, with pairwise p-values as brackets (up to
/// `max_brackets` pairs; more are listed in a note).
#[derive(Debug, Clone, PartialEq)]
pub struct BoxFigure {
    /// Title.
    pub title: String,
    /// y-axis label.
    pub y_label: String,
    /// Boxes, left to right.
    pub groups: Vec<BoxGroup>,
    /// (i, j, p) for the pairs to annotate.
    pub pvalues: Vec<(usize, usize, f64)>,
    /// Most brackets drawn.
    pub max_brackets: usize,
}

/// p-value as text: "p = 0.012", "p < 0.001".
pub fn format_p(p: f64) -> String {
    if !p.is_finite() {
        "p = n/a".into()
    } else if p < 0.001 {
        "p < 0.001".into()
    } else {
        format!("p = {p:.3}")
    }
}

impl Figure for BoxFigure {
    fn size(&self) -> (u32, u32) {
        ((260 + 170 * self.groups.len() as u32).max(700), 760)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> R {
        root.fill(&WHITE).map_err(err)?;
        let (lo, hi) = self.value_range();
        let brackets = self.brackets();
        let step = (hi - lo) * 0.09;
        let top = hi + step * (brackets.len() as f64 + 0.3);
        let mut chart = self.chart(root, lo..top)?;
        for (i, g) in self.groups.iter().enumerate() {
            draw_box(&mut chart, i as f64, g)?;
        }
        for (level, &pair) in brackets.iter().enumerate() {
            draw_bracket(&mut chart, pair, hi + step * (level as f64 + 0.3), step * 0.25)?;
        }
        self.draw_note(root, !brackets.is_empty())
    }
}

impl BoxFigure {
    /// The range of the finite values, with a margin.
    fn value_range(&self) -> (f64, f64) {
        let vals = self
            .groups
            .iter()
            .flat_map(|g| g.values.iter().copied().filter(|v| v.is_finite()));
        let (lo, hi) = extent(vals);
        nice_range(lo, hi, 0.06)
    }

    /// The pairs drawn as brackets: all of them, or none when there are more than
    /// `max_brackets`.
    fn brackets(&self) -> Vec<(usize, usize, f64)> {
        if self.pvalues.len() <= self.max_brackets {
            self.pvalues.clone()
        } else {
            Vec::new()
        }
    }

    /// The titled chart with its mesh, settings as x tick labels, values `y` along y.
    fn chart<'a, DB: DrawingBackend>(
        &self,
        root: &'a DrawingArea<DB, Shift>,
        y: std::ops::Range<f64>,
    ) -> Result<Chart<'a, DB>, DrawError> {
        let labels: Vec<String> = self.groups.iter().map(|g| g.label.clone()).collect();
        let long = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
        let style = FrameStyle {
            label_areas: (if long * 9 > 160 { 120 } else { 75 }, 85),
            x_grid: false,
            ..FrameStyle::default()
        };
        let x = Axis::classes(-0.6..(labels.len() as f64 - 0.4), &labels, None);
        chart(root, &self.title, &style, x, Axis::numbers(y, &self.y_label))
    }

    /// The note under the chart: what the brackets are, or where the p-values went.
    fn draw_note<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, brackets: bool) -> R {
        let (w, h) = root.dim_in_pixel();
        let note = if !brackets && !self.pvalues.is_empty() {
            format!(
                "{} pairwise two-sided Mann–Whitney U p-values: see summary.md",
                self.pvalues.len()
            )
        } else if brackets {
            "brackets: two-sided Mann–Whitney U p-values".to_string()
        } else {
            String::new()
        };
        if !note.is_empty() {
            root.draw(&Text::new(
                note,
                (w as i32 / 2, h as i32 - 8),
                anchored(14, HPos::Center, VPos::Bottom),
            ))
            .map_err(err)?;
        }
        Ok(())
    }
}

/// The box of group `g` at x: quartiles, median, whiskers, and every run as a dot.
fn draw_box<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, x: f64, g: &BoxGroup) -> R {
    let color = setting_color(g.color);
    let Some(b) = crate::stats::BoxStats::of(&g.values) else {
        return Ok(());
    };
    let hw = 0.3;
    chart
        .draw_series([
            Rectangle::new([(x - hw, b.q1), (x + hw, b.q3)], color.mix(0.35).filled()),
            Rectangle::new([(x - hw, b.q1), (x + hw, b.q3)], color.stroke_width(2)),
        ])
        .map_err(err)?;
    let line = |pts: Vec<(f64, f64)>, w: u32| PathElement::new(pts, BLACK.stroke_width(w));
    chart
        .draw_series([
            line(vec![(x - hw, b.median), (x + hw, b.median)], 3),
            line(vec![(x, b.q3), (x, b.high)], 1),
            line(vec![(x, b.q1), (x, b.low)], 1),
            line(vec![(x - hw / 2.0, b.high), (x + hw / 2.0, b.high)], 1),
            line(vec![(x - hw / 2.0, b.low), (x + hw / 2.0, b.low)], 1),
        ])
        .map_err(err)?;
    // Every run as a dot, spread deterministically across the box.
    let m = g.values.len().max(1);
    chart
        .draw_series(
            g.values
                .iter()
                .enumerate()
                .filter(|(_, v)| v.is_finite())
                .map(|(k, &v)| {
                    let jitter = ((k as f64 + 0.5) / m as f64 - 0.5) * hw * 1.2;
                    Circle::new((x + jitter, v), 4, BLACK.mix(0.75).filled())
                }),
        )
        .map_err(err)?;
    Ok(())
}

/// A bracket between boxes i and j at height y (ticks `tick` long), labelled with p.
fn draw_bracket<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, (i, j, p): (usize, usize, f64), y: f64, tick: f64) -> R {
    let (a, b) = (i.min(j) as f64, i.max(j) as f64);
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(a, y - tick), (a, y), (b, y), (b, y - tick)],
            BLACK.stroke_width(1),
        )))
        .map_err(err)?;
    chart
        .draw_series(std::iter::once(Text::new(
            format_p(p),
            ((a + b) / 2.0, y),
            anchored(15, HPos::Center, VPos::Bottom),
        )))
        .map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p_values_read_well() {
        assert_eq!(format_p(0.0123), "p = 0.012");
        assert_eq!(format_p(1e-5), "p < 0.001");
    }
}
