//! Sensor descriptions: a [`SensorSpec`] is plain data naming one sensor kind (vsr-model.md
//! §3.1–3.2), possibly wrapped. It is the list of registered kinds: each variant's description, its
//! readings, domains, checks and running form live in that sensor's file and are reached through
//! [`SensorSpec::as_kind`], the only `match` over the kinds.

use super::angle;
use super::area_ratio;
use super::average::AverageSpec;
use super::constant::ConstantPositionSpec;
use super::cpg;
use super::kind::SensorKind;
use super::lidar::LidarSpec;
use super::malfunction;
use super::noise::NoisySpec;
use super::normalization::NormalizationSpec;
use super::soft_normalization::SoftNormalizationSpec;
use super::touch;
use super::trend::TrendSpec;
use super::velocity::VelocitySpec;
use serde::{Deserialize, Serialize};
use vsrlab_field::FieldError;

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
    /// Voxel velocity; domain [−vmax, vmax] per component ([`VelocitySpec`]).
    Velocity(VelocitySpec),
    /// Voxel angle; domain [−π, π].
    Angle,
    /// Distances from the voxel centre to static geometry along rays on the voxel's outer side;
    /// domain [0, range] per ray ([`LidarSpec`]).
    Lidar(LidarSpec),
    /// sin(−2πt), t the simulated time; domain [−1, 1].
    Cpg,
    /// The voxel's relative grid position along an axis, fixed; domain [0, 1]
    /// ([`ConstantPositionSpec`]).
    ConstantPosition(ConstantPositionSpec),
    /// 1 once the voxel is broken (no voxel can break yet, so always 0); domain [0, 1].
    Malfunction,
    /// Mean of the inner readings over a time window; domain unchanged ([`AverageSpec`]).
    Average(AverageSpec),
    /// Slope of the inner readings over a time window; domain ±extent/window ([`TrendSpec`]).
    Trend(TrendSpec),
    /// Clip to the inner domain, then map linearly to [0, 1] ([`NormalizationSpec`]).
    Normalization(NormalizationSpec),
    /// tanh(2(2v − 1))/2 + 1/2 of the linearly normalised value v; domain [0, 1]
    /// ([`SoftNormalizationSpec`]).
    SoftNormalization(SoftNormalizationSpec),
    /// Adds Gaussian noise relative to the inner domain's extent; domain unchanged
    /// ([`NoisySpec`]).
    Noisy(NoisySpec),
}

impl SensorSpec {
    /// The registered kind's description, through which every other method goes.
    pub(crate) fn as_kind(&self) -> &dyn SensorKind {
        match self {
            SensorSpec::AreaRatio => &area_ratio::SPEC,
            SensorSpec::Touch => &touch::SPEC,
            SensorSpec::Velocity(kind) => kind,
            SensorSpec::Angle => &angle::SPEC,
            SensorSpec::Lidar(kind) => kind,
            SensorSpec::Cpg => &cpg::SPEC,
            SensorSpec::ConstantPosition(kind) => kind,
            SensorSpec::Malfunction => &malfunction::SPEC,
            SensorSpec::Average(kind) => kind,
            SensorSpec::Trend(kind) => kind,
            SensorSpec::Normalization(kind) => kind,
            SensorSpec::SoftNormalization(kind) => kind,
            SensorSpec::Noisy(kind) => kind,
        }
    }

    /// This sensor averaged over `window` seconds.
    pub fn averaged(self, window: f64) -> SensorSpec {
        SensorSpec::Average(AverageSpec {
            window,
            inner: Box::new(self),
        })
    }

    /// The trend of this sensor over `window` seconds.
    pub fn trend(self, window: f64) -> SensorSpec {
        SensorSpec::Trend(TrendSpec {
            window,
            inner: Box::new(self),
        })
    }

    /// This sensor clipped and mapped linearly to [0, 1].
    pub fn normalized(self) -> SensorSpec {
        SensorSpec::Normalization(NormalizationSpec { inner: Box::new(self) })
    }

    /// This sensor soft-normalised, thesis-era style (no clipping).
    pub fn soft_normalized(self) -> SensorSpec {
        SensorSpec::SoftNormalization(SoftNormalizationSpec {
            clip: false,
            inner: Box::new(self),
        })
    }

    /// This sensor with Gaussian noise of relative standard deviation `sigma`.
    pub fn noisy(self, sigma: f64) -> SensorSpec {
        SensorSpec::Noisy(NoisySpec {
            sigma,
            inner: Box::new(self),
        })
    }

    /// Number of readings.
    pub fn dimension(&self) -> usize {
        self.as_kind().dimension()
    }

    /// Declared domain (min, max) of each reading, after wrapping.
    pub fn domains(&self) -> Vec<(f64, f64)> {
        self.as_kind().domains()
    }

    /// Checks every parameter of the tree. The error's path locates the parameter in this
    /// description (`window`, `inner.range`: a wrapped sensor's); its message names the parameter
    /// in words (`lidar range must be …`) and the accepted range.
    pub fn validate(&self) -> Result<(), FieldError> {
        self.validate_at(0)
    }

