//! Text on frames: the bundled DejaVu Sans (`assets/fonts/`, Bitstream Vera licence) rasterised
//! with `ab_glyph` straight into the pixmap, so no system font is needed.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont};
use std::sync::OnceLock;
use tiny_skia::{Pixmap, PremultipliedColorU8};

static FONT_BYTES: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

fn font() -> &'static FontRef<'static> {
    static FONT: OnceLock<FontRef<'static>> = OnceLock::new();
    FONT.get_or_init(|| FontRef::try_from_slice(FONT_BYTES).expect("the bundled DejaVu Sans font is valid"))
}

/// Width in pixels of `text` at `size` pixels.
pub(crate) fn width(text: &str, size: f32) -> f32 {
    let scaled = font().as_scaled(PxScale::from(size));
    text.chars().map(|c| scaled.h_advance(font().glyph_id(c))).sum()
}

/// Draws `text` with its top-left corner at (`x`, `y`) pixels, `size` pixels high, in `rgb`.
pub(crate) fn draw(pm: &mut Pixmap, text: &str, x: f32, y: f32, size: f32, rgb: [u8; 3]) {
    let font = font();
    let scaled = font.as_scaled(PxScale::from(size));
    let baseline = y + scaled.ascent();
    let mut caret = x;
    for c in text.chars() {
        let id = font.glyph_id(c);
        let glyph = id.with_scale_and_position(size, ab_glyph::point(caret, baseline));
        caret += scaled.h_advance(id);
        let Some(outline) = font.outline_glyph(glyph) else {
            continue;
        };
        let bounds = outline.px_bounds();
        outline.draw(|gx, gy, coverage| {
            let px = bounds.min.x as i64 + i64::from(gx);
            let py = bounds.min.y as i64 + i64::from(gy);
            blend(pm, px, py, rgb, coverage);
        });
    }
}

/// Blends `rgb` over the pixel at (`x`, `y`) with opacity `alpha` (pixels outside are ignored).
pub(crate) fn blend(pm: &mut Pixmap, x: i64, y: i64, rgb: [u8; 3], alpha: f32) {
    let (w, h) = (i64::from(pm.width()), i64::from(pm.height()));
    if x < 0 || y < 0 || x >= w || y >= h || alpha <= 0.0 {
        return;
    }
    let a = alpha.min(1.0);
    let i = (y * w + x) as usize;
    let pixel = pm.pixels_mut()[i];
    let mix = |src: u8, dst: u8| (f32::from(src) * a + f32::from(dst) * (1.0 - a)).round() as u8;
    // frames are opaque, so premultiplied and straight colours are the same
    let blended = PremultipliedColorU8::from_rgba(
        mix(rgb[0], pixel.red()),
        mix(rgb[1], pixel.green()),
        mix(rgb[2], pixel.blue()),
        255,
    );
    if let Some(p) = blended {
        pm.pixels_mut()[i] = p;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_darkens_pixels_where_it_is_drawn_and_only_there() {
        let mut pm = Pixmap::new(120, 30).unwrap();
        pm.fill(tiny_skia::Color::WHITE);
        draw(&mut pm, "t = 1.5 s", 2.0, 2.0, 16.0, [0, 0, 0]);
        let dark = |x0: u32, x1: u32| {
            (0..30)
                .flat_map(|y| (x0..x1).map(move |x| (x, y)))
                .filter(|&(x, y)| pm.pixels()[(y * 120 + x) as usize].red() < 128)
                .count()
        };
        let w = width("t = 1.5 s", 16.0);
        assert!(w > 40.0 && w < 110.0, "{w}");
        assert!(dark(0, w as u32 + 3) > 30);
        assert_eq!(dark(w as u32 + 4, 120), 0);
    }
}
