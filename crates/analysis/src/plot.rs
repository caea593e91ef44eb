//! Figures (PNG through plotters' bitmap backend, SVG through its SVG backend): median ± sd
//! bands, boxplots with pairwise p-values, species bubble plots and scatters.
//!
//! Text is drawn with DejaVu Sans, bundled in the crate (`assets/`, Bitstream Vera licence) and
//! registered with plotters' `ab_glyph` feature, so no system font is looked up. Settings get
//! the colours of [`setting_color`] by their index, the same in every figure.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};
use std::sync::Once;

const FONT: &str = "sans-serif";
static FONT_BYTES: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

fn register_font() {
    REGISTER.call_once(|| {
        if plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES).is_err() {
            panic!("the bundled DejaVu Sans font is valid");
        }
    });
}

/// Tableau 10: distinct, print- and colour-blind-friendly enough for up to 10 settings.
const PALETTE: [(u8, u8, u8); 10] = [
    (0x4E, 0x79, 0xA7),
    (0xF2, 0x8E, 0x2B),
    (0xE1, 0x57, 0x59),
    (0x76, 0xB7, 0xB2),
    (0x59, 0xA1, 0x4F),
    (0xED, 0xC9, 0x48),
    (0xB0, 0x7A, 0xA1),
    (0xFF, 0x9D, 0xA7),
    (0x9C, 0x75, 0x5F),
    (0xBA, 0xB0, 0xAC),
];

/// The colour of setting number `i` (cycling after 10).
pub fn setting_color(i: usize) -> RGBColor {
    let (r, g, b) = PALETTE[i % PALETTE.len()];
    RGBColor(r, g, b)
}

/// Viridis-like colour map, t ∈ [0, 1] (linear interpolation between 9 anchors of viridis).
pub fn viridis(t: f64) -> RGBColor {
    const ANCHORS: [(u8, u8, u8); 9] = [
        (0x44, 0x01, 0x54),
        (0x47, 0x2C, 0x7A),
        (0x3B, 0x51, 0x8B),
        (0x2C, 0x71, 0x8E),
        (0x21, 0x90, 0x8D),
        (0x27, 0xAD, 0x81),
        (0x5C, 0xC8, 0x63),
        (0xAA, 0xDC, 0x32),
        (0xFD, 0xE7, 0x25),
    ];
    let t = if t.is_finite() { t.clamp(0.0, 1.0) } else { 0.0 };
    let pos = t * (ANCHORS.len() - 1) as f64;
    let i = (pos.floor() as usize).min(ANCHORS.len() - 2);
    let f = pos - i as f64;
    let lerp = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    let (a, b) = (ANCHORS[i], ANCHORS[i + 1]);
    RGBColor(lerp(a.0, b.0), lerp(a.1, b.1), lerp(a.2, b.2))
}

/// Why a figure could not be written.
#[derive(Debug, thiserror::Error)]
#[error("figure {path}: {msg}")]
pub struct PlotError {
    /// The file.
    pub path: String,
    /// What went wrong.
    pub msg: String,
}

type R = Result<(), String>;

fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// A figure that can be drawn on any plotters backend.
pub trait Figure {
    /// Size in pixels (PNG) or user units (SVG).
    fn size(&self) -> (u32, u32) {
        (1200, 800)
    }
    /// Draws the figure on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> R;
}

/// Writes `figure` as `<stem>.png` and `<stem>.svg`; returns the two paths.
pub fn save(figure: &impl Figure, stem: &Path) -> Result<Vec<PathBuf>, PlotError> {
    register_font();
    let png = stem.with_extension("png");
    let svg = stem.with_extension("svg");
    let size = figure.size();
    let fail = |p: &Path, msg: String| PlotError {
        path: p.display().to_string(),
        msg,
    };
    {
        let root = BitMapBackend::new(&png, size).into_drawing_area();
        figure.draw(&root).map_err(|m| fail(&png, m))?;
        root.present().map_err(|e| fail(&png, e.to_string()))?;
    }
    {
        let root = SVGBackend::new(&svg, size).into_drawing_area();
        figure.draw(&root).map_err(|m| fail(&svg, m))?;
        root.present().map_err(|e| fail(&svg, e.to_string()))?;
    }
    Ok(vec![png, svg])
}

fn text_style(size: u32) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).color(&BLACK)
}

