//! The camera: which rectangle of the world a frame shows (vsr-model.md §6, `AllRobotFollower(1.5, 2)`).

use crate::RenderOptions;
use vsrlab_physics::Vec2;
use vsrlab_tasks::{channels, Trace};

/// Simulated seconds of history whose bounding boxes the camera keeps in view.
pub(crate) const WINDOW: f64 = 2.0;
/// Factor by which the union of the bounding boxes is enlarged.
pub(crate) const ENLARGE: f64 = 1.5;

/// The rectangle of the world shown by a frame (world units, y up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Left edge.
    pub min_x: f64,
    /// Bottom edge.
    pub min_y: f64,
    /// Right edge.
    pub max_x: f64,
    /// Top edge.
    pub max_y: f64,
}

impl View {
    /// Pixels per world unit for an image `width` pixels wide.
    pub fn scale(&self, width: u32) -> f64 {
        f64::from(width) / (self.max_x - self.min_x)
    }
    /// Whether the world point `p` is inside the view.
    pub fn contains(&self, p: Vec2) -> bool {
        (self.min_x..=self.max_x).contains(&p.x) && (self.min_y..=self.max_y).contains(&p.y)
    }
    /// Image coordinates (x right, y down) of the world point `p` in an image `width` pixels wide.
    pub fn to_pixel(&self, p: Vec2, width: u32) -> (f32, f32) {
        let s = self.scale(width);
        (((p.x - self.min_x) * s) as f32, ((self.max_y - p.y) * s) as f32)
    }
}

/// An axis-aligned box in world coordinates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BBox {
    pub min: Vec2,
    pub max: Vec2,
}

impl BBox {
    /// The smallest box holding the finite points of `pts`, if any.
    pub fn of_points(pts: impl IntoIterator<Item = Vec2>) -> Option<BBox> {
        pts.into_iter()
            .filter(|p| p.x.is_finite() && p.y.is_finite())
            .map(|p| BBox { min: p, max: p })
            .reduce(BBox::union)
    }
    /// The smallest box holding both.
    pub fn union(self, o: BBox) -> BBox {
        BBox {
            min: Vec2::new(self.min.x.min(o.min.x), self.min.y.min(o.min.y)),
            max: Vec2::new(self.max.x.max(o.max.x), self.max.y.max(o.max.y)),
        }
    }
}

/// The robot's bounding box at every step: of its voxel polygons, or, for traces recorded
/// without them, a voxel-sized box around its centre.
pub(crate) fn step_boxes(trace: &Trace) -> Vec<Option<BBox>> {
    let half = side(trace) / 2.0;
    let obstacles = channels::obstacles(trace);
    (0..trace.len())
        .map(|k| {
            let body = BBox::of_points(trace.polygons_at(k).iter().flatten().copied()).or_else(|| {
                let c = *trace.centers.get(k)?;
                BBox::of_points([c - Vec2::new(half, half), c + Vec2::new(half, half)])
            })?;
            // the loose balls, and obstacles that overlap the body's box grown by its own size
            // (a cage around it), stay in view
            let ball_boxes = channels::balls(trace, k)
                .into_iter()
                .filter_map(|(c, _, r)| BBox::of_points([c - Vec2::new(r, r), c + Vec2::new(r, r)]));
            let reach = BBox {
                min: body.min - (body.max - body.min),
                max: body.max + (body.max - body.min),
            };
            let near = obstacles
                .iter()
                .filter_map(|p| BBox::of_points(p.iter().copied()))
                .filter(|o| {
                    o.min.x <= reach.max.x && o.max.x >= reach.min.x && o.min.y <= reach.max.y && o.max.y >= reach.min.y
                });
            Some(ball_boxes.chain(near).fold(body, BBox::union))
        })
        .collect()
}

