//! `vsrlab-render`: draws episodes recorded in a [`Trace`] as PNG images, GIF animations or MP4
//! videos.
//!
//! Drawing follows the original simulator's conventions (vsr-model.md §6):
//! - each voxel's outer polygon is filled by its area ratio (red ≤ 0.75, yellow at 1, green ≥ 1.25,
//!   all at 50 % alpha, linear in between) and outlined in blue (darker and thicker while it
//!   touches the ground);
//! - sensor readings are a half-disk at the voxel centre (radius √area / 2, turned by the voxel
//!   angle), split evenly among the voxel's readings, each a black 33 %-alpha sector whose radius
//!   is proportional to the reading;
//! - each lidar ray is a red segment from the voxel centre as long as the measured distance, with a
//!   0.5-diameter circle at the hit when something was closer than the range;
//! - the ground is a grey polygon outlined in black;
//! - the camera frames the union of the robot's bounding boxes over the last 2 s, enlarged ×1.5 and
//!   padded to the image's aspect ratio.
//!
//! World y points up, image y points down. A thin bar along the top edge shows elapsed time.
//!
//! 3D traces (channel `voxel_xyz`) are drawn in perspective instead: a camera from the front side
//! and above follows the body; each voxel is a cube shaded by a fixed light over a checkerboard floor.
#![warn(missing_docs)]

mod attention;
mod camera;
mod draw;
mod file;
mod gif_out;
mod graph;
mod mp4_out;
mod overlay;
mod palette;
pub mod replay;
mod solid3d;
mod text;
pub mod viewer;

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

pub use camera::{camera_view, View};
pub use draw::render_frame;
pub use mp4_out::ffmpeg_available;
pub use tiny_skia::Pixmap;
pub use vsrlab_tasks::Trace;

/// Largest image side accepted (pixels).
pub const MAX_SIDE: u32 = 8192;

/// How to draw an episode.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RenderOptions {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Frames per second of videos (frames are picked from the trace's steps by time).
    pub fps: f64,
    /// Whether to draw the sensor-reading half-disks.
    pub draw_sensors: bool,
    /// Whether to draw the lidar rays.
    pub draw_lidar: bool,
    /// Whether to write time, distance and velocity at the top left.
    pub draw_overlay: bool,
    /// Whether to draw distance ticks into the ground (one per voxel side).
    pub draw_ticks: bool,
    /// Whether to draw the legend of the voxel colours at the top right.
    pub draw_legend: bool,
    /// Whether to draw the path of the robot's centre.
    pub draw_trail: bool,
    /// Whether to draw each voxel's attention matrix (attention brains), in place of its sensor
    /// glyph.
    pub draw_attention: bool,
    /// Whether to draw a graph brain's neurons and edges over the body (graph brains), in
    /// place of the sensor glyphs.
    pub draw_graph: bool,
    /// Whether to colour each voxel by its vote (brains that vote, e.g. `elman`): blue for
    /// "passable" (> 0), red for "impassable", in place of the actuation tint.
    pub draw_votes: bool,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            width: 640,
            height: 360,
            fps: 25.0,
            draw_sensors: true,
            draw_lidar: true,
            draw_overlay: true,
            draw_ticks: true,
            draw_legend: true,
            draw_trail: false,
            draw_attention: true,
            draw_graph: true,
            draw_votes: true,
        }
    }
}

/// The layers `--draw` can name, in drawing order.
pub const LAYERS: &[&str] = &[
    "ticks",
    "trail",
    "sensors",
    "lidar",
    "attention",
    "graph",
    "votes",
    "overlay",
    "legend",
];

