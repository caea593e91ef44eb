//! The fixed perspective camera of 3D frames: it looks at a target from the front side and above
//! (a set azimuth and elevation) and projects world points to pixels.

use super::vec3::Vec3;

/// Direction of the camera seen from the target, degrees counter-clockwise from +x: in front of
/// the body (−y) and a little to its right, so a body walking along +x crosses the image left to right.
pub(crate) const AZIMUTH_DEG: f64 = -60.0;
/// Height of the camera above the target's horizontal plane, degrees.
pub(crate) const ELEVATION_DEG: f64 = 25.0;
/// Field of view across the image's shorter side, degrees: wide enough that the horizon shows
/// near the top.
pub(crate) const FOV_DEG: f64 = 55.0;
/// Image row of the target, as a fraction of the height from the top (below the middle, to show
/// more sky).
const TARGET_ROW: f64 = 0.55;
/// How much room the framing leaves around the body (1: its bounding sphere touches the edges).
const MARGIN: f64 = 1.4;
/// Nearest depth drawn, as a fraction of the distance to the target.
const NEAR_FRACTION: f64 = 0.02;

/// A perspective camera: its position, axes (right, up, forward) and the pixel scale.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Camera {
    eye: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    /// Pixels per unit of (lateral offset / depth).
    focal: f64,
    /// Where the view axis meets the image, in pixels (the target's pixel).
    centre: (f64, f64),
    /// Points closer than this depth are cut away.
    near: f64,
}

impl Camera {
    /// The camera `distance` metres from `target` at the fixed azimuth and elevation, for an
    /// image `width` × `height` pixels.
    pub fn looking_at(target: Vec3, distance: f64, width: u32, height: u32) -> Camera {
        let (az, el) = (AZIMUTH_DEG.to_radians(), ELEVATION_DEG.to_radians());
        let towards_eye = Vec3::new(el.cos() * az.cos(), el.cos() * az.sin(), el.sin());
        let forward = -towards_eye;
        let right = forward.cross(Vec3::new(0.0, 0.0, 1.0)).normalized();
        let up = right.cross(forward);
        let short_side = f64::from(width.min(height));
        Camera {
            eye: target + towards_eye * distance,
            right,
            up,
            forward,
            focal: 0.5 * short_side / (FOV_DEG.to_radians() / 2.0).tan(),
            centre: (f64::from(width) / 2.0, f64::from(height) * TARGET_ROW),
            near: distance * NEAR_FRACTION,
        }
    }

    /// The distance at which a sphere of `radius` around the target fills the view with margin
    /// (the image's shorter side).
    pub fn framing_distance(radius: f64) -> f64 {
        radius * MARGIN / (FOV_DEG.to_radians() / 2.0).sin()
    }

    /// Where the camera is.
    pub fn eye(&self) -> Vec3 {
        self.eye
    }

    /// Depth of world point `p` along the view direction (negative behind the camera).
    pub fn depth(&self, p: Vec3) -> f64 {
        (p - self.eye).dot(self.forward)
    }