/// Voxel side length, or 1 when the trace does not say.
pub(crate) fn side(trace: &Trace) -> f64 {
    if trace.side_length.is_finite() && trace.side_length > 0.0 {
        trace.side_length
    } else {
        1.0
    }
}

/// The view at `step` given the per-step boxes of [`step_boxes`].
pub(crate) fn view_at(trace: &Trace, boxes: &[Option<BBox>], step: usize, width: u32, height: u32) -> View {
    let mut union: Option<BBox> = None;
    if let Some(&now) = trace.times.get(step) {
        let mut j = step.min(boxes.len().saturating_sub(1));
        while let Some(b) = boxes.get(j) {
            if let Some(b) = b {
                union = Some(union.map_or(*b, |u| u.union(*b)));
            }
            if j == 0 || trace.times.get(j - 1).is_none_or(|&t| t < now - WINDOW - 1e-9) {
                break;
            }
            j -= 1;
        }
    }
    let min_size = side(trace);
    let b = union.unwrap_or(BBox {
        min: Vec2::new(0.0, 0.0),
        max: Vec2::new(10.0 * min_size, 10.0 * min_size),
    });
    let c = (b.min + b.max) * 0.5;
    let mut w = (b.max.x - b.min.x).max(min_size) * ENLARGE;
    let mut h = (b.max.y - b.min.y).max(min_size) * ENLARGE;
    let aspect = f64::from(width.max(1)) / f64::from(height.max(1));
    if w / h < aspect {
        w = h * aspect;
    } else {
        h = w / aspect;
    }
    View {
        min_x: c.x - w / 2.0,
        min_y: c.y - h / 2.0,
        max_x: c.x + w / 2.0,
        max_y: c.y + h / 2.0,
    }
}

/// The rectangle of the world that [`render_frame`](crate::render_frame) shows at `step`: the union
/// of the robot's bounding boxes over the last 2 s of simulated time, enlarged ×1.5 about its
/// centre and padded to the image's aspect ratio.
pub fn camera_view(trace: &Trace, step: usize, opts: &RenderOptions) -> View {
    let boxes = step_boxes(trace);
    view_at(
        trace,
        &boxes,
        step.min(trace.len().saturating_sub(1)),
        opts.width,
        opts.height,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{moving_square, square_trace};

    #[test]
    fn view_is_enlarged_and_padded_to_aspect() {
        let t = square_trace(1.0);
        let v = camera_view(&t, 0, &RenderOptions::default());
        // one 3×3 voxel at x∈[10,13], y∈[5,8]: 4.5 high after ×1.5, 8 wide after 16:9 padding
        assert!((v.max_y - v.min_y - 4.5).abs() < 1e-9, "{v:?}");
        assert!((v.max_x - v.min_x - 8.0).abs() < 1e-9, "{v:?}");
        assert!((v.min_x + v.max_x - 23.0).abs() < 1e-9, "{v:?}");
        assert!((v.min_y + v.max_y - 13.0).abs() < 1e-9, "{v:?}");
    }

    #[test]
    fn view_covers_the_last_two_seconds() {
        // moves right 10 units per second for 5 s at 60 Hz
        let t = moving_square(301, 10.0);
        let k = 300;
        let v = camera_view(&t, k, &RenderOptions::default());
        let now = t.polygons_at(k).first().unwrap();
        let two_s_ago = t.polygons_at(k - 120).first().unwrap();
        let older = t.polygons_at(k - 240).first().unwrap();
        for p in now.iter().chain(two_s_ago.iter()) {
            assert!(v.contains(*p), "{p:?} not in {v:?}");
        }
        assert!(
            !older.iter().all(|p| v.contains(*p)),
            "a box 4 s old is still fully in view"
        );
    }

    #[test]
    fn empty_trace_gives_a_finite_view() {
        let v = camera_view(&Trace::default(), 3, &RenderOptions::default());
        assert!(v.min_x.is_finite() && v.max_x > v.min_x && v.max_y > v.min_y);
    }
}