impl RenderOptions {
    /// The same options drawing exactly the layers named in `list` (comma-separated names from
    /// [`LAYERS`], `all`, or `none`: the world and the robot only).
    pub fn with_layers(&self, list: &str) -> Result<RenderOptions, RenderError> {
        let mut o = self.clone();
        let names: Vec<&str> = list.split(',').map(str::trim).filter(|s| !s.is_empty()).collect();
        let all = names == ["all"];
        for layer in LAYERS {
            let on = all || names.contains(layer);
            match *layer {
                "ticks" => o.draw_ticks = on,
                "trail" => o.draw_trail = on,
                "sensors" => o.draw_sensors = on,
                "lidar" => o.draw_lidar = on,
                "attention" => o.draw_attention = on,
                "graph" => o.draw_graph = on,
                "votes" => o.draw_votes = on,
                "overlay" => o.draw_overlay = on,
                _ => o.draw_legend = on,
            }
        }
        if let Some(bad) = names
            .iter()
            .find(|n| !LAYERS.contains(n) && !["all", "none"].contains(n))
        {
            return Err(RenderError::InvalidOptions(format!(
                "draw: unknown layer '{bad}': expected some of {}, or all, or none",
                LAYERS.join(", ")
            )));
        }
        Ok(o)
    }

    /// Checks sizes and frame rate; the error message names the bad field.
    pub fn validate(&self) -> Result<(), RenderError> {
        for (name, v) in [("width", self.width), ("height", self.height)] {
            if v == 0 || v > MAX_SIDE {
                return Err(RenderError::InvalidOptions(format!(
                    "{name} must be between 1 and {MAX_SIDE} pixels, got {v}"
                )));
            }
        }
        if !(self.fps.is_finite() && self.fps > 0.0 && self.fps <= 1000.0) {
            return Err(RenderError::InvalidOptions(format!(
                "fps must be a number in (0, 1000], got {}",
                self.fps
            )));
        }
        Ok(())
    }
}

/// What went wrong while drawing or writing a file.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    /// The options are unusable; the message names the field.
    #[error("invalid render options: {0}")]
    InvalidOptions(String),
    /// The trace cannot be drawn (empty, or recorded without the voxel polygons).
    #[error("cannot render {path}: {problem}")]
    InvalidTrace {
        /// The file that was to be written.
        path: PathBuf,
        /// What is missing.
        problem: String,
    },
    /// The requested step is not in the trace.
    #[error("cannot render {path}: step {step} is out of range (the trace has {len} steps)")]
    StepOutOfRange {
        /// The file that was to be written.
        path: PathBuf,
        /// The requested step.
        step: usize,
        /// Number of steps in the trace.
        len: usize,
    },
    /// The file extension names no supported format.
    #[error("cannot render {path}: unsupported extension {ext:?} (use .gif, .mp4 or .png)")]
    UnsupportedExtension {
        /// The file that was to be written.
        path: PathBuf,
        /// The extension found (empty when there is none).
        ext: String,
    },
    /// The encoder needed for this format is missing (message says how to get it).
    #[error("{0}")]
    EncoderUnavailable(String),
    /// The encoder failed.
    #[error("encoding {path} failed: {message}")]
    Encode {
        /// The file that was being written.
        path: PathBuf,
        /// The encoder's report.
        message: String,
    },
    /// Reading or writing a file failed.
    #[error("cannot write {path}: {source}")]
    Io {
        /// The file concerned.
        path: PathBuf,
        /// The system's report.
        source: std::io::Error,
    },
}

/// The kind of file written by [`save_video`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum VideoFormat {
    /// Animated GIF (built in).
    Gif,
    /// H.264 (or MPEG-4 part 2) in MP4, through an external `ffmpeg`.
    Mp4,
    /// A single PNG image of the last step.
    Png,
}

/// What [`save_video`] wrote.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VideoInfo {
    /// The file written.
    pub path: PathBuf,
    /// Its format.
    pub format: VideoFormat,
    /// Number of frames (1 for PNG).
    pub frames: usize,
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Frames per second.
    pub fps: f64,
    /// Playing time in seconds (frames / fps).
    pub duration: f64,
    /// Size of the file in bytes.
    pub bytes: u64,
}