    /// [`SensorSpec::validate`] below `noisy_depth` `Noisy` wrappers.
    pub(crate) fn validate_at(&self, noisy_depth: usize) -> Result<(), FieldError> {
        self.as_kind().validate(noisy_depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensors::{Axes, RayLayout};
    use std::f64::consts::PI;

    #[test]
    fn dimensions_and_domains_follow_the_wrappers() {
        let v = SensorSpec::Velocity(VelocitySpec {
            rotated: true,
            vmax: 4.0,
            axes: Axes::Xy,
        });
        assert_eq!(v.dimension(), 2);
        assert_eq!(v.domains(), vec![(-4.0, 4.0); 2]);
        assert_eq!(v.clone().trend(0.5).domains(), vec![(-16.0, 16.0); 2]);
        assert_eq!(v.clone().averaged(0.5).domains(), vec![(-4.0, 4.0); 2]);
        assert_eq!(v.clone().trend(0.5).soft_normalized().domains(), vec![(0.0, 1.0); 2]);
        assert_eq!(v.noisy(0.1).domains(), vec![(-4.0, 4.0); 2]);
        let lidar = SensorSpec::Lidar(LidarSpec {
            range: 10.0,
            rays: 5,
            layout: RayLayout::Ends,
        });
        assert_eq!((lidar.dimension(), lidar.domains()[4]), (5, (0.0, 10.0)));
        assert_eq!(SensorSpec::Angle.domains(), vec![(-PI, PI)]);
        assert_eq!(SensorSpec::AreaRatio.domains(), vec![(0.5, 1.5)]);
        assert_eq!(SensorSpec::Cpg.normalized().domains(), vec![(0.0, 1.0)]);
    }

    #[test]
    fn validation_names_the_bad_parameter() {
        let e = SensorSpec::Touch.averaged(-1.0).validate().unwrap_err();
        assert_eq!(e.path, "window");
        assert_eq!(e.message, "window must be a finite number > 0, got -1");
        let e = SensorSpec::Lidar(LidarSpec {
            range: 10.0,
            rays: 0,
            layout: RayLayout::Ends,
        })
        .trend(1.0)
        .validate()
        .unwrap_err();
        assert_eq!(
            (e.path.as_str(), e.message.as_str()),
            ("inner.rays", "lidar rays must be 1 to 1024, got 0")
        );
        let e = SensorSpec::AreaRatio
            .noisy(f64::NAN)
            .normalized()
            .validate()
            .unwrap_err();
        assert_eq!(e.path, "inner.sigma");
        assert!(e.message.starts_with("noise sigma must be"), "{e}");
        let e = SensorSpec::Velocity(VelocitySpec {
            rotated: true,
            vmax: 0.0,
            axes: Axes::X,
        })
        .validate()
        .unwrap_err();
        assert_eq!(
            (e.path.as_str(), e.message.as_str()),
            ("vmax", "velocity vmax must be a finite number > 0, got 0")
        );
        assert!(SensorSpec::Touch.averaged(0.25).noisy(0.0).validate().is_ok());
    }

    #[test]
    fn serde_round_trips_a_tree() {
        let spec = SensorSpec::Velocity(VelocitySpec {
            rotated: true,
            vmax: 8.0,
            axes: Axes::Xy,
        })
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

    #[test]
    fn serialised_forms_keep_their_field_order_and_reject_unknown_fields() {
        let forms = [
            (
                "vxy",
                r#"{"kind":"soft-normalization","clip":false,"inner":{"kind":"average","window":0.5,"inner":{"kind":"velocity","rotated":true,"vmax":8.0,"axes":"xy"}}}"#,
            ),
            (
                "l5",
                r#"{"kind":"normalization","inner":{"kind":"lidar","range":10.0,"rays":5,"layout":"bins"}}"#,
            ),
            ("px", r#"{"kind":"constant-position","axis":"x"}"#),
            ("m", r#"{"kind":"malfunction"}"#),
        ];
        for (name, json) in forms {
            let spec = SensorSpec::named(name).unwrap();
            assert_eq!(serde_json::to_string(&spec).unwrap(), json, "{name}");
        }
        let head = SensorSpec::named_in("l5", crate::Preset::Y2022).unwrap();
        assert_eq!(
            serde_json::to_string(&head).unwrap(),
            r#"{"kind":"normalization","inner":{"kind":"lidar","range":10.0,"rays":5}}"#,
            "the default layout is left out"
        );
        let noisy = SensorSpec::Touch.trend(0.5).noisy(0.1);
        assert_eq!(
            serde_json::to_string(&noisy).unwrap(),
            r#"{"kind":"noisy","sigma":0.1,"inner":{"kind":"trend","window":0.5,"inner":{"kind":"touch"}}}"#
        );
        for bad in [
            r#"{"kind": "lidar", "range": 1, "rays": 2, "angle": 1}"#,
            r#"{"kind": "noisy", "sigma": 0.1}"#,
            r#"{"kind": "average", "window": 0.1, "inner": {"kind": "cpg"}, "clip": true}"#,
            r#"{"kind": "constant-position", "axis": "z"}"#,
            r#"{"kind": "gyroscope"}"#,
        ] {
            assert!(serde_json::from_str::<SensorSpec>(bad).is_err(), "{bad}");
        }
    }
}
