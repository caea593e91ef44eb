//! Sensor descriptions: what each sensor measures, its domain, and the named sensors of
//! vsr-model.md §3.3.

use serde::{Deserialize, Serialize};

/// Which velocity components a velocity sensor reports.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axes {
    /// Horizontal (or the voxel's own x axis when rotated).
    X,
    /// Vertical (or the voxel's own y axis when rotated).
    Y,
    /// Both, x first.
    Xy,
}

/// A grid axis for the constant position sensor.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// Relative column x/(W−1).
    X,
    /// Relative row y/(H−1).
    Y,
}

/// A sensor, possibly wrapped (averages, normalisations, noise). Domains follow vsr-model.md §3.1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum SensorSpec {
    /// Voxel area / L²; domain [0.5, 1.5].
    AreaRatio,
    /// 1 when any corner touches the ground or another robot, else 0; domain [0, 1].
    Touch,
    /// Voxel velocity, optionally in the voxel's own frame; domain [−vmax, vmax] per axis.
    Velocity {
        /// Project on the voxel's own axes instead of the world's.
        rotated: bool,
        /// Half-width of the domain.
        vmax: f64,
        /// Components reported.
        axes: Axes,
    },
    /// Voxel angle; domain [−π, π].
    Angle,
    /// Distances to static geometry along rays on the voxel's side; domain [0, range].
    Lidar {
        /// Maximum distance.
        range: f64,
        /// Number of rays (≥ 1).
        rays: usize,
    },
    /// Central pattern generator sin(−2πt); domain [−1, 1].
    Cpg,
    /// Constant relative position of the voxel in the grid; domain [0, 1].
    Position {
        /// Which axis.
        axis: Axis,
    },
    /// 1 if the voxel is broken (no breakable voxels yet: always 0); domain [0, 1].
    Malfunction,
    /// Mean of the inner readings over samples with time ≥ t − window.
    Average {
        /// Window (s).
        window: f64,
        /// Inner sensor.
        of: Box<SensorSpec>,
    },
    /// (last − first)/(t_last − t_first) over the window; domain ±extent/window.
    Trend {
        /// Window (s).
        window: f64,
        /// Inner sensor.
        of: Box<SensorSpec>,
    },
    /// Clip to the inner domain, then map linearly to [0, 1].
    Normalization {
        /// Inner sensor.
        of: Box<SensorSpec>,
    },
    /// tanh(2(2v − 1))/2 + 1/2 of the linearly normalised value v; with `clip`, v is first clipped to
    /// [0, 1] (2D-VSR-Sim ≥ v1.11); without, as in the thesis era.
    SoftNormalization {
        /// Clip v to [0, 1] first.
        #[serde(default)]
        clip: bool,
        /// Inner sensor.
        of: Box<SensorSpec>,
    },
    /// Adds Gaussian noise with standard deviation σ times the extent of the inner domain.
    Noisy {
        /// Relative standard deviation.
        sigma: f64,
        /// Inner sensor.
        of: Box<SensorSpec>,
    },
}

fn boxed(s: SensorSpec) -> Box<SensorSpec> {
    Box::new(s)
}

impl SensorSpec {
    /// The named sensors of 2D-VSR-Sim (`a`, `t`, `r`, `vx`, `vy`, `vxy`, `ax`, `ay`, `axy`, `px`,
    /// `py`, `m`, `cpg`, `l5`, `l1`).
    pub fn named(name: &str) -> Option<SensorSpec> {
        use SensorSpec::*;
        let soft = |s| SoftNormalization { clip: false, of: boxed(s) };
        let velocity = |vmax, axes| Velocity { rotated: true, vmax, axes };
        let avg_v = |axes| soft(Average { window: 0.5, of: boxed(velocity(8.0, axes)) });
        let trend_v = |axes| soft(Trend { window: 0.5, of: boxed(velocity(4.0, axes)) });
        Some(match name {
            "a" => soft(AreaRatio),
            "t" => Average { window: 0.25, of: boxed(Touch) },
            "r" => soft(Angle),
            "vx" => avg_v(Axes::X),
            "vy" => avg_v(Axes::Y),
            "vxy" => avg_v(Axes::Xy),
            "ax" => trend_v(Axes::X),
            "ay" => trend_v(Axes::Y),
            "axy" => trend_v(Axes::Xy),
            "px" => Position { axis: Axis::X },
            "py" => Position { axis: Axis::Y },
            "m" => Malfunction,
            "cpg" => Normalization { of: boxed(Cpg) },
            "l5" => Normalization { of: boxed(Lidar { range: 10.0, rays: 5 }) },
            "l1" => Normalization { of: boxed(Lidar { range: 10.0, rays: 1 }) },
            _ => return None,
        })
    }

