//! Output files: encoded images written atomically through the project's helper
//! ([`vsrlab_tasks::files::write_atomic`]), and the errors that name them.

use crate::RenderError;
use std::io::Write;
use std::path::Path;
use tiny_skia::Pixmap;
use vsrlab_tasks::files::write_atomic;

/// An `io::Error` → [`RenderError::Io`] naming `path`.
pub(crate) fn io_err(path: &Path) -> impl Fn(std::io::Error) -> RenderError + '_ {
    move |source| RenderError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// An encoder failure → [`RenderError::Encode`] naming `path`.
pub(crate) fn encode_err<E: std::fmt::Display>(path: &Path) -> impl Fn(E) -> RenderError + '_ {
    move |e| RenderError::Encode {
        path: path.to_path_buf(),
        message: e.to_string(),
    }
}

/// Writes `bytes` to `dest` atomically (through [`write_atomic`]): on any error nothing is left
/// behind.
pub(crate) fn write_file(dest: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    write_atomic(dest, bytes).map_err(io_err(dest))
}

/// The opaque frame's pixels as packed RGB (frames are opaque, so premultiplication is moot).
pub(crate) fn to_rgb(pm: &Pixmap, out: &mut Vec<u8>) {
    out.clear();
    out.reserve(pm.data().len() / 4 * 3);
    for px in pm.data().chunks_exact(4) {
        out.extend_from_slice(&px[..3]);
    }
}

/// Encodes `pm` as an 8-bit RGB PNG into `w`; errors name `dest`.
pub(crate) fn write_png(w: impl Write, pm: &Pixmap, dest: &Path) -> Result<(), RenderError> {
    let mut rgb = Vec::new();
    to_rgb(pm, &mut rgb);
    let mut enc = png::Encoder::new(w, pm.width(), pm.height());
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(encode_err(dest))?;
    writer.write_image_data(&rgb).map_err(encode_err(dest))?;
    writer.finish().map_err(encode_err(dest))
}
