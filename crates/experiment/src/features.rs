//! The shape and behaviour features the runner hands to the speciated evolver (SE-s, SE-b), computed
//! by `vsrlab-analysis` so that evolution and analysis see the same numbers (thesis §3.3.2–3.3.3;
//! docs/analysis.md has every definition and its departures from the thesis). MAP-Elites'
//! morphology descriptors come from the robot's kind (`vsrlab_tasks::BodySummary`; the grid kinds
//! compute them with `vsrlab_body::descriptors`, which analyses use too).
//!
//! | feature | definition |
//! | --- | --- |
//! | d_num | voxels of the decoded body |
//! | d_elong | eccentricity of the moment-equivalent ellipse of the voxel cells |
//! | d_compact | voxels ÷ cells inside or on the convex hull of the voxel cells |
//! | SE-s | 16×16 dynamic pose (element-wise mode of the per-step poses), as 0/1 values |
//! | SE-b | spectrum of \|Δy\| of the robot's centre, 100 bins over (0, 10] Hz (2D-VSR-Sim's \|Δy\|, exact bin frequencies) |

use vsrlab_analysis::{pose, spectrum, Axis, SpectrumParams};
use vsrlab_tasks::Trace;

/// Number of values of the SE-s feature vector.
pub const POSE_LEN: usize = pose::POSE_SIDE * pose::POSE_SIDE;

/// The spectrum settings of SE-b.
fn se_b_spectrum() -> SpectrumParams {
    SpectrumParams {
        absolute: true,
        ..SpectrumParams::default()
    }
}

/// Number of values of the SE-b feature vector.
pub fn spectrum_len() -> usize {
    se_b_spectrum().bins
}

/// SE-s: the dynamic pose of a full trace, 1.0 for an occupied cell.
pub fn dynamic_pose(trace: &Trace) -> Vec<f64> {
    pose::dynamic_pose(trace)
        .0
        .iter()
        .map(|&on| if on { 1.0 } else { 0.0 })
        .collect()
}

/// SE-b: the spectrum of |Δy| of the robot's centre.
pub fn center_spectrum(trace: &Trace) -> Vec<f64> {
    spectrum::center_spectrum(&trace.centers, trace.dt, Axis::Y, &se_b_spectrum())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feature_lengths_are_the_thesis_ones() {
        assert_eq!(POSE_LEN, 256);
        assert_eq!(spectrum_len(), 100);
    }
}
