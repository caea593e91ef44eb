//! Atomic file writing: write a hidden temporary file beside the target, then rename it.

use crate::RenderError;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use tiny_skia::Pixmap;

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

/// A temporary file in the target's directory, removed on drop unless committed.
pub(crate) struct TempFile {
    /// Where the temporary file lives.
    pub path: PathBuf,
    committed: bool,
}

impl TempFile {
    /// A fresh temporary name beside `dest` (nothing is created yet).
    pub fn beside(dest: &Path) -> TempFile {
        static COUNTER: AtomicU64 = AtomicU64::new(0);
        let dir = match dest.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = dest
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let path = dir.join(format!(".{name}.{}.{n}.tmp", std::process::id()));
        TempFile { path, committed: false }
    }

    /// Moves the temporary file to `dest`, replacing what is there.
    pub fn commit(mut self, dest: &Path) -> Result<(), RenderError> {
        std::fs::rename(&self.path, dest).map_err(io_err(dest))?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// Writes `dest` through `write`, atomically: on any error nothing is left behind.
pub(crate) fn write_atomically(
    dest: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), RenderError>,
) -> Result<(), RenderError> {
    let tmp = TempFile::beside(dest);
    let file = File::create(&tmp.path).map_err(io_err(dest))?;
    let mut w = BufWriter::with_capacity(1 << 16, file);
    write(&mut w)?;
    let file = w.into_inner().map_err(|e| io_err(dest)(e.into_error()))?;
    file.sync_all().map_err(io_err(dest))?;
    drop(file);
    tmp.commit(dest)
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
