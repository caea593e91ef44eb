//! Animated GIF output: frames drawn without anti-aliasing, a fixed 128-colour palette, and each
//! frame after the first holding only the rectangle that changed, unchanged pixels transparent.

use crate::draw::Scene;
use crate::file::{encode_err, write_file};
use crate::palette::Palette;
use crate::{RenderError, RenderOptions};
use gif::{DisposalMethod, Encoder, Frame, Repeat};
use std::borrow::Cow;
use std::path::Path;
use vsrlab_tasks::Trace;

/// Delay of frame `i` in hundredths of a second, rounded so that delays add up to the right
/// total; at least 2 (players slow down shorter delays), so GIFs above 50 fps play slower.
pub(crate) fn delay(i: usize, fps: f64) -> u16 {
    let at = |i: usize| (i as f64 * 100.0 / fps).round();
    (at(i + 1) - at(i)).clamp(2.0, f64::from(u16::MAX)) as u16
}

/// The GIF frame turning `prev` (the indices on screen) into `cur`.
pub(crate) fn frame_between(
    prev: Option<&[u8]>,
    cur: &[u8],
    width: u16,
    height: u16,
    transparent: u8,
) -> Frame<'static> {
    let (w, h) = (usize::from(width), usize::from(height));
    let Some(prev) = prev else {
        return Frame::from_indexed_pixels(width, height, cur.to_vec(), None);
    };
    let (mut top, mut bottom, mut left, mut right) = (usize::MAX, 0, usize::MAX, 0);
    for y in 0..h {
        let (a, b) = (&prev[y * w..(y + 1) * w], &cur[y * w..(y + 1) * w]);
        if a == b {
            continue;
        }
        let first = a.iter().zip(b).position(|(p, q)| p != q).unwrap_or(0);
        let last = w
            - 1
            - a.iter()
                .rev()
                .zip(b.iter().rev())
                .position(|(p, q)| p != q)
                .unwrap_or(0);
        top = top.min(y);
        bottom = y;
        left = left.min(first);
        right = right.max(last);
    }
    if top == usize::MAX {
        // nothing changed: one transparent pixel keeps the frame (and its delay)
        return Frame {
            width: 1,
            height: 1,
            transparent: Some(transparent),
            buffer: Cow::Owned(vec![transparent]),
            ..Frame::default()
        };
    }
    let (fw, fh) = (right - left + 1, bottom - top + 1);
    let mut buf = Vec::with_capacity(fw * fh);
    for y in top..=bottom {
        let row = y * w + left..y * w + right + 1;
        buf.extend(
            prev[row.clone()]
                .iter()
                .zip(&cur[row])
                .map(|(&p, &q)| if p == q { transparent } else { q }),
        );
    }
    Frame {
        left: left as u16,
        top: top as u16,
        width: fw as u16,
        height: fh as u16,
        transparent: Some(transparent),
        buffer: Cow::Owned(buf),
        ..Frame::default()
    }
}

/// Writes the frames showing `steps` of `trace` as a looping GIF at `path`.
pub(crate) fn save_gif(trace: &Trace, steps: &[usize], opts: &RenderOptions, path: &Path) -> Result<(), RenderError> {
    // without anti-aliasing: edges stay crisp in the palette and the file is about half as large
    let scene = Scene::new(trace, opts, false);
    let palette = Palette::get();
    let (width, height) = (opts.width as u16, opts.height as u16);
    let mut bytes = Vec::new();
    {
        let mut enc = Encoder::new(&mut bytes, width, height, &palette.rgb).map_err(encode_err(path))?;
        enc.set_repeat(Repeat::Infinite).map_err(encode_err(path))?;
        let mut pm = scene.new_pixmap();
        let (mut prev, mut cur) = (Vec::new(), Vec::new());
        for (i, &step) in steps.iter().enumerate() {
            scene.draw(step, &mut pm);
            palette.quantize(pm.data(), &mut cur);
            let mut frame = frame_between(
                (i > 0).then_some(prev.as_slice()),
                &cur,
                width,
                height,
                palette.transparent,
            );
            frame.delay = delay(i, opts.fps);
            frame.dispose = DisposalMethod::Keep;
            enc.write_frame(&frame).map_err(encode_err(path))?;
            std::mem::swap(&mut prev, &mut cur);
        }
        enc.into_inner().map_err(encode_err(path))?;
    }
    write_file(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn delays_add_up() {
        let total: u32 = (0..30).map(|i| u32::from(delay(i, 30.0))).sum();
        assert_eq!(total, 100);
        assert!((0..30).all(|i| (3..=4).contains(&delay(i, 30.0))));
        assert_eq!(delay(0, 1000.0), 2);
    }

    #[test]
    fn frame_holds_only_the_changed_rectangle() {
        let (w, h) = (5u16, 4u16);
        let prev = vec![1u8; 20];
        let mut cur = prev.clone();
        cur[5 + 1] = 7; // (1, 1)
        cur[2 * 5 + 3] = 9; // (3, 2)
        let transparent = 63;
        let f = frame_between(Some(&prev), &cur, w, h, transparent);
        assert_eq!((f.left, f.top, f.width, f.height), (1, 1, 3, 2));
        assert_eq!(&*f.buffer, &[7, transparent, transparent, transparent, transparent, 9]);
        let same = frame_between(Some(&prev), &prev, w, h, transparent);
        assert_eq!((same.width, same.height, &*same.buffer), (1, 1, &[transparent][..]));
        let first = frame_between(None, &cur, w, h, transparent);
        assert_eq!((first.width, first.height, first.transparent), (5, 4, None));
    }
}
