//! Sensor descriptions: what a sensor measures, how it is wrapped, how many readings it gives and
//! their declared domains (vsr-model.md §3.1–3.2). A [`SensorSpec`] is plain data; the suite turns
//! it into a running sensor.

use super::{angle, area_ratio, constant, cpg, lidar, malfunction, noise::MAX_NOISY_DEPTH, touch, trend, velocity};
use serde::{Deserialize, Serialize};

/// Longest accepted window of `Average` and `Trend` (s).
pub const MAX_WINDOW: f64 = 3600.0;
/// Most rays one lidar may cast.
pub const MAX_RAYS: usize = 1024;

/// Which velocity components a velocity sensor reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axes {
    /// The x component only.
    X,
    /// The y component only.
    Y,
    /// Both, x first.
    Xy,
}

/// A grid axis, for the constant position sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// Column: x/(W − 1).
    X,
    /// Row: y/(H − 1), row 0 at the bottom.
    Y,
}

/// A sensor, raw or wrapped. Wrappers hold the sensor they transform in `inner`, so a spec is a
/// small tree, e.g. `SoftNormalization(Average(Velocity))` for `vxy`.
///
/// Serialised with a `kind` tag: `{"kind": "average", "window": 0.25, "inner": {"kind": "touch"}}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SensorSpec {
    /// Voxel area over rest area; domain [0.5, 1.5].
    AreaRatio,
    /// 1 while any corner touches the ground, an obstacle or another robot, else 0; domain [0, 1].
    Touch,
    /// Voxel velocity; domain [−vmax, vmax] per component.
    Velocity {
        /// Project on the voxel's own x axis (its angle) and y axis (angle + π/2) instead of the
        /// world's.
        rotated: bool,
        /// Half-width of the domain.
        vmax: f64,
        /// Components reported.
        axes: Axes,
    },
    /// Voxel angle; domain [−π, π].
    Angle,
    /// Distances from the voxel centre to static geometry along `rays` rays on the voxel's outer
    /// side; domain [0, range] per ray.
    Lidar {
        /// Ray length; a ray that hits nothing reads this.
        range: f64,
        /// Number of rays (1 to [`MAX_RAYS`]).
        rays: usize,
    },
    /// sin(−2πt), t the simulated time; domain [−1, 1].
    Cpg,
    /// The voxel's relative grid position along an axis, fixed; domain [0, 1].
    ConstantPosition {
        /// Which axis.
        axis: Axis,
    },
    /// 1 once the voxel is broken (no voxel can break yet, so always 0); domain [0, 1].
    Malfunction,
    /// Mean of the inner readings over the samples taken at or after t − window; domain unchanged.
    Average {
        /// Window (s).
        window: f64,
        /// The averaged sensor.
        inner: Box<SensorSpec>,
    },
    /// (last − first)/(t_last − t_first) over the window; domain ±extent/window.
    Trend {
        /// Window (s).
        window: f64,
        /// The sensor whose trend is taken.
        inner: Box<SensorSpec>,
    },
    /// Clip to the inner domain, then map linearly to [0, 1].
    Normalization {
        /// The normalised sensor.
        inner: Box<SensorSpec>,
    },
    /// tanh(2(2v − 1))/2 + 1/2 of the linearly normalised value v; domain [0, 1].
    SoftNormalization {
        /// Clip v to [0, 1] first: false (default) as in the thesis era (2D-VSR-Sim ≤ v1.10), true
        /// as in v1.11 and later.
        #[serde(default)]
        clip: bool,
        /// The normalised sensor.
        inner: Box<SensorSpec>,
    },
    /// Adds N(0, (σ·extent)²) to each inner reading, extent being the width of its domain; domain
    /// unchanged. Each instance has its own noise stream (see the module docs of `sensors`).
    Noisy {
        /// Standard deviation relative to the domain's extent (≥ 0).
        sigma: f64,
        /// The sensor the noise is added to.
        inner: Box<SensorSpec>,
    },
}

