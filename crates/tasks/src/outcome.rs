//! What an episode returns: distance, velocity, and optionally a per-step trace.

use serde::{Deserialize, Serialize};
use vsrlab_physics::Vec2;

/// How much of an episode to record.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum TraceLevel {
    /// Only the summary figures (fastest; what evolution uses).
    #[default]
    None,
    /// Also the robot's centre at every step.
    Center,
    /// Everything needed to draw or analyse the episode.
    Full,
}

/// The result of one episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// x displacement of the robot's centre over the evaluated window.
    pub distance: f64,
    /// distance / elapsed time of the window (the usual fitness).
    pub velocity: f64,
    /// Simulated time spanned by the window (t_last − t_first).
    pub elapsed: f64,
    /// Number of physics steps simulated.
    pub steps: u64,
    /// Number of voxels of the robot.
    pub voxels: usize,
    /// Per-step record, when asked for.
    pub trace: Option<Trace>,
}

/// A lidar ray of one voxel: direction relative to the voxel angle, and its range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RayInfo {
    /// Index of the voxel (grid order).
    pub voxel: usize,
    /// Direction relative to the voxel's angle (radians).
    pub relative_angle: f64,
    /// Maximum distance.
    pub range: f64,
}

/// Per-step record of an episode. Arrays indexed [step][voxel] are stored flat, step-major.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Trace {
    /// Time step (s).
    pub dt: f64,
    /// Voxel side length.
    pub side_length: f64,
    /// Terrain polyline.
    pub terrain: Vec<Vec2>,
    /// Grid cell of each voxel (grid order).
    pub cells: Vec<(usize, usize)>,
    /// Time of each recorded step.
    pub times: Vec<f64>,
    /// Robot centre at each step.
    pub centers: Vec<Vec2>,
    /// Voxel outer polygons (NW, NE, SE, SW corners), [step][voxel].
    pub polygons: Vec<[Vec2; 4]>,
    /// Area ratios, [step][voxel].
    pub area_ratios: Vec<f64>,
    /// Voxel angles, [step][voxel].
    pub angles: Vec<f64>,
    /// Touch flags, [step][voxel].
    pub touching: Vec<bool>,
    /// Actuation applied after sensing, [step][voxel].
    pub actuations: Vec<f64>,
    /// Number of sensor readings of each voxel.
    pub readings_per_voxel: Vec<usize>,
    /// Sensor readings scaled to [0, 1] by each reading's domain, [step][reading].
    pub readings: Vec<f32>,
    /// The lidar rays, in order.
    pub rays: Vec<RayInfo>,
    /// Lidar distances, [step][ray].
    pub ray_distances: Vec<f32>,
}

impl Trace {
    /// Number of recorded steps.
    pub fn len(&self) -> usize {
        self.times.len()
    }
    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.times.is_empty()
    }
    /// Number of voxels.
    pub fn voxels(&self) -> usize {
        self.cells.len()
    }
    /// Voxel polygons at step `k`.
    pub fn polygons_at(&self, k: usize) -> &[[Vec2; 4]] {
        let n = self.voxels();
        self.polygons.get(k * n..(k + 1) * n).unwrap_or(&[])
    }
}
