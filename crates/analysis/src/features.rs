//! All descriptors of one simulated robot, from a full trace: the morphology features (dynamic
//! pose, 256 values) and the behaviour features (centre spectra on x and y, 2 × 100 values, and
//! the five footprint-gait features), thesis §3.3.3.

use crate::footprint::{gait_of, terrain_height, Footprint, FootprintParams, Gait};
use crate::pose::{dynamic_pose, Pose};
use crate::spectrum::{center_spectrum, Axis, SpectrumParams};
use serde::{Deserialize, Serialize};
use vsrlab_tasks::Trace;

/// Settings of every feature.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct FeatureParams {
    /// Centre-of-mass spectra.
    pub spectrum: SpectrumParams,
    /// Footprints and gait.
    pub footprint: FootprintParams,
}

/// The features of one episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotFeatures {
    /// Dynamic pose (f_morph).
    pub pose: Pose,
    /// Spectrum of the centre's x differences (f_center,x).
    pub spectrum_x: Vec<f64>,
    /// Spectrum of the centre's y differences (f_center,y).
    pub spectrum_y: Vec<f64>,
    /// Quantised footprints (one per Δt_footprint window).
    pub footprints: Vec<Footprint>,
    /// Main footprint n-gram and its features (f_footprint).
    pub gait: Gait,
    /// Net rotation of the body over the episode, in turns (negative: clockwise), from the
    /// orientation of voxel 0's bottom edge. Not a classifier input; used by the label proposals.
    pub turns: f64,
    /// Fraction of steps with the whole body off the ground ([`airborne_fraction`]). Not a
    /// classifier input.
    pub airborne: f64,
    /// Net x displacement of the centre over the episode, in voxel sides (negative: backwards).
    /// Not a classifier input; used by the label proposals.
    #[serde(default)]
    pub displacement: f64,
}

/// Net rotation (turns) of the bottom edge (SW → SE corner) of voxel 0, unwrapped step by step.
pub fn net_turns(trace: &Trace) -> f64 {
    let mut total = 0.0;
    let mut prev: Option<f64> = None;
    for k in 0..trace.len() {
        let Some(p) = trace.polygons_at(k).first() else {
            continue;
        };
        let a = (p[2].y - p[3].y).atan2(p[2].x - p[3].x);
        if let Some(b) = prev {
            let mut d = a - b;
            while d > std::f64::consts::PI {
                d -= 2.0 * std::f64::consts::PI;
            }
            while d <= -std::f64::consts::PI {
                d += 2.0 * std::f64::consts::PI;
            }
            total += d;
        }
        prev = Some(a);
    }
    total / (2.0 * std::f64::consts::PI)
}

/// Net x displacement of the centre from the first to the last recorded step, in voxel sides
/// (0 without centres or side length).
pub fn displacement(trace: &Trace) -> f64 {
    match (trace.centers.first(), trace.centers.last()) {
        (Some(a), Some(b)) if trace.side_length > 0.0 && (b.x - a.x).is_finite() => (b.x - a.x) / trace.side_length,
        _ => 0.0,
    }
}

/// A step is airborne when the body's lowest corner is more than this many voxel sides above the
/// terrain.
pub const AIRBORNE_CLEARANCE: f64 = 0.1;

/// Fraction of recorded steps in which the whole body is above the terrain by more than
/// [`AIRBORNE_CLEARANCE`] voxel sides (0 without outlines). Geometric rather than from the
/// contact flags, which flicker while a foot rests on the ground.
pub fn airborne_fraction(trace: &Trace) -> f64 {
    if trace.is_empty() || trace.terrain.is_empty() {
        return 0.0;
    }
    let clearance = AIRBORNE_CLEARANCE * trace.side_length;
    let steps = trace.len();
    let air = (0..steps)
        .filter(|&k| {
            let lowest = trace
                .polygons_at(k)
                .iter()
                .flat_map(|poly| poly.iter())
                .map(|v| v.y - terrain_height(&trace.terrain, v.x).unwrap_or(f64::NEG_INFINITY))
                .fold(f64::INFINITY, f64::min);
            lowest.is_finite() && lowest > clearance
        })
        .count();
    air as f64 / steps as f64
}

impl RobotFeatures {
    /// Extracts every feature from a trace recorded with `TraceLevel::Full` (the pose and
    /// footprints are empty for a centre-only trace).
    pub fn from_trace(trace: &Trace, params: &FeatureParams) -> RobotFeatures {
        let (footprints, gait) = gait_of(trace, &params.footprint);
        RobotFeatures {
            pose: dynamic_pose(trace),
            spectrum_x: center_spectrum(&trace.centers, trace.dt, Axis::X, &params.spectrum),
            spectrum_y: center_spectrum(&trace.centers, trace.dt, Axis::Y, &params.spectrum),
            footprints,
            gait,
            turns: net_turns(trace),
            airborne: airborne_fraction(trace),
            displacement: displacement(trace),
        }
    }