impl SensorSpec {
    /// This sensor averaged over `window` seconds.
    pub fn averaged(self, window: f64) -> SensorSpec {
        SensorSpec::Average {
            window,
            inner: Box::new(self),
        }
    }

    /// The trend of this sensor over `window` seconds.
    pub fn trend(self, window: f64) -> SensorSpec {
        SensorSpec::Trend {
            window,
            inner: Box::new(self),
        }
    }

    /// This sensor clipped and mapped linearly to [0, 1].
    pub fn normalized(self) -> SensorSpec {
        SensorSpec::Normalization { inner: Box::new(self) }
    }

    /// This sensor soft-normalised, thesis-era style (no clipping).
    pub fn soft_normalized(self) -> SensorSpec {
        SensorSpec::SoftNormalization {
            clip: false,
            inner: Box::new(self),
        }
    }

    /// This sensor with Gaussian noise of relative standard deviation `sigma`.
    pub fn noisy(self, sigma: f64) -> SensorSpec {
        SensorSpec::Noisy {
            sigma,
            inner: Box::new(self),
        }
    }

    /// Number of readings.
    pub fn dimension(&self) -> usize {
        match self {
            SensorSpec::Velocity { axes: Axes::Xy, .. } => 2,
            SensorSpec::Lidar { rays, .. } => *rays,
            SensorSpec::Average { inner, .. }
            | SensorSpec::Trend { inner, .. }
            | SensorSpec::Normalization { inner }
            | SensorSpec::SoftNormalization { inner, .. }
            | SensorSpec::Noisy { inner, .. } => inner.dimension(),
            SensorSpec::AreaRatio
            | SensorSpec::Touch
            | SensorSpec::Velocity { .. }
            | SensorSpec::Angle
            | SensorSpec::Cpg
            | SensorSpec::ConstantPosition { .. }
            | SensorSpec::Malfunction => 1,
        }
    }

    /// Declared domain (min, max) of each reading, after wrapping.
    pub fn domains(&self) -> Vec<(f64, f64)> {
        match self {
            SensorSpec::AreaRatio => vec![area_ratio::DOMAIN],
            SensorSpec::Touch => vec![touch::DOMAIN],
            SensorSpec::Velocity { vmax, .. } => vec![velocity::domain(*vmax); self.dimension()],
            SensorSpec::Angle => vec![angle::DOMAIN],
            SensorSpec::Lidar { range, rays } => vec![lidar::domain(*range); *rays],
            SensorSpec::Cpg => vec![cpg::DOMAIN],
            SensorSpec::ConstantPosition { .. } => vec![constant::DOMAIN],
            SensorSpec::Malfunction => vec![malfunction::DOMAIN],
            SensorSpec::Average { inner, .. } | SensorSpec::Noisy { inner, .. } => inner.domains(),
            SensorSpec::Trend { window, inner } => {
                inner.domains().into_iter().map(|d| trend::domain(d, *window)).collect()
            }
            SensorSpec::Normalization { inner } | SensorSpec::SoftNormalization { inner, .. } => {
                vec![(0.0, 1.0); inner.dimension()]
            }
        }
    }

    /// Checks every parameter of the tree; the message names the parameter and the accepted range.
    pub fn validate(&self) -> Result<(), String> {
        self.validate_at(0)
    }