fn anchored(size: u32, h: HPos, v: VPos) -> TextStyle<'static> {
    text_style(size).pos(Pos::new(h, v))
}

/// A legend box of coloured squares and labels, stacked, in pixel coordinates of `area`.
fn draw_legend<DB: DrawingBackend>(
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
fn legend_width(entries: &[(String, RGBColor)], title: &str) -> u32 {
    let longest = entries
        .iter()
        .map(|(l, _)| l.chars().count())
        .max()
        .unwrap_or(0)
        .max(title.chars().count());
    (50 + 9 * longest as u32).clamp(120, 420)
}

fn nice_range(lo: f64, hi: f64, pad: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    if hi - lo < 1e-12 {
        let d = if lo.abs() > 1e-12 { lo.abs() * 0.1 } else { 1.0 };
        return (lo - d, hi + d);
    }
    let d = (hi - lo) * pad;
    (lo - d, hi + d)
}

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
}

impl BandChart {
    fn draw_on<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> R {
        let pts = || {
            self.series.iter().flat_map(|s| {
                s.x.iter()
                    .zip(&s.center)
                    .zip(&s.spread)
                    .filter(|((x, c), _)| x.is_finite() && c.is_finite())
            })
        };
        let (x0, x1) = pts().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), ((x, _), _)| {
            (a.min(*x), b.max(*x))
        });
        let (y0, y1) = pts().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), ((_, c), s)| {
            let s = if s.is_finite() { *s } else { 0.0 };
            (a.min(c - s), b.max(c + s))
        });
        let (x0, x1) = if x0.is_finite() {
            (x0, x1.max(x0 + 1e-9))
        } else {
            (0.0, 1.0)
        };
        let (y0, y1) = nice_range(y0, y1, 0.05);
        let mut chart = ChartBuilder::on(area)
            .caption(&self.title, text_style(22))
            .margin(12)
            .x_label_area_size(55)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style(text_style(15))
            .axis_desc_style(text_style(18))
            .max_light_lines(2)
            .light_line_style(RGBColor(242, 242, 242))
            .bold_line_style(RGBColor(215, 215, 215))
            .x_label_formatter(&|v| format_tick(*v))
            .y_label_formatter(&|v| format_tick(*v))
            .draw()
            .map_err(err)?;
        for s in &self.series {
            let color = setting_color(s.color);
            let ok: Vec<(f64, f64, f64)> =
                s.x.iter()
                    .zip(&s.center)
                    .zip(&s.spread)
                    .filter(|((x, c), _)| x.is_finite() && c.is_finite())
                    .map(|((x, c), sd)| (*x, *c, if sd.is_finite() { *sd } else { 0.0 }))
                    .collect();
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

/// Tick label: short, without trailing zeros; thousands as "k" above 10 000.
pub fn format_tick(v: f64) -> String {
    let a = v.abs();
    if a >= 10_000.0 {
        let k = v / 1000.0;
        if (k - k.round()).abs() < 1e-9 {
            format!("{}k", k.round())
        } else {
            format!("{k:.1}k")
        }
    } else if a >= 100.0 || a == 0.0 {
        format!("{}", v.round())
    } else if a >= 1.0 {
        trim(format!("{v:.2}"))
    } else {
        trim(format!("{v:.3}"))
    }
}

fn trim(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
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
        let lw = legend_width(&entries, &self.legend_title);
        let (plots, legend) = root.split_horizontally(root.dim_in_pixel().0.saturating_sub(lw));
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
        draw_legend(&legend, &self.legend_title, &entries, 40)?;
        let y = 40 + 30 + 28 * entries.len() as i32 + 10;
        for (k, line) in ["line: median", "band: ± sd", "(across runs)"].iter().enumerate() {
            legend
                .draw(&Text::new(
                    line.to_string(),
                    (10, y + 18 * k as i32),
                    anchored(13, HPos::Left, VPos::Top),
                ))
                .map_err(err)?;
        }
        Ok(())
    }
}

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
        let vals = self
            .groups
            .iter()
            .flat_map(|g| g.values.iter().copied().filter(|v| v.is_finite()));
        let (lo, hi) = vals.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        let (lo, hi) = nice_range(lo, hi, 0.06);
        let brackets: Vec<(usize, usize, f64)> = if self.pvalues.len() <= self.max_brackets {
            self.pvalues.clone()
        } else {
            Vec::new()
        };
        let step = (hi - lo) * 0.09;
        let top = hi + step * (brackets.len() as f64 + 0.3);
        let n = self.groups.len();
        let labels: Vec<String> = self.groups.iter().map(|g| g.label.clone()).collect();
        let long = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
        let bottom_area = if long * 9 > 160 { 120 } else { 75 };
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, text_style(24))
            .margin(15)
            .x_label_area_size(bottom_area)
            .y_label_area_size(85)
            .build_cartesian_2d(-0.6..(n as f64 - 0.4), lo..top)
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
        for (i, g) in self.groups.iter().enumerate() {
            let color = setting_color(g.color);
            let x = i as f64;
            let Some(b) = crate::stats::BoxStats::of(&g.values) else {
                continue;
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
        }
        for (level, &(i, j, p)) in brackets.iter().enumerate() {
            let y = hi + step * (level as f64 + 0.3);
            let (a, b) = (i.min(j) as f64, i.max(j) as f64);
            let tick = step * 0.25;
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
        }
        let (w, h) = root.dim_in_pixel();
        let note = if brackets.is_empty() && !self.pvalues.is_empty() {
            format!(
                "{} pairwise two-sided Mann–Whitney U p-values: see summary.md",
                self.pvalues.len()
            )
        } else if !brackets.is_empty() {
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
        let values = self
            .panels
            .iter()
            .flat_map(|p| p.bubbles.iter().map(|b| b.value))
            .filter(|v| v.is_finite());
        let (vmin, vmax) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        let (vmin, vmax) = if vmin.is_finite() {
            (vmin, vmax.max(vmin + 1e-9))
        } else {
            (0.0, 1.0)
        };
        let n = self.panels.len().max(1);
        let cols = n.min(3);
        let rows = n.div_ceil(3);
        let areas = plots.split_evenly((rows, cols));
        for (panel, area) in self.panels.iter().zip(areas) {
            let (nx, ny) = (self.x_classes.len(), self.y_classes.len());
            let xs = self.x_classes.clone();
            let ys = self.y_classes.clone();
            let mut chart = ChartBuilder::on(&area)
                .caption(&panel.title, text_style(19))
                .margin(10)
                .x_label_area_size(60)
                .y_label_area_size(100)
                .build_cartesian_2d(-0.5..(nx as f64 - 0.5), -0.5..(ny as f64 - 0.5))
                .map_err(err)?;
            let fx = move |v: &f64| class_tick(*v, &xs);
            let fy = move |v: &f64| class_tick(*v, &ys);
            chart
                .configure_mesh()
                .x_labels(nx * 2 + 1)
                .y_labels(ny * 2 + 1)
                .x_label_formatter(&fx)
                .y_label_formatter(&fy)
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .label_style(text_style(14))
                .axis_desc_style(text_style(16))
                .light_line_style(WHITE)
                .bold_line_style(RGBColor(230, 230, 230))
                .draw()
                .map_err(err)?;
            let (pw, ph) = area.dim_in_pixel();
            let cell = ((pw.saturating_sub(110)) as f64 / nx.max(1) as f64)
                .min((ph.saturating_sub(90)) as f64 / ny.max(1) as f64);
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
        }
        // Colour bar.
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
                format_tick(v),
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

fn class_tick(v: f64, classes: &[String]) -> String {
    let i = v.round();
    if (v - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < classes.len() {
        classes[i as usize].clone()
    } else {
        String::new()
    }
}

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
        if let Some((title, sizes)) = &self.size_legend {
            let mut y = 40 + 30 + 28 * entries.len() as i32 + 30;
            legend
                .draw(&Text::new(title.clone(), (10, y), anchored(16, HPos::Left, VPos::Top)))
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
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_and_p_values_read_well() {
        assert_eq!(format_tick(30_000.0), "30k");
        assert_eq!(format_tick(12_500.0), "12.5k");
        assert_eq!(format_tick(250.0), "250");
        assert_eq!(format_tick(2.5), "2.5");
        assert_eq!(format_tick(0.125), "0.125");
        assert_eq!(format_tick(0.0), "0");
        assert_eq!(format_p(0.0123), "p = 0.012");
        assert_eq!(format_p(1e-5), "p < 0.001");
        assert_eq!(viridis(0.0), RGBColor(0x44, 0x01, 0x54));
        assert_eq!(viridis(1.0), RGBColor(0xFD, 0xE7, 0x25));
    }

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
    }
}