    /// `p` in camera coordinates: x right, y up, z depth along the view direction.
    fn camera_space(&self, p: Vec3) -> Vec3 {
        let d = p - self.eye;
        Vec3::new(d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }

    /// Pixel of a camera-space point in front of the camera.
    fn pixel_of(&self, c: Vec3) -> (f32, f32) {
        let x = self.centre.0 + self.focal * c.x / c.z;
        let y = self.centre.1 - self.focal * c.y / c.z;
        (x as f32, y as f32)
    }

    /// Pixel of world point `p`, or `None` when it is behind the near plane (tests use it to find
    /// where things land).
    #[cfg(test)]
    pub fn project(&self, p: Vec3) -> Option<(f32, f32)> {
        let c = self.camera_space(p);
        (c.z >= self.near).then(|| self.pixel_of(c))
    }

    /// The polygon of world points `corners` in pixels, cut at the near plane (empty when it
    /// lies wholly behind it).
    pub fn project_polygon(&self, corners: &[Vec3]) -> Vec<(f32, f32)> {
        let in_camera: Vec<Vec3> = corners.iter().map(|&p| self.camera_space(p)).collect();
        clip_near(&in_camera, self.near)
            .into_iter()
            .map(|c| self.pixel_of(c))
            .collect()
    }

    /// Image row of the horizon (where the floor meets the sky far away): above the target by
    /// the elevation's tangent.
    pub fn horizon_y(&self) -> f32 {
        (self.centre.1 - self.focal * ELEVATION_DEG.to_radians().tan()) as f32
    }

    /// Image row where the horizontal floor at height `floor_z` is `depth` away (rows nearer the
    /// horizon are farther): a plane's depth depends on the row only.
    pub fn floor_row(&self, floor_z: f64, depth: f64) -> f32 {
        let el = ELEVATION_DEG.to_radians();
        let height = self.eye.z - floor_z;
        let v = (el.sin() - height / depth) / el.cos();
        (self.centre.1 - self.focal * v) as f32
    }
}

/// The part of a camera-space polygon at depth ≥ `near` (Sutherland–Hodgman against one plane).
fn clip_near(poly: &[Vec3], near: f64) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, &a) in poly.iter().enumerate() {
        let b = poly[(i + 1) % poly.len()];
        let (a_in, b_in) = (a.z >= near, b.z >= near);
        if a_in {
            out.push(a);
        }
        if a_in != b_in {
            out.push(a.lerp(b, (near - a.z) / (b.z - a.z)));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_target_projects_to_the_image_centre_and_up_stays_up() {
        let target = Vec3::new(1.0, 2.0, 0.5);
        let cam = Camera::looking_at(target, 3.0, 200, 100);
        let (x, y) = cam.project(target).unwrap();
        assert!((x - 100.0).abs() < 1e-3 && (y - 55.0).abs() < 1e-3, "{x} {y}");
        let (_, above) = cam.project(target + Vec3::new(0.0, 0.0, 0.1)).unwrap();
        assert!(above < y, "higher points are higher in the image");
        let (right, _) = cam.project(target + Vec3::new(0.1, 0.0, 0.0)).unwrap();
        assert!(right > x, "+x runs to the right");
        assert!(cam.eye().y < target.y && cam.eye().z > target.z, "in front and above");
    }

    #[test]
    fn points_behind_the_camera_are_cut_away() {
        let cam = Camera::looking_at(Vec3::default(), 1.0, 100, 100);
        let behind = cam.eye() + (cam.eye() - Vec3::default());
        assert_eq!(cam.project(behind), None);
        assert!(cam
            .project_polygon(&[
                behind,
                behind + Vec3::new(0.1, 0.0, 0.0),
                behind + Vec3::new(0.0, 0.0, 0.1)
            ])
            .is_empty());
        let half = cam.project_polygon(&[behind, Vec3::default(), Vec3::new(0.1, 0.0, 0.0)]);
        assert_eq!(half.len(), 4, "a triangle cut once becomes a quadrilateral");
        assert!(half.iter().all(|p| p.0.is_finite() && p.1.is_finite()));
    }

    #[test]
    fn far_floor_points_approach_the_horizon() {
        let cam = Camera::looking_at(Vec3::default(), 1.0, 100, 100);
        let far = Vec3::new(0.0, 0.0, 0.0) + (Vec3::default() - cam.eye()) * 1e6;
        let (_, y) = cam.project(Vec3::new(far.x, far.y, 0.0)).unwrap();
        assert!((y - cam.horizon_y()).abs() < 0.1, "{y} vs {}", cam.horizon_y());
    }

    #[test]
    fn floor_rows_match_projected_floor_points() {
        let cam = Camera::looking_at(Vec3::new(0.3, 0.2, 0.5), 2.0, 300, 200);
        for p in [
            Vec3::new(0.3, 0.2, 0.0),
            Vec3::new(1.0, 3.0, 0.0),
            Vec3::new(-2.0, 0.5, 0.0),
        ] {
            let (_, y) = cam.project(p).unwrap();
            let row = cam.floor_row(0.0, cam.depth(p));
            assert!((y - row).abs() < 1e-3, "{y} vs {row}");
        }
    }
}
