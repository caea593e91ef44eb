//! Attention matrices drawn on the voxels (thesis Fig. 4.12): a small r × r heat map in each
//! voxel, blue for −1, white for 0, red for +1 (the entries of A = tanh(Q·Kᵀ/√d) lie in [−1, 1]).

use tiny_skia::{Color, Paint, Pixmap, Rect, Transform};

/// Colour of an attention value: white at 0, towards blue (−1) or red (+1).
pub(crate) fn attention_color(value: f32) -> [u8; 3] {
    let v = if value.is_finite() { value.clamp(-1.0, 1.0) } else { 0.0 };
    let towards = if v >= 0.0 {
        [200.0, 30.0, 30.0]
    } else {
        [40.0, 80.0, 210.0]
    };
    let k = v.abs();
    towards.map(|c: f32| (255.0 + (c - 255.0) * k).round() as u8)
}

/// Draws an r × r matrix (row-major) as a heat map whose top-left corner is at `top_left` (pixels)
/// and whose side is `size` pixels, with a dark frame.
pub(crate) fn draw_matrix(pm: &mut Pixmap, top_left: (f32, f32), size: f32, r: usize, matrix: &[f64]) {
    if r == 0 || size < 2.0 || matrix.len() < r * r {
        return;
    }
    // whole pixels and no anti-aliasing: crisp cells, and no sub-pixel rectangles (which
    // tiny-skia's anti-aliased hairline filler rejects)
    let size = size.round();
    let top_left = (top_left.0.round(), top_left.1.round());
    let cell = (size / r as f32).floor().max(1.0);
    let size = cell * r as f32;
    let mut paint = Paint {
        anti_alias: false,
        ..Paint::default()
    };
    for a in 0..r {
        for b in 0..r {
            let [red, green, blue] = attention_color(matrix[a * r + b] as f32);
            paint.set_color(Color::from_rgba8(red, green, blue, 235));
            let x = top_left.0 + b as f32 * cell;
            let y = top_left.1 + a as f32 * cell;
            if let Some(rect) = Rect::from_xywh(x, y, cell, cell) {
                pm.fill_rect(rect, &paint, Transform::identity(), None);
            }
        }
    }
    paint.set_color(Color::from_rgba8(40, 40, 40, 255));
    let (x, y) = top_left;
    for rect in [
        Rect::from_xywh(x, y, size, 1.0),
        Rect::from_xywh(x, y + size - 1.0, size, 1.0),
        Rect::from_xywh(x, y, 1.0, size),
        Rect::from_xywh(x + size - 1.0, y, 1.0, size),
    ]
    .into_iter()
    .flatten()
    {
        pm.fill_rect(rect, &paint, Transform::identity(), None);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_run_from_blue_through_white_to_red() {
        assert_eq!(attention_color(0.0), [255, 255, 255]);
        assert_eq!(attention_color(1.0), [200, 30, 30]);
        assert_eq!(attention_color(-1.0), [40, 80, 210]);
        assert_eq!(attention_color(5.0), attention_color(1.0));
        assert_eq!(attention_color(f32::NAN), [255, 255, 255]);
    }

    #[test]
    fn each_cell_gets_its_value_colour() {
        let mut pm = Pixmap::new(40, 40).unwrap();
        draw_matrix(&mut pm, (0.0, 0.0), 40.0, 2, &[1.0, 0.0, -1.0, 0.0]);
        let at = |x: u32, y: u32| {
            let p = pm.pixel(x, y).unwrap().demultiply();
            [p.red(), p.green(), p.blue()]
        };
        assert!(
            at(10, 10)[0] > 190 && at(10, 10)[2] < 60,
            "top-left red: {:?}",
            at(10, 10)
        );
        assert!(
            at(10, 30)[2] > 190 && at(10, 30)[0] < 60,
            "bottom-left blue: {:?}",
            at(10, 30)
        );
        assert!(at(30, 10).iter().all(|&c| c > 240), "top-right white: {:?}", at(30, 10));
    }
}
