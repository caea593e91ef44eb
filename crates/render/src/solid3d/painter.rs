//! The painter's algorithm: every visible face of every cube, sorted far to near, filled and
//! outlined in that order so nearer faces cover farther ones.

use super::camera::Camera;
use super::cube::Cube;
use super::shading;
use super::vec3::Vec3;
use crate::draw::{paint, stroke, Rgba};
use tiny_skia::{FillRule, PathBuilder, Pixmap, Transform};

/// A face to paint: its corners, shaded fill, outline and its width, and its distance from the
/// eye.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Face {
    corners: [Vec3; 4],
    fill: Rgba,
    outline: Rgba,
    outline_width: f32,
    distance: f64,
}

/// The faces of `cube` that `camera` sees, in base colour `color` shaded by their direction,
/// outlined in a darker shade, or in `border` (2 pixels wide) when given.
pub(crate) fn visible_faces(
    cube: &Cube,
    color: Rgba,
    border: Option<Rgba>,
    camera: &Camera,
) -> impl Iterator<Item = Face> {
    let eye = camera.eye();
    cube.visible_faces(eye).map(move |f| Face {
        corners: f.corners,
        fill: shading::shaded(color, f.normal),
        outline: border.unwrap_or_else(|| shading::outline(color)),
        outline_width: if border.is_some() { 2.0 } else { 1.0 },
        distance: (f.centre - eye).length(),
    })
}

/// Paints `faces` far to near (sorted in place).
pub(crate) fn paint_faces(pm: &mut Pixmap, camera: &Camera, faces: &mut [Face], anti_alias: bool) {
    faces.sort_by(|a, b| b.distance.total_cmp(&a.distance));
    for face in faces.iter() {
        let pixels = camera.project_polygon(&face.corners);
        fill_polygon(
            pm,
            &pixels,
            face.fill,
            Some((face.outline, face.outline_width)),
            anti_alias,
        );
    }
}

/// Fills the pixel polygon `pixels` with `fill`, and strokes it with `outline` (colour, width in
/// pixels) when given (nothing for fewer than three corners).
pub(crate) fn fill_polygon(
    pm: &mut Pixmap,
    pixels: &[(f32, f32)],
    fill: Rgba,
    outline: Option<(Rgba, f32)>,
    anti_alias: bool,
) {
    let Some(path) = closed_path(pixels) else {
        return;
    };
    pm.fill_path(
        &path,
        &paint(fill, anti_alias),
        FillRule::Winding,
        Transform::identity(),
        None,
    );
    if let Some((outline, width)) = outline {
        pm.stroke_path(
            &path,
            &paint(outline, anti_alias),
            &stroke(width),
            Transform::identity(),
            None,
        );
    }
}

/// The closed path through `pixels` (`None` under three corners or with a non-finite one).
fn closed_path(pixels: &[(f32, f32)]) -> Option<tiny_skia::Path> {
    if pixels.len() < 3 || pixels.iter().any(|p| !p.0.is_finite() || !p.1.is_finite()) {
        return None;
    }
    let mut pb = PathBuilder::new();
    pb.move_to(pixels[0].0, pixels[0].1);
    for &(x, y) in &pixels[1..] {
        pb.line_to(x, y);
    }
    pb.close();
    pb.finish()
}
