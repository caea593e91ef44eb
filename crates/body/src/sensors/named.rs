//! The named sensors of 2D-VSR-Sim (vsr-model.md §3.3), as used in placement strings.
//!
//! | name | sensor |
//! |---|---|
//! | `a` | SoftNormalization(AreaRatio) |
//! | `t` | Average(Touch, 0.25 s) |
//! | `r` | SoftNormalization(Angle) |
//! | `vx`, `vy`, `vxy` | SoftNormalization(Average(Velocity(rotated, 8, x / y / xy), 0.5 s)) |
//! | `ax`, `ay`, `axy` | SoftNormalization(Trend(Velocity(rotated, 4, x / y / xy), 0.5 s)) |
//! | `px`, `py` | ConstantPosition(x / y) |
//! | `m` | Malfunction |
//! | `cpg` | Normalization(Cpg) |
//! | `l5`, `l1` | Normalization(Lidar(range 10, 5 / 1 rays)) |
//!
//! Soft normalisations here do not clip (thesis era). `ax`…`axy` use `Trend` (2D-VSR-Sim since
//! 2021-08; earlier versions used a one-step `Derivative`), and the lidars are normalised (since
//! 2021-08; raw before).

use super::spec::{Axes, Axis, SensorSpec};

/// Every sensor name accepted in placements, in the order used by `uniformAll` (the original's
/// sorted key order).
pub const SENSOR_NAMES: [&str; 15] = [
    "a", "ax", "axy", "ay", "cpg", "l1", "l5", "m", "px", "py", "r", "t", "vx", "vxy", "vy",
];

impl SensorSpec {
    /// The named sensor `name` (see [`SENSOR_NAMES`]), or `None` if there is no such name.
    pub fn named(name: &str) -> Option<SensorSpec> {
        let velocity = |vmax: f64, axes| SensorSpec::Velocity {
            rotated: true,
            vmax,
            axes,
        };
        let lidar = |rays| SensorSpec::Lidar { range: 10.0, rays };
        Some(match name {
            "a" => SensorSpec::AreaRatio.soft_normalized(),
            "t" => SensorSpec::Touch.averaged(0.25),
            "r" => SensorSpec::Angle.soft_normalized(),
            "vx" => velocity(8.0, Axes::X).averaged(0.5).soft_normalized(),
            "vy" => velocity(8.0, Axes::Y).averaged(0.5).soft_normalized(),
            "vxy" => velocity(8.0, Axes::Xy).averaged(0.5).soft_normalized(),
            "ax" => velocity(4.0, Axes::X).trend(0.5).soft_normalized(),
            "ay" => velocity(4.0, Axes::Y).trend(0.5).soft_normalized(),
            "axy" => velocity(4.0, Axes::Xy).trend(0.5).soft_normalized(),
            "px" => SensorSpec::ConstantPosition { axis: Axis::X },
            "py" => SensorSpec::ConstantPosition { axis: Axis::Y },
            "m" => SensorSpec::Malfunction,
            "cpg" => SensorSpec::Cpg.normalized(),
            "l5" => lidar(5).normalized(),
            "l1" => lidar(1).normalized(),
            _ => return None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_name_resolves_and_no_other() {
        for name in SENSOR_NAMES {
            let spec = SensorSpec::named(name).unwrap_or_else(|| panic!("{name}"));
            assert!(spec.validate().is_ok(), "{name}");
        }
        for bad in ["", "A", "v", "l2", "cgp", "lf5", "a "] {
            assert_eq!(SensorSpec::named(bad), None, "{bad:?}");
        }
        let mut sorted = SENSOR_NAMES;
        sorted.sort_unstable();
        assert_eq!(sorted, SENSOR_NAMES);
    }

    #[test]
    fn names_map_to_the_published_trees() {
        let vxy = SensorSpec::SoftNormalization {
            clip: false,
            inner: Box::new(SensorSpec::Average {
                window: 0.5,
                inner: Box::new(SensorSpec::Velocity {
                    rotated: true,
                    vmax: 8.0,
                    axes: Axes::Xy,
                }),
            }),
        };
        assert_eq!(SensorSpec::named("vxy"), Some(vxy));
        let t = SensorSpec::Average {
            window: 0.25,
            inner: Box::new(SensorSpec::Touch),
        };
        assert_eq!(SensorSpec::named("t"), Some(t));
        let ay = SensorSpec::named("ay").unwrap();
        assert_eq!(
            ay,
            SensorSpec::Velocity {
                rotated: true,
                vmax: 4.0,
                axes: Axes::Y
            }
            .trend(0.5)
            .soft_normalized()
        );
        let dims: Vec<usize> = SENSOR_NAMES
            .iter()
            .map(|n| SensorSpec::named(n).unwrap().dimension())
            .collect();
        assert_eq!(dims, vec![1, 1, 2, 1, 1, 1, 5, 1, 1, 1, 1, 1, 1, 2, 1]);
        assert_eq!(SensorSpec::named("t").unwrap().domains(), vec![(0.0, 1.0)]);
        assert_eq!(SensorSpec::named("l5").unwrap().domains(), vec![(0.0, 1.0); 5]);
    }
}
