//! MP4 output through an external `ffmpeg` reading raw RGB frames on its standard input.

use crate::draw::Scene;
use crate::file::{io_err, to_rgb};
use crate::{RenderError, RenderOptions};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use vsrlab_tasks::files::TempPath;
use vsrlab_tasks::Trace;

/// The `ffmpeg` executable on PATH, if any.
pub(crate) fn find_ffmpeg() -> Option<PathBuf> {
    let names: &[&str] = if cfg!(windows) { &["ffmpeg.exe"] } else { &["ffmpeg"] };
    std::env::split_paths(&std::env::var_os("PATH")?)
        .flat_map(|dir| names.iter().map(move |n| dir.join(n)))
        .find(|p| p.is_file())
}

/// Whether an `ffmpeg` executable is on PATH.
pub fn ffmpeg_available() -> bool {
    find_ffmpeg().is_some()
}

/// The error when `ffmpeg`, asked to write `path`, cannot be started.
fn cannot_run<'a>(ffmpeg: &'a Path, path: &'a Path) -> impl FnOnce(std::io::Error) -> RenderError + 'a {
    move |e| {
        RenderError::EncoderUnavailable(format!(
            "cannot write {}: cannot run {}: {e}",
            path.display(),
            ffmpeg.display()
        ))
    }
}

/// Codec arguments: H.264 when this ffmpeg has libx264, else MPEG-4 part 2.
fn codec_args(ffmpeg: &Path, path: &Path) -> Result<&'static [&'static str], RenderError> {
    let out = Command::new(ffmpeg)
        .args(["-hide_banner", "-encoders"])
        .stdin(Stdio::null())
        .stderr(Stdio::null())
        .output()
        .map_err(cannot_run(ffmpeg, path))?;
    let list = String::from_utf8_lossy(&out.stdout);
    let has = |name: &str| list.lines().any(|l| l.split_whitespace().nth(1) == Some(name));
    if has("libx264") {
        Ok(&[
            "-c:v",
            "libx264",
            "-preset",
            "veryfast",
            "-crf",
            "20",
            "-pix_fmt",
            "yuv420p",
            "-movflags",
            "+faststart",
        ])
    } else if has("mpeg4") {
        Ok(&[
            "-c:v",
            "mpeg4",
            "-q:v",
            "3",
            "-pix_fmt",
            "yuv420p",
            "-movflags",
            "+faststart",
        ])
    } else {
        Err(RenderError::EncoderUnavailable(format!(
            "cannot write {}: {} has neither the libx264 nor the mpeg4 encoder; use .gif",
            path.display(),
            ffmpeg.display()
        )))
    }
}

/// Writes the frames showing `steps` of `trace` as an MP4 at `path`.
pub(crate) fn save_mp4(trace: &Trace, steps: &[usize], opts: &RenderOptions, path: &Path) -> Result<(), RenderError> {
    let Some(ffmpeg) = find_ffmpeg() else {
        return Err(RenderError::EncoderUnavailable(format!(
            "cannot write {}: mp4 needs ffmpeg on PATH: apt-get install ffmpeg, or use .gif",
            path.display()
        )));
    };
    let codec = codec_args(&ffmpeg, path)?;
    let tmp = TempPath::beside(path);
    let size = format!("{}x{}", opts.width, opts.height);
    let fps = format!("{}", opts.fps);
    let mut child = Command::new(&ffmpeg)
        .args([
            "-hide_banner",
            "-loglevel",
            "error",
            "-y",
            "-f",
            "rawvideo",
            "-pix_fmt",
            "rgb24",
        ])
        .args(["-s", &size, "-framerate", &fps, "-i", "pipe:0", "-an"])
        .args(["-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"])
        .args(codec)
        .args(["-f", "mp4"])
        .arg(tmp.path())
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .map_err(cannot_run(&ffmpeg, path))?;
    let mut stderr = child.stderr.take().expect("stderr is piped");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = stderr.read_to_string(&mut s);
        s
    });
    let mut stdin = child.stdin.take().expect("stdin is piped");
    let scene = Scene::new(trace, opts, true);
    let mut pm = scene.new_pixmap();
    let mut rgb = Vec::new();
    let mut write_error = None;
    for &step in steps {
        scene.draw(step, &mut pm);
        to_rgb(&pm, &mut rgb);
        if let Err(e) = stdin.write_all(&rgb) {
            write_error = Some(e);
            break;
        }
    }
    drop(stdin);
    let status = child.wait().map_err(io_err(path))?;
    let log = reader.join().unwrap_or_default();
    if !status.success() || write_error.is_some() {
        let detail = log.trim();
        let detail = if detail.is_empty() {
            write_error.map(|e| e.to_string()).unwrap_or_default()
        } else {
            detail
                .lines()
                .rev()
                .take(5)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
                .join("; ")
        };
        return Err(RenderError::Encode {
            path: path.to_path_buf(),
            message: format!("ffmpeg ({status}): {detail}"),
        });
    }
    tmp.commit().map_err(io_err(path))
}