    /// f_morph: the 256 pose cells (row-major from the bottom row, 1 = on).
    pub fn morphology_vector(&self) -> Vec<f64> {
        self.pose.features()
    }

    /// f_behaviour = [f_center,x f_center,y f_footprint]: 2·n_freq + 5 values (205 by default).
    pub fn behaviour_vector(&self) -> Vec<f64> {
        let mut v = self.spectrum_x.clone();
        v.extend_from_slice(&self.spectrum_y);
        v.extend_from_slice(&self.gait.features());
        v
    }
}

/// Column names of [`RobotFeatures::morphology_vector`].
pub fn morphology_feature_names() -> Vec<String> {
    (0..crate::pose::POSE_SIDE * crate::pose::POSE_SIDE)
        .map(|i| format!("pose_{}_{}", i % crate::pose::POSE_SIDE, i / crate::pose::POSE_SIDE))
        .collect()
}

/// Column names of [`RobotFeatures::behaviour_vector`].
pub fn behaviour_feature_names(params: &SpectrumParams) -> Vec<String> {
    let mut names = Vec::new();
    for axis in ["x", "y"] {
        for j in 0..params.bins {
            names.push(format!("spectrum_{axis}_{:.2}hz", params.bin_upper(j)));
        }
    }
    names.extend(Gait::FEATURE_NAMES.iter().map(|s| s.to_string()));
    names
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_physics::Vec2;

    /// A synthetic "hopper": one voxel bouncing at 2 Hz, touching the ground in the lower half
    /// of each cycle, for 10 s at 60 Hz.
    fn hopper() -> Trace {
        let dt = 1.0 / 60.0;
        let mut t = Trace {
            dt,
            side_length: 3.0,
            outline_corners: vec![4],
            ..Default::default()
        };
        t.terrain = vec![Vec2::new(-1e3, 0.0), Vec2::new(1e3, 0.0)];
        for k in 0..=600 {
            let time = k as f64 * dt;
            let h = 0.5 - 0.5 * (2.0 * std::f64::consts::PI * 2.0 * time).cos(); // 0..1
            let x = 0.3 * time;
            t.times.push(time);
            t.centers.push(Vec2::new(x + 1.5, h + 1.5));
            t.outlines.extend_from_slice(&[
                Vec2::new(x, h + 3.0),
                Vec2::new(x + 3.0, h + 3.0),
                Vec2::new(x + 3.0, h),
                Vec2::new(x, h),
            ]);
            vsrlab_tasks::Probe::step(&mut t, &vsrlab_tasks::channels::TOUCH, &[f64::from(u8::from(h < 0.05))]);
        }
        t
    }

    #[test]
    fn features_of_a_hopper() {
        let f = RobotFeatures::from_trace(&hopper(), &FeatureParams::default());
        assert_eq!(f.pose.count(), 256);
        let peak = (0..100)
            .max_by(|&a, &b| f.spectrum_y[a].total_cmp(&f.spectrum_y[b]))
            .unwrap();
        assert_eq!(peak, 19, "2 Hz bin");
        assert_eq!(f.morphology_vector().len(), 256);
        assert_eq!(f.behaviour_vector().len(), 205);
        assert_eq!(behaviour_feature_names(&SpectrumParams::default()).len(), 205);
        assert_eq!(morphology_feature_names().len(), 256);
        // Touching only ~1/7 of each 0.5 s cycle: every quantised footprint is empty, so the main
        // n-gram is two empty footprints repeating every 1 s.
        assert_eq!(f.footprints.len(), 20);
        assert!(f.footprints.iter().all(|&p| p == 0));
        assert_eq!(f.gait.ngram, vec![0, 0]);
        assert_eq!(f.gait.occurrences, 10);
        assert!(f.turns.abs() < 1e-12);
        // Airborne while h > 0.1 · 3 = 0.3, i.e. cos θ < 0.4: 1 − acos(0.4)/π ≈ 0.631 of each cycle.
        assert!((0.62..0.645).contains(&f.airborne), "{}", f.airborne);
    }

    #[test]
    fn turns_of_a_rolling_square() {
        // A unit square rotating clockwise by 3 full turns over 300 steps.
        let mut t = Trace {
            dt: 0.01,
            outline_corners: vec![4],
            ..Default::default()
        };
        for k in 0..=300 {
            let a = -2.0 * std::f64::consts::PI * 3.0 * k as f64 / 300.0;
            let c = |dx: f64, dy: f64| Vec2::new(dx * a.cos() - dy * a.sin(), dx * a.sin() + dy * a.cos());
            t.times.push(k as f64 * 0.01);
            t.outlines
                .extend_from_slice(&[c(-0.5, 0.5), c(0.5, 0.5), c(0.5, -0.5), c(-0.5, -0.5)]);
        }
        assert!((net_turns(&t) + 3.0).abs() < 1e-9);
    }
}