    fn validate_at(&self, noisy_depth: usize) -> Result<(), String> {
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(format!("{name} must be a finite number > 0, got {v}"))
            }
        };
        match self {
            SensorSpec::Velocity { vmax, .. } => positive("velocity vmax", *vmax),
            SensorSpec::Lidar { range, rays } => {
                positive("lidar range", *range)?;
                if (1..=MAX_RAYS).contains(rays) {
                    Ok(())
                } else {
                    Err(format!("lidar rays must be 1 to {MAX_RAYS}, got {rays}"))
                }
            }
            SensorSpec::Average { window, inner } | SensorSpec::Trend { window, inner } => {
                positive("window", *window)?;
                if *window > MAX_WINDOW {
                    return Err(format!("window must be at most {MAX_WINDOW} s, got {window}"));
                }
                inner.validate_at(noisy_depth)
            }
            SensorSpec::Noisy { sigma, inner } => {
                if !(sigma.is_finite() && *sigma >= 0.0) {
                    return Err(format!("noise sigma must be a finite number ≥ 0, got {sigma}"));
                }
                if noisy_depth + 1 >= MAX_NOISY_DEPTH {
                    return Err(format!("at most {} nested noisy wrappers", MAX_NOISY_DEPTH - 1));
                }
                inner.validate_at(noisy_depth + 1)
            }
            SensorSpec::Normalization { inner } | SensorSpec::SoftNormalization { inner, .. } => {
                inner.validate_at(noisy_depth)
            }
            SensorSpec::AreaRatio
            | SensorSpec::Touch
            | SensorSpec::Angle
            | SensorSpec::Cpg
            | SensorSpec::ConstantPosition { .. }
            | SensorSpec::Malfunction => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn dimensions_and_domains_follow_the_wrappers() {
        let v = SensorSpec::Velocity {
            rotated: true,
            vmax: 4.0,
            axes: Axes::Xy,
        };
        assert_eq!(v.dimension(), 2);
        assert_eq!(v.domains(), vec![(-4.0, 4.0); 2]);
        assert_eq!(v.clone().trend(0.5).domains(), vec![(-16.0, 16.0); 2]);
        assert_eq!(v.clone().averaged(0.5).domains(), vec![(-4.0, 4.0); 2]);
        assert_eq!(v.clone().trend(0.5).soft_normalized().domains(), vec![(0.0, 1.0); 2]);
        assert_eq!(v.noisy(0.1).domains(), vec![(-4.0, 4.0); 2]);
        let lidar = SensorSpec::Lidar { range: 10.0, rays: 5 };
        assert_eq!((lidar.dimension(), lidar.domains()[4]), (5, (0.0, 10.0)));
        assert_eq!(SensorSpec::Angle.domains(), vec![(-PI, PI)]);
        assert_eq!(SensorSpec::AreaRatio.domains(), vec![(0.5, 1.5)]);
        assert_eq!(SensorSpec::Cpg.normalized().domains(), vec![(0.0, 1.0)]);
    }

    #[test]
    fn validation_names_the_bad_parameter() {
        let e = SensorSpec::Touch.averaged(-1.0).validate().unwrap_err();
        assert!(e.contains("window") && e.contains("-1"), "{e}");
        let e = SensorSpec::Lidar { range: 10.0, rays: 0 }.validate().unwrap_err();
        assert!(e.contains("rays"), "{e}");
        let e = SensorSpec::AreaRatio
            .noisy(f64::NAN)
            .normalized()
            .validate()
            .unwrap_err();
        assert!(e.contains("sigma"), "{e}");
        let e = SensorSpec::Velocity {
            rotated: true,
            vmax: 0.0,
            axes: Axes::X,
        }
        .validate()
        .unwrap_err();
        assert!(e.contains("vmax"), "{e}");
        assert!(SensorSpec::Touch.averaged(0.25).noisy(0.0).validate().is_ok());
    }

    #[test]
    fn serde_round_trips_a_tree() {
        let spec = SensorSpec::Velocity {
            rotated: true,
            vmax: 8.0,
            axes: Axes::Xy,
        }
        .averaged(0.5)
        .soft_normalized()
        .noisy(0.01);
        let text = serde_json::to_string(&spec).unwrap();
        assert_eq!(serde_json::from_str::<SensorSpec>(&text).unwrap(), spec);
        let parsed: SensorSpec =
            serde_json::from_str(r#"{"kind": "soft-normalization", "inner": {"kind": "area-ratio"}}"#).unwrap();
        assert_eq!(parsed, SensorSpec::AreaRatio.soft_normalized());
        let typo = r#"{"kind": "velocity", "rotated": true, "vmax": 8, "axes": "x", "vmx": 4}"#;
        assert!(serde_json::from_str::<SensorSpec>(typo).is_err());
    }
}
