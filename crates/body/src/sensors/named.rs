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
//! | `l5`, `l3`, `l1` | Normalization(Lidar(range 10, 5 / 3 / 1 rays)) (`l3`: 2D-VSR-Sim 07f9395, the Hebbian study) |
//!
//! Soft normalisations here do not clip (thesis era). `ax`…`axy` use `Trend` (2D-VSR-Sim since
//! 2021-08; earlier versions used a one-step `Derivative`), and the lidars are normalised (since
//! 2021-08; raw before).

use super::constant::{Axis, ConstantPositionSpec};
use super::lidar::LidarSpec;
use super::spec::SensorSpec;
use super::velocity::{Axes, VelocitySpec};

/// One named sensor: its name in placements and the sensor tree it stands for.
#[derive(Debug, Clone, Copy)]
pub struct NamedSensor {
    /// The name, as written in placement strings and per-voxel lists.
    pub name: &'static str,
    /// Builds the sensor tree.
    pub spec: fn() -> SensorSpec,
}

/// Every named sensor, in the order used by `uniformAll` (the original's sorted key order). A new
/// named sensor is one entry here.
pub const NAMED_SENSORS: &[NamedSensor] = &[
    NamedSensor {
        name: "a",
        spec: || SensorSpec::AreaRatio.soft_normalized(),
    },
    NamedSensor {
        name: "ax",
        spec: || velocity(4.0, Axes::X).trend(0.5).soft_normalized(),
    },
    NamedSensor {
        name: "axy",
        spec: || velocity(4.0, Axes::Xy).trend(0.5).soft_normalized(),
    },
    NamedSensor {
        name: "ay",
        spec: || velocity(4.0, Axes::Y).trend(0.5).soft_normalized(),
    },
    NamedSensor {
        name: "cpg",
        spec: || SensorSpec::Cpg.normalized(),
    },
    NamedSensor {
        name: "l1",
        spec: || lidar(1).normalized(),
    },
    NamedSensor {
        name: "l3",
        spec: || lidar(3).normalized(),
    },
    NamedSensor {
        name: "l5",
        spec: || lidar(5).normalized(),
    },
    NamedSensor {
        name: "m",
        spec: || SensorSpec::Malfunction,
    },
    NamedSensor {
        name: "px",
        spec: || SensorSpec::ConstantPosition(ConstantPositionSpec { axis: Axis::X }),
    },
    NamedSensor {
        name: "py",
        spec: || SensorSpec::ConstantPosition(ConstantPositionSpec { axis: Axis::Y }),
    },
    NamedSensor {
        name: "r",
        spec: || SensorSpec::Angle.soft_normalized(),
    },
    NamedSensor {
        name: "t",
        spec: || SensorSpec::Touch.averaged(0.25),
    },
    NamedSensor {
        name: "vx",
        spec: || velocity(8.0, Axes::X).averaged(0.5).soft_normalized(),
    },
    NamedSensor {
        name: "vxy",
        spec: || velocity(8.0, Axes::Xy).averaged(0.5).soft_normalized(),
    },
    NamedSensor {
        name: "vy",
        spec: || velocity(8.0, Axes::Y).averaged(0.5).soft_normalized(),
    },
];

/// Every sensor name accepted in placements: the names of [`NAMED_SENSORS`], in that order.
pub const SENSOR_NAMES: [&str; NAMED_SENSORS.len()] = {
    let mut names = [""; NAMED_SENSORS.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = NAMED_SENSORS[i].name;
        i += 1;
    }
    names
};

/// A velocity sensor in the voxel's frame.
fn velocity(vmax: f64, axes: Axes) -> SensorSpec {
    SensorSpec::Velocity(VelocitySpec {
        rotated: true,
        vmax,
        axes,
    })
}

/// A lidar of range 10.
fn lidar(rays: usize) -> SensorSpec {
    SensorSpec::Lidar(LidarSpec { range: 10.0, rays })
}

impl SensorSpec {
    /// The named sensor `name` (see [`NAMED_SENSORS`]), or `None` if there is no such name.
    pub fn named(name: &str) -> Option<SensorSpec> {
        NAMED_SENSORS
            .iter()
            .find(|named| named.name == name)
            .map(|named| (named.spec)())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::{AverageSpec, SoftNormalizationSpec};

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
        let vxy = SensorSpec::SoftNormalization(SoftNormalizationSpec {
            clip: false,
            inner: Box::new(SensorSpec::Average(AverageSpec {
                window: 0.5,
                inner: Box::new(SensorSpec::Velocity(VelocitySpec {
                    rotated: true,
                    vmax: 8.0,
                    axes: Axes::Xy,
                })),
            })),
        });
        assert_eq!(SensorSpec::named("vxy"), Some(vxy));
        let t = SensorSpec::Average(AverageSpec {
            window: 0.25,
            inner: Box::new(SensorSpec::Touch),
        });
        assert_eq!(SensorSpec::named("t"), Some(t));
        let ay = SensorSpec::named("ay").unwrap();
        assert_eq!(
            ay,
            SensorSpec::Velocity(VelocitySpec {
                rotated: true,
                vmax: 4.0,
                axes: Axes::Y
            })
            .trend(0.5)
            .soft_normalized()
        );
        let dims: Vec<usize> = SENSOR_NAMES
            .iter()
            .map(|n| SensorSpec::named(n).unwrap().dimension())
            .collect();
        assert_eq!(dims, vec![1, 1, 2, 1, 1, 1, 3, 5, 1, 1, 1, 1, 1, 1, 2, 1]);
        assert_eq!(SensorSpec::named("t").unwrap().domains(), vec![(0.0, 1.0)]);
        assert_eq!(SensorSpec::named("l5").unwrap().domains(), vec![(0.0, 1.0); 5]);
    }
}
