//! Boxplots: one box per setting, every run as a dot, pairwise p-values as brackets.

use super::axes::{format_tick, nice_range};
use super::colors::setting_color;
use super::text::{anchored, text_style};
use super::{err, DrawError, Figure, R};
use plotters::coord::cartesian::Cartesian2d;
use plotters::coord::types::RangedCoordf64;
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

/// The chart of a boxplot: setting index along x, values along y.
type BoxChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

impl BoxFigure {
    /// The range of the finite values, with a margin.
    fn value_range(&self) -> (f64, f64) {
        let vals = self
            .groups
            .iter()
            .flat_map(|g| g.values.iter().copied().filter(|v| v.is_finite()));
        let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
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
    ) -> Result<BoxChart<'a, DB>, DrawError> {
        let n = self.groups.len();
        let labels: Vec<String> = self.groups.iter().map(|g| g.label.clone()).collect();
        let long = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
        let bottom_area = if long * 9 > 160 { 120 } else { 75 };
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, text_style(24))
            .margin(15)
            .x_label_area_size(bottom_area)
            .y_label_area_size(85)
            .build_cartesian_2d(-0.6..(n as f64 - 0.4), y)
            .map_err(err)?;
        let fmt_x = |v: &f64| {
            let i = v.round();
            if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < n {
                labels[i as usize].clone()
            } else {
                String::new()
            }
        };
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(n * 2 + 1)
            .x_label_formatter(&fmt_x)
            .y_label_formatter(&|v| format_tick(*v))
            .y_desc(&self.y_label)
            .label_style(text_style(15))
            .axis_desc_style(text_style(18))
            .max_light_lines(2)
            .light_line_style(RGBColor(244, 244, 244))
            .bold_line_style(RGBColor(220, 220, 220))
            .draw()
            .map_err(err)?;
        Ok(chart)
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
fn draw_box<DB: DrawingBackend>(chart: &mut BoxChart<'_, DB>, x: f64, g: &BoxGroup) -> R {
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
fn draw_bracket<DB: DrawingBackend>(
    chart: &mut BoxChart<'_, DB>,
    (i, j, p): (usize, usize, f64),
    y: f64,
    tick: f64,
) -> R {
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