    /// Domain (min, max) of each reading.
    pub fn domains(&self) -> Vec<(f64, f64)> {
        use SensorSpec::*;
        match self {
            AreaRatio => vec![(0.5, 1.5)],
            Touch | Malfunction | Position { .. } => vec![(0.0, 1.0)],
            Velocity { vmax, axes, .. } => vec![(-vmax, *vmax); if *axes == Axes::Xy { 2 } else { 1 }],
            Angle => vec![(-std::f64::consts::PI, std::f64::consts::PI)],
            Lidar { range, rays } => vec![(0.0, *range); *rays],
            Cpg => vec![(-1.0, 1.0)],
            Average { of, .. } | Noisy { of, .. } => of.domains(),
            Trend { window, of } => of
                .domains()
                .into_iter()
                .map(|(lo, hi)| ((lo - hi) / window, (hi - lo) / window))
                .collect(),
            Normalization { of } | SoftNormalization { of, .. } => vec![(0.0, 1.0); of.dimension()],
        }
    }

    /// Number of readings.
    pub fn dimension(&self) -> usize {
        use SensorSpec::*;
        match self {
            Velocity { axes: Axes::Xy, .. } => 2,
            Lidar { rays, .. } => *rays,
            Average { of, .. } | Trend { of, .. } | Normalization { of } | SoftNormalization { of, .. } | Noisy { of, .. } => of.dimension(),
            _ => 1,
        }
    }

    /// Checks parameters (positive windows, ranges, at least one ray, finite σ).
    pub fn validate(&self) -> Result<(), String> {
        use SensorSpec::*;
        match self {
            Velocity { vmax, .. } if !(vmax.is_finite() && *vmax > 0.0) => Err(format!("velocity vmax must be > 0, got {vmax}")),
            Lidar { range, rays } if !(range.is_finite() && *range > 0.0) || *rays == 0 || *rays > 64 => {
                Err(format!("lidar needs range > 0 and 1..=64 rays, got range {range}, {rays} rays"))
            }
            Average { window, of } | Trend { window, of } => {
                if !(window.is_finite() && *window > 0.0 && *window <= 60.0) {
                    return Err(format!("window must be in (0, 60] s, got {window}"));
                }
                of.validate()
            }
            Noisy { sigma, of } => {
                if !(sigma.is_finite() && *sigma >= 0.0) {
                    return Err(format!("noise sigma must be ≥ 0, got {sigma}"));
                }
                of.validate()
            }
            Normalization { of } | SoftNormalization { of, .. } => of.validate(),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_sensors_have_the_documented_shapes() {
        assert_eq!(SensorSpec::named("vxy").unwrap().dimension(), 2);
        assert_eq!(SensorSpec::named("l5").unwrap().dimension(), 5);
        assert_eq!(SensorSpec::named("t").unwrap().domains(), vec![(0.0, 1.0)]);
        assert!(SensorSpec::named("zz").is_none());
        let trend = SensorSpec::Trend {
            window: 0.5,
            of: Box::new(SensorSpec::Velocity { rotated: true, vmax: 4.0, axes: Axes::X }),
        };
        assert_eq!(trend.domains(), vec![(-16.0, 16.0)]);
    }
}
