//! Text: the bundled DejaVu Sans font (`assets/fonts/` of the workspace, Bitstream Vera licence), registered with
//! plotters' `ab_glyph` feature so no system font is looked up, and the text styles figures use.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::sync::Once;

const FONT: &str = "sans-serif";
static FONT_BYTES: &[u8] = include_bytes!("../../../../assets/fonts/DejaVuSans.ttf");
static REGISTER: Once = Once::new();

/// Registers the bundled font with plotters (once per process).
pub(super) fn register_font() {
    REGISTER.call_once(|| {
        if plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES).is_err() {
            panic!("the bundled DejaVu Sans font is valid");
        }
    });
}

/// Black text of `size` pixels.
pub(super) fn text_style(size: u32) -> TextStyle<'static> {
    TextStyle::from((FONT, size).into_font()).color(&BLACK)
}

/// Black text of `size` pixels anchored at (`h`, `v`) of its position.
pub(super) fn anchored(size: u32, h: HPos, v: VPos) -> TextStyle<'static> {
    text_style(size).pos(Pos::new(h, v))
}
