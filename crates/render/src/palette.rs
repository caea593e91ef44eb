//! A fixed GIF palette of 128 colours: the exact colours the drawing uses, a 4×4×4 colour cube and
//! greys, with a lookup table from 15-bit colour to palette index. (A palette under 128 entries
//! keeps GIF's LZW codes a bit shorter than a full 256-entry one.)

use crate::draw::{self, Rgba};
use std::sync::OnceLock;

/// Number of palette entries, the last one reserved for transparency.
const SIZE: usize = 128;

/// The palette and its lookup table.
pub(crate) struct Palette {
    /// 256 RGB triplets, as the GIF global colour table.
    pub rgb: Vec<u8>,
    /// Nearest palette index of each 5-bit-per-channel colour.
    lut: Vec<u8>,
    /// Index reserved for "unchanged since the previous frame" (the last one).
    pub transparent: u8,
}

/// `top` with alpha over the opaque `under`.
fn over(top: Rgba, under: [u8; 3]) -> [u8; 3] {
    let a = f64::from(top[3]) / 255.0;
    std::array::from_fn(|i| (f64::from(top[i]) * a + f64::from(under[i]) * (1.0 - a)).round() as u8)
}

fn rgb(c: Rgba) -> [u8; 3] {
    [c[0], c[1], c[2]]
}

impl Palette {
    /// The shared palette (built once).
    pub fn get() -> &'static Palette {
        static PALETTE: OnceLock<Palette> = OnceLock::new();
        PALETTE.get_or_init(Palette::build)
    }

    fn build() -> Palette {
        let mut colors: Vec<[u8; 3]> = Vec::with_capacity(256);
        fn push(colors: &mut Vec<[u8; 3]>, c: [u8; 3]) {
            if !colors.contains(&c) {
                colors.push(c);
            }
        }
        let white = rgb(draw::BACKGROUND);
        let ground = rgb(draw::GROUND);
        for c in [
            white,
            ground,
            rgb(draw::VOXEL_OUTLINE),
            rgb(draw::TOUCH_OUTLINE),
            rgb(draw::LIDAR),
            rgb(draw::TIME_BAR),
        ] {
            push(&mut colors, c);
        }
        for ratio in [0.75, 0.8125, 0.875, 0.9375, 1.0, 1.0625, 1.125, 1.1875, 1.25] {
            let fill = over(draw::area_color(ratio), white);
            push(&mut colors, fill);
            push(&mut colors, over(draw::SENSOR_FILL, fill));
        }
        for ratio in [0.75, 1.0, 1.25] {
            push(&mut colors, over(draw::area_color(ratio), ground));
        }
        push(&mut colors, over(draw::SENSOR_FILL, white));
        push(&mut colors, over(draw::SENSOR_FILL, ground));
        let levels = [0u8, 85, 170, 255];
        let total = SIZE;
        for r in levels {
            for g in levels {
                for b in levels {
                    push(&mut colors, [r, g, b]);
                }
            }
        }
        for grey in (8..=248u8).step_by(8) {
            if colors.len() + 1 >= total {
                break;
            }
            push(&mut colors, [grey, grey, grey]);
        }
        assert!(colors.len() < total, "palette too large: {}", colors.len());
        let lut = (0..1u32 << 15)
            .map(|bin| {
                let centre = |shift: u32| ((((bin >> shift) & 31) << 3) | 4) as i32;
                let (r, g, b) = (centre(10), centre(5), centre(0));
                let dist = |c: &[u8; 3]| {
                    let (dr, dg, db) = (i32::from(c[0]) - r, i32::from(c[1]) - g, i32::from(c[2]) - b);
                    dr * dr + dg * dg + db * db
                };
                (0..colors.len())
                    .min_by_key(|&i| dist(&colors[i]))
                    .expect("palette is not empty") as u8
            })
            .collect();
        let mut table = Vec::with_capacity(768);
        for i in 0..total {
            table.extend_from_slice(colors.get(i).unwrap_or(&[255, 0, 255]));
        }
        Palette {
            rgb: table,
            lut,
            transparent: (total - 1) as u8,
        }
    }

    /// Palette index for a colour.
    #[inline]
    pub fn index(&self, r: u8, g: u8, b: u8) -> u8 {
        self.lut[(usize::from(r >> 3) << 10) | (usize::from(g >> 3) << 5) | usize::from(b >> 3)]
    }

    /// The colour of a palette index.
    #[cfg(test)]
    pub fn color(&self, i: u8) -> [u8; 3] {
        let i = usize::from(i) * 3;
        [self.rgb[i], self.rgb[i + 1], self.rgb[i + 2]]
    }

    /// Palette indices of opaque RGBA pixels, into `out`.
    pub fn quantize(&self, rgba: &[u8], out: &mut Vec<u8>) {
        out.clear();
        out.extend(rgba.chunks_exact(4).map(|p| self.index(p[0], p[1], p[2])));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_colours_map_to_themselves() {
        let p = Palette::get();
        assert_eq!(p.rgb.len(), 3 * (usize::from(p.transparent) + 1));
        for c in [
            [255, 255, 255],
            [180, 180, 180],
            [0, 0, 255],
            [255, 0, 0],
            [0, 0, 0],
            [255, 255, 127],
        ] {
            let i = p.index(c[0], c[1], c[2]);
            assert_ne!(i, p.transparent);
            assert_eq!(p.color(i), c, "{c:?}");
        }
    }

    #[test]
    fn every_colour_maps_close() {
        let p = Palette::get();
        for r in (0..=255u8).step_by(5) {
            for g in (0..=255u8).step_by(5) {
                for b in (0..=255u8).step_by(5) {
                    let i = p.index(r, g, b);
                    assert_ne!(i, p.transparent);
                    let c = p.color(i);
                    let err = [r, g, b].iter().zip(c).map(|(a, b)| a.abs_diff(b)).max().unwrap();
                    assert!(err <= 72, "{:?} -> {c:?}", [r, g, b]);
                }
            }
        }
    }
}