/// Steps of `trace` shown by the frames of a video at `fps` frames per second: one frame every
/// 1/fps s of simulated time from the first step to the last, each the step nearest in time.
pub fn frame_steps(trace: &Trace, fps: f64) -> Vec<usize> {
    let times = &trace.times;
    let (Some(&t0), Some(&t1)) = (times.first(), times.last()) else {
        return Vec::new();
    };
    let usable = fps.is_finite() && fps > 0.0 && t1.is_finite() && t0.is_finite() && t1 >= t0;
    if !usable {
        return vec![0];
    }
    let frames = ((t1 - t0) * fps + 1e-6).floor() as usize + 1;
    (0..frames)
        .map(|i| {
            let t = t0 + i as f64 / fps;
            let j = times.partition_point(|&x| x < t).min(times.len() - 1);
            if j > 0 && (t - times[j - 1]) <= (times[j] - t) {
                j - 1
            } else {
                j
            }
        })
        .collect()
}

/// Checks that `trace` holds what drawing needs; `path` is named in the error.
fn check_trace(trace: &Trace, path: &Path) -> Result<(), RenderError> {
    let problem = |p: &str| RenderError::InvalidTrace {
        path: path.to_path_buf(),
        problem: p.to_string(),
    };
    if trace.is_empty() {
        return Err(problem("the trace has no steps"));
    }
    if solid3d::is_solid(trace) {
        if !solid3d::has_every_step(trace) {
            return Err(problem("the 3D trace has no voxel positions for every step"));
        }
        return Ok(());
    }
    if trace.outline_corners.is_empty() || trace.outlines.len() < trace.len() * trace.corners_per_step() {
        return Err(problem(
            "the trace has no voxel polygons for every step (record it with trace level \"full\")",
        ));
    }
    Ok(())
}

/// Draws step `step` of `trace` and writes it as a PNG to `path` (atomically).
pub fn save_png(trace: &Trace, step: usize, opts: &RenderOptions, path: impl AsRef<Path>) -> Result<(), RenderError> {
    let path = path.as_ref();
    opts.validate()?;
    check_trace(trace, path)?;
    if step >= trace.len() {
        return Err(RenderError::StepOutOfRange {
            path: path.to_path_buf(),
            step,
            len: trace.len(),
        });
    }
    let pixmap = render_frame(trace, step, opts);
    let mut bytes = Vec::new();
    file::write_png(&mut bytes, &pixmap, path)?;
    file::write_file(path, &bytes)
}

/// Renders the whole episode to `path`, the format chosen by its extension (any case): `.gif`
/// (built in; looping, 128 colours, drawn without anti-aliasing to stay small; GIF timing is in
/// hundredths of a second, so above 50 fps it plays slower), `.mp4` (H.264, or MPEG-4 part 2, by
/// piping frames to `ffmpeg` found on PATH) or `.png` (only the last step). The file is written
/// atomically: nothing is left at `path` (nor beside it) when an error is returned.
pub fn save_video(trace: &Trace, opts: &RenderOptions, path: impl AsRef<Path>) -> Result<VideoInfo, RenderError> {
    let path = path.as_ref();
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    let format = match ext.as_str() {
        "gif" => VideoFormat::Gif,
        "mp4" => VideoFormat::Mp4,
        "png" => VideoFormat::Png,
        _ => {
            return Err(RenderError::UnsupportedExtension {
                path: path.to_path_buf(),
                ext,
            })
        }
    };
    opts.validate()?;
    check_trace(trace, path)?;
    let frames = match format {
        VideoFormat::Png => {
            save_png(trace, trace.len() - 1, opts, path)?;
            1
        }
        VideoFormat::Gif => {
            let steps = frame_steps(trace, opts.fps);
            gif_out::save_gif(trace, &steps, opts, path)?;
            steps.len()
        }
        VideoFormat::Mp4 => {
            let steps = frame_steps(trace, opts.fps);
            mp4_out::save_mp4(trace, &steps, opts, path)?;
            steps.len()
        }
    };
    let bytes = std::fs::metadata(path)
        .map_err(|source| RenderError::Io {
            path: path.to_path_buf(),
            source,
        })?
        .len();
    Ok(VideoInfo {
        path: path.to_path_buf(),
        format,
        frames,
        width: opts.width,
        height: opts.height,
        fps: opts.fps,
        duration: if format == VideoFormat::Png {
            0.0
        } else {
            frames as f64 / opts.fps
        },
        bytes,
    })
}

#[cfg(test)]
mod tests;
#[cfg(test)]
pub(crate) mod testutil;
