//! Bubble plots: the species of populations, bubble area ∝ share, colour = value.

use super::axes::{data_range, format_tick_within};
use super::colors::viridis;
use super::frame::{chart, Axis, FrameStyle};
use super::text::{anchored, text_style};
use super::{err, Figure, R};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

/// One bubble: a (shape class, behaviour class) species.
#[derive(Debug, Clone, PartialEq)]
pub struct Bubble {
    /// Index into [`BubbleFigure::x_classes`].
    pub x: usize,
    /// Index into [`BubbleFigure::y_classes`].
    pub y: usize,
    /// Share of the individuals, in [0, 1].
    pub share: f64,
    /// Colour value (best velocity of the species).
    pub value: f64,
}

/// One panel of bubbles (e.g. one setting).
#[derive(Debug, Clone, PartialEq)]
pub struct BubblePanel {
    /// Panel title.
    pub title: String,
    /// The bubbles.
    pub bubbles: Vec<Bubble>,
}

/// Species bubble plot: x = morphology class, y = behaviour class, area ∝ share, colour = value
/// on a shared viridis scale with a colour bar.
#[derive(Debug, Clone, PartialEq)]
pub struct BubbleFigure {
    /// Title.
    pub title: String,
    /// x classes (morphology).
    pub x_classes: Vec<String>,
    /// y classes (behaviour).
    pub y_classes: Vec<String>,
    /// x-axis label.
    pub x_label: String,
    /// y-axis label.
    pub y_label: String,
    /// Colour-bar label.
    pub value_label: String,
    /// Panels, in a row (wrapping after 3).
    pub panels: Vec<BubblePanel>,
}

impl Figure for BubbleFigure {
    fn size(&self) -> (u32, u32) {
        let n = self.panels.len().max(1) as u32;
        let cols = n.min(3);
        let rows = n.div_ceil(3);
        (cols * 520 + 170, rows * 480 + 60)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> R {
        root.fill(&WHITE).map_err(err)?;
        let root = root.titled(&self.title, text_style(26)).map_err(err)?;
        let (w, _) = root.dim_in_pixel();
        let (plots, bar) = root.split_horizontally(w.saturating_sub(170));
        let range = self.value_range();
        let n = self.panels.len().max(1);
        let cols = n.min(3);
        let rows = n.div_ceil(3);
        let areas = plots.split_evenly((rows, cols));
        for (panel, area) in self.panels.iter().zip(areas) {
            self.draw_panel(panel, &area, range)?;
        }
        self.draw_color_bar(&bar, range)
    }
}

impl BubbleFigure {
    /// The range of the finite bubble values (0..1 without any), shared by every panel.
    fn value_range(&self) -> (f64, f64) {
        let values = self
            .panels
            .iter()
            .flat_map(|p| p.bubbles.iter().map(|b| b.value))
            .filter(|v| v.is_finite());
        data_range(values)
    }

    /// One panel: the class grid and its bubbles, each labelled with its share.
    fn draw_panel<DB: DrawingBackend>(
        &self,
        panel: &BubblePanel,
        area: &DrawingArea<DB, Shift>,
        (vmin, vmax): (f64, f64),
    ) -> R {
        let (nx, ny) = (self.x_classes.len(), self.y_classes.len());
        let style = FrameStyle {
            caption: 19,
            margin: 10,
            label_areas: (60, 100),
            text: (14, 16),
            grid: (WHITE, RGBColor(230, 230, 230)),
            max_light_lines: 10, // plotters' default
            ..FrameStyle::default()
        };
        let x = Axis::classes(-0.5..(nx as f64 - 0.5), &self.x_classes, Some(&self.x_label));
        let y = Axis::classes(-0.5..(ny as f64 - 0.5), &self.y_classes, Some(&self.y_label));
        let mut chart = chart(area, &panel.title, &style, x, y)?;
        let (pw, ph) = area.dim_in_pixel();
        let cell =
            ((pw.saturating_sub(110)) as f64 / nx.max(1) as f64).min((ph.saturating_sub(90)) as f64 / ny.max(1) as f64);
        let max_r = (cell * 0.48).max(4.0);
        for b in &panel.bubbles {
            if b.share <= 0.0 {
                continue;
            }
            let r = (max_r * b.share.sqrt()).max(3.0) as i32;
            let c = viridis((b.value - vmin) / (vmax - vmin));
            let (x, y) = (b.x as f64, b.y as f64);
            chart
                .draw_series([
                    Circle::new((x, y), r, c.mix(0.9).filled()),
                    Circle::new((x, y), r, BLACK.stroke_width(1)),
                ])
                .map_err(err)?;
            let label = format!("{:.0}%", b.share * 100.0);
            let light = (c.0 as u32 + c.1 as u32 + c.2 as u32) < 330;
            let style = anchored(13, HPos::Center, VPos::Center).color(if light { &WHITE } else { &BLACK });
            if r >= 14 {
                chart
                    .draw_series(std::iter::once(Text::new(label, (x, y), style)))
                    .map_err(err)?;
            } else {
                // Right of the bubble: r + 4 pixels, in data units.
                let ppu = chart.plotting_area().dim_in_pixel().0 as f64 / nx.max(1) as f64;
                let right = anchored(12, HPos::Left, VPos::Center);
                let at = (x + (r as f64 + 4.0) / ppu.max(1.0), y);
                chart.plotting_area().draw(&Text::new(label, at, right)).map_err(err)?;
            }
        }
        Ok(())
    }

    /// The viridis colour bar of the values, with five ticks.
    fn draw_color_bar<DB: DrawingBackend>(&self, bar: &DrawingArea<DB, Shift>, (vmin, vmax): (f64, f64)) -> R {
        let (_, bh) = bar.dim_in_pixel();
        let (top, bottom) = (70i32, (bh as i32 - 90).max(120));
        bar.draw(&Text::new(
            self.value_label.clone(),
            (15, top - 40),
            anchored(15, HPos::Left, VPos::Top),
        ))
        .map_err(err)?;
        let steps = 64;
        for k in 0..steps {
            let t0 = k as f64 / steps as f64;
            let y0 = bottom - ((bottom - top) as f64 * t0) as i32;
            let y1 = bottom - ((bottom - top) as f64 * (k + 1) as f64 / steps as f64) as i32;
            bar.draw(&Rectangle::new(
                [(20, y1), (45, y0)],
                viridis(t0 + 0.5 / steps as f64).filled(),
            ))
            .map_err(err)?;
        }
        bar.draw(&Rectangle::new([(20, top), (45, bottom)], BLACK.stroke_width(1)))
            .map_err(err)?;
        for k in 0..=4 {
            let t = k as f64 / 4.0;
            let y = bottom - ((bottom - top) as f64 * t) as i32;
            bar.draw(&PathElement::new(vec![(45, y), (50, y)], BLACK.stroke_width(1)))
                .map_err(err)?;
            let v = vmin + (vmax - vmin) * t;
            bar.draw(&Text::new(
                format_tick_within(v, vmax - vmin),
                (54, y),
                anchored(13, HPos::Left, VPos::Center),
            ))
            .map_err(err)?;
        }
        bar.draw(&Text::new(
            "area ∝ share".to_string(),
            (15, bottom + 25),
            anchored(13, HPos::Left, VPos::Top),
        ))
        .map_err(err)?;
        Ok(())
    }
}
