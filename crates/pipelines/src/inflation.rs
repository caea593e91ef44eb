//! `vsrlab inflate`: the PSA inflation protocol of thesis §6.4.1 for each size (springs at rest,
//! pressure from 0 up by p_max/100 per step to p_max), with φ = area/(π r²) and p/p_max per step
//! in `inflation.csv` and in a figure (`inflation.png`/`.svg`), and a summary per size.

use crate::error::AnalysisError;
use crate::output::{create_folder, write_output};
use std::fmt::Write as _;
use std::path::PathBuf;
use vsrlab_analysis::plot::{self, BandChart, BandFigure, BandSeries};
use vsrlab_body::psa::{PsaParams, PsaSize};
use vsrlab_physics::Vec2;
use vsrlab_tasks::kinds::psa::inflation::{inflate, psa_physics, InflationPoint};

/// Options of the inflation protocol.
#[derive(Debug, Clone)]
pub struct InflationOptions {
    /// The sizes, in order.
    pub sizes: Vec<PsaSize>,
    /// Simulated seconds per size (the pressure reaches p_max after 100 steps).
    pub duration: f64,
    /// Without gravity (the balloon alone, no ground contact).
    pub zero_gravity: bool,
    /// Output folder.
    pub out: PathBuf,
}

/// φ of one size once the pressure is at p_max.
#[derive(Debug, Clone, PartialEq)]
pub struct InflationSummary {
    /// The size.
    pub size: PsaSize,
    /// φ at the first step with p = p_max.
    pub at_max: f64,
    /// Mean, smallest and largest φ over the last second.
    pub last_second: (f64, f64, f64),
    /// Largest φ over the whole protocol.
    pub max: f64,
}

/// What `inflate` wrote and measured.
#[derive(Debug, Clone)]
pub struct InflationReport {
    /// One summary per size.
    pub sizes: Vec<InflationSummary>,
    /// Files written.
    pub files: Vec<PathBuf>,
}

/// Runs the protocol for every size and writes the CSV and the figure.
pub fn inflation(options: &InflationOptions) -> Result<InflationReport, AnalysisError> {
    if !(options.duration.is_finite() && options.duration >= 2.0 && options.duration <= 600.0) {
        return Err(AnalysisError::Option {
            option: "duration",
            message: format!("must be in [2, 600] seconds, got {}", options.duration),
        });
    }
    if options.sizes.is_empty() {
        return Err(AnalysisError::Option {
            option: "sizes",
            message: "give at least one size".into(),
        });
    }
    let mut physics = psa_physics();
    if options.zero_gravity {
        physics.gravity = Vec2::ZERO;
    }
    let steps = (options.duration / physics.dt).round() as usize;
    let mut curves = Vec::new();
    for &size in &options.sizes {
        let points = inflate(&PsaParams::of_size(size), &physics, steps).map_err(|e| AnalysisError::Option {
            option: "sizes",
            message: format!("{}: {e}", size.name()),
        })?;
        curves.push((size, points));
    }
    create_folder(&options.out)?;
    let mut csv = String::from("size,step,time,pressure_ratio,phi\n");
    for (size, points) in &curves {
        for (k, p) in points.iter().enumerate() {
            let _ = writeln!(
                csv,
                "{},{},{},{},{}",
                size.name(),
                k + 1,
                p.time,
                p.pressure_ratio,
                p.phi
            );
        }
    }
    let path = options.out.join("inflation.csv");
    write_output(&path, csv.as_bytes())?;
    let mut files = vec![path];
    files.extend(plot::save(
        &figure(&curves, options.zero_gravity),
        &options.out.join("inflation"),
    )?);
    let sizes = curves
        .iter()
        .map(|(size, points)| summary(*size, points, (1.0 / physics.dt).round() as usize))
        .collect();
    Ok(InflationReport { sizes, files })
}

fn summary(size: PsaSize, points: &[InflationPoint], per_second: usize) -> InflationSummary {
    let at_max = points
        .iter()
        .find(|p| p.pressure_ratio >= 1.0)
        .map_or(f64::NAN, |p| p.phi);
    let tail = &points[points.len().saturating_sub(per_second)..];
    let mean = tail.iter().map(|p| p.phi).sum::<f64>() / tail.len().max(1) as f64;
    let lo = tail.iter().map(|p| p.phi).fold(f64::INFINITY, f64::min);
    let hi = tail.iter().map(|p| p.phi).fold(f64::NEG_INFINITY, f64::max);
    let max = points.iter().map(|p| p.phi).fold(f64::NEG_INFINITY, f64::max);
    InflationSummary {
        size,
        at_max,
        last_second: (mean, lo, hi),
        max,
    }
}

fn figure(curves: &[(PsaSize, Vec<InflationPoint>)], zero_gravity: bool) -> BandFigure {
    let series = |value: fn(&InflationPoint) -> f64| {
        curves
            .iter()
            .enumerate()
            .map(|(i, (size, points))| BandSeries {
                label: size.name().to_string(),
                color: i,
                x: points.iter().map(|p| p.time).collect(),
                center: points.iter().map(value).collect(),
                spread: vec![0.0; points.len()],
            })
            .collect()
    };
    BandFigure {
        title: format!(
            "PSA inflation: springs at rest, pressure +p_max/100 per step{}",
            if zero_gravity { " (no gravity)" } else { "" }
        ),
        panels: vec![
            BandChart {
                title: "area ratio φ = a / (π r²)".into(),
                x_label: "time (s)".into(),
                y_label: "φ".into(),
                series: series(|p| p.phi),
            },
            BandChart {
                title: "relative pressure".into(),
                x_label: "time (s)".into(),
                y_label: "p / p_max".into(),
                series: series(|p| p.pressure_ratio),
            },
        ],
        legend_title: "size".into(),
        note: vec!["one run".into(), "per size".into()],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_row_per_step_and_size_and_refuses_bad_options() {
        let dir = tempfile::tempdir().unwrap();
        let options = InflationOptions {
            sizes: vec![PsaSize::Small, PsaSize::Large],
            duration: 3.0,
            zero_gravity: true,
            out: dir.path().to_path_buf(),
        };
        let report = inflation(&options).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("inflation.csv")).unwrap();
        assert_eq!(csv.lines().count(), 1 + 2 * 180);
        assert!(dir.path().join("inflation.png").exists());
        // without gravity the large balloon stretches its springs beyond the circle
        assert!(report.sizes[1].last_second.0 > 1.0, "{:?}", report.sizes[1]);
        let bad = InflationOptions {
            duration: 0.5,
            ..options.clone()
        };
        assert!(inflation(&bad).unwrap_err().to_string().starts_with("duration"));
        let none = InflationOptions {
            sizes: vec![],
            ..options
        };
        assert!(inflation(&none).unwrap_err().to_string().starts_with("sizes"));
    }
}
