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
//! Two things depend on the simulator version, so each named sensor is built for a preset
//! ([`SensorSpec::named_in`], vsr-model.md §3.2 and §9.1): soft normalisations clip their value to
//! [0, 1] before the tanh in 2022 (2D-VSR-Sim ≥ v1.11) and not in 2021 (≤ v1.10, the thesis
//! era); lidar rays include the side's ends in 2022 and point at the centres of equal bins in 2021
//! ([`RayLayout`]). `ax`…`axy` use `Trend` (2D-VSR-Sim since 2021-08; earlier versions used a
//! one-step `Derivative`), and the lidars are normalised (since 2021-08; raw before).

use super::constant::{Axis, ConstantPositionSpec};
use super::lidar::{LidarSpec, RayLayout};
use super::soft_normalization::SoftNormalizationSpec;
use super::spec::SensorSpec;
use super::velocity::{Axes, VelocitySpec};
use crate::params::Preset;

/// One named sensor: its name in placements and the sensor tree it stands for.
#[derive(Debug, Clone, Copy)]
pub struct NamedSensor {
    /// The name, as written in placement strings and per-voxel lists.
    pub name: &'static str,
    /// Builds the sensor tree as the simulator of a preset does.
    pub spec: fn(Preset) -> SensorSpec,
}

/// Every named sensor, in the order used by `uniformAll` (the original's sorted key order). A new
/// named sensor is one entry here.
pub const NAMED_SENSORS: &[NamedSensor] = &[
    NamedSensor {
        name: "a",
        spec: |p| SensorSpec::AreaRatio.soft_normalized_in(p),
    },
    NamedSensor {
        name: "ax",
        spec: |p| velocity(4.0, Axes::X).trend(0.5).soft_normalized_in(p),
    },
    NamedSensor {
        name: "axy",
        spec: |p| velocity(4.0, Axes::Xy).trend(0.5).soft_normalized_in(p),
    },
    NamedSensor {
        name: "ay",
        spec: |p| velocity(4.0, Axes::Y).trend(0.5).soft_normalized_in(p),
    },
    NamedSensor {
        name: "cpg",
        spec: |_| SensorSpec::Cpg.normalized(),
    },
    NamedSensor {
        name: "l1",
        spec: |p| lidar(1, p).normalized(),
    },
    NamedSensor {
        name: "l3",
        spec: |p| lidar(3, p).normalized(),
    },
    NamedSensor {
        name: "l5",
        spec: |p| lidar(5, p).normalized(),
    },
    NamedSensor {
        name: "m",
        spec: |_| SensorSpec::Malfunction,
    },
    NamedSensor {
        name: "px",
        spec: |_| SensorSpec::ConstantPosition(ConstantPositionSpec { axis: Axis::X }),
    },
    NamedSensor {
        name: "py",
        spec: |_| SensorSpec::ConstantPosition(ConstantPositionSpec { axis: Axis::Y }),
    },
    NamedSensor {
        name: "r",
        spec: |p| SensorSpec::Angle.soft_normalized_in(p),
    },
    NamedSensor {
        name: "t",
        spec: |_| SensorSpec::Touch.averaged(0.25),
    },
    NamedSensor {
        name: "vx",
        spec: |p| velocity(8.0, Axes::X).averaged(0.5).soft_normalized_in(p),
    },
    NamedSensor {
        name: "vxy",
        spec: |p| velocity(8.0, Axes::Xy).averaged(0.5).soft_normalized_in(p),
    },
    NamedSensor {
        name: "vy",
        spec: |p| velocity(8.0, Axes::Y).averaged(0.5).soft_normalized_in(p),
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

/// A lidar of range 10, its rays spread as in `preset`'s simulator.
fn lidar(rays: usize, preset: Preset) -> SensorSpec {
    let layout = match preset {
        Preset::Y2021 => RayLayout::Bins,
        Preset::Y2022 => RayLayout::Ends,
    };
    SensorSpec::Lidar(LidarSpec {
        range: 10.0,
        rays,
        layout,
    })
}

impl SensorSpec {
    /// The named sensor `name` (see [`NAMED_SENSORS`]) of the default preset (2021), or `None` if
    /// there is no such name.
    pub fn named(name: &str) -> Option<SensorSpec> {
        SensorSpec::named_in(name, Preset::default())
    }

    /// The named sensor `name` as the simulator of `preset` builds it, or `None` if there is no
    /// such name.
    pub fn named_in(name: &str, preset: Preset) -> Option<SensorSpec> {
        NAMED_SENSORS
            .iter()
            .find(|named| named.name == name)
            .map(|named| (named.spec)(preset))
    }

    /// Soft normalisation as in `preset`'s simulator: clipped first in 2022, not in 2021.
    fn soft_normalized_in(self, preset: Preset) -> SensorSpec {
        SensorSpec::SoftNormalization(SoftNormalizationSpec {
            clip: preset == Preset::Y2022,
            inner: Box::new(self),
        })
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

    /// vsr-model.md §3.2 and §9.1: 2022 soft normalisations clip first, 2021 ones do not; 2021
    /// lidars point at bin centres, 2022 ones include the ends. Sensors without either are equal.
    #[test]
    fn the_preset_decides_clipping_and_ray_layout() {
        let clip = |name: &str, preset| match SensorSpec::named_in(name, preset) {
            Some(SensorSpec::SoftNormalization(s)) => s.clip,
            other => panic!("{other:?}"),
        };
        assert!(!clip("a", Preset::Y2021) && clip("a", Preset::Y2022));
        assert!(!clip("vxy", Preset::Y2021) && clip("vxy", Preset::Y2022));
        let layout = |preset| match SensorSpec::named_in("l5", preset) {
            Some(SensorSpec::Normalization(n)) => match *n.inner {
                SensorSpec::Lidar(l) => l.layout,
                other => panic!("{other:?}"),
            },
            other => panic!("{other:?}"),
        };
        assert_eq!(
            (layout(Preset::Y2021), layout(Preset::Y2022)),
            (RayLayout::Bins, RayLayout::Ends)
        );
        assert_eq!(SensorSpec::named("l5"), SensorSpec::named_in("l5", Preset::Y2021));
        for name in ["t", "cpg", "px", "m"] {
            assert_eq!(
                SensorSpec::named_in(name, Preset::Y2021),
                SensorSpec::named_in(name, Preset::Y2022)
            );
        }
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
