//! Tests of the file outputs.

use crate::palette::Palette;
use crate::testutil::*;
use crate::*;
use std::path::Path;

/// A fresh empty directory for one test, removed with its files when dropped.
struct Scratch(PathBuf);

impl Scratch {
    /// The directory `vsrlab-render-<process>-<name>` in the system's temporary folder, emptied.
    fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("vsrlab-render-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;

    fn deref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A video of the moving square that a test saved in its scratch directory.
struct Saved {
    /// The scratch directory.
    dir: Scratch,
    /// The trace drawn: the voxel moving right at 3 units per second.
    trace: Trace,
    /// The options it was drawn with.
    opts: RenderOptions,
    /// The file written.
    path: PathBuf,
    /// What [`save_video`] returned.
    result: Result<VideoInfo, RenderError>,
}

/// Saves `steps` steps of the moving square, `width` × `height` pixels (default options
/// otherwise), as `file` in a fresh scratch directory.
fn save_moving_square(file: &str, steps: usize, (width, height): (u32, u32)) -> Saved {
    let dir = Scratch::new(file);
    let trace = moving_square(steps, 3.0);
    let opts = RenderOptions {
        width,
        height,
        ..RenderOptions::default()
    };
    let path = dir.join(file);
    let result = save_video(&trace, &opts, &path);
    Saved {
        dir,
        trace,
        opts,
        path,
        result,
    }
}

/// Names of the files in `dir`.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Decodes a GIF: number of frames, the screen's palette indices after the last frame, and delays.
fn decode_gif(path: &Path) -> (usize, Vec<u8>, Vec<u16>) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::Indexed);
    let mut dec = opts.read_info(std::fs::File::open(path).unwrap()).unwrap();
    let (w, h) = (usize::from(dec.width()), usize::from(dec.height()));
    let mut screen = vec![0u8; w * h];
    let (mut frames, mut delays) = (0, Vec::new());
    while let Some(f) = dec.read_next_frame().unwrap() {
        frames += 1;
        delays.push(f.delay);
        assert_eq!(f.dispose, gif::DisposalMethod::Keep);
        for y in 0..usize::from(f.height) {
            for x in 0..usize::from(f.width) {
                let i = f.buffer[y * usize::from(f.width) + x];
                if Some(i) != f.transparent {
                    screen[(y + usize::from(f.top)) * w + x + usize::from(f.left)] = i;
                }
            }
        }
    }
    (frames, screen, delays)
}

#[test]
fn frame_steps_subsample_by_time() {
    let t = moving_square(121, 1.0); // 2 s at 60 Hz
    let s = frame_steps(&t, 30.0);
    assert_eq!(s.len(), 61);
    assert!(s.iter().enumerate().all(|(i, &k)| k == 2 * i), "{s:?}");
    assert_eq!(frame_steps(&t, 60.0), (0..121).collect::<Vec<_>>());
    assert_eq!(frame_steps(&t, 1.0), vec![0, 60, 120]);
    assert!(frame_steps(&Trace::default(), 30.0).is_empty());
}

#[test]
fn gif_has_header_frames_and_final_picture() {
    let v = save_moving_square("walk.gif", 121, (160, 90));
    let info = v.result.unwrap();
    assert_eq!(info.format, VideoFormat::Gif);
    assert_eq!(info.frames, 51);
    assert_eq!((info.width, info.height), (160, 90));
    let bytes = std::fs::read(&v.path).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    assert_eq!(info.bytes, bytes.len() as u64);
    let (frames, screen, delays) = decode_gif(&v.path);
    assert_eq!(frames, 51);
    // 25 fps: every frame lasts exactly 4 hundredths, so playback keeps simulated time
    assert!(delays.iter().all(|&d| d == 4), "{delays:?}");
    // what the player shows at the end is the last frame (drawn without anti-aliasing), quantized
    let scene = crate::draw::Scene::new(&v.trace, &v.opts, false);
    let mut last = scene.new_pixmap();
    scene.draw(120, &mut last);
    let mut want = Vec::new();
    Palette::get().quantize(last.data(), &mut want);
    let colors: std::collections::HashSet<&u8> = want.iter().collect();
    assert!(colors.len() >= 5, "too few colours: {colors:?}");
    assert!(!screen.contains(&Palette::get().transparent));
    assert!(screen == want, "composited GIF differs from the last frame");
    assert_eq!(listing(&v.dir), vec!["walk.gif"], "temporary files left behind");
}

#[test]
fn png_is_the_last_frame() {
    let v = save_moving_square("last.PNG", 30, (200, 120));
    let info = v.result.unwrap();
    assert_eq!((info.format, info.frames), (VideoFormat::Png, 1));
    let dec = png::Decoder::new(std::fs::File::open(&v.path).unwrap());
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut buf).unwrap();
    assert_eq!(
        (frame.width, frame.height, frame.color_type),
        (200, 120, png::ColorType::Rgb)
    );
    let mut want = Vec::new();
    file::to_rgb(&render_frame(&v.trace, 29, &v.opts), &mut want);
    assert!(buf[..frame.buffer_size()] == want[..]);
    let mut first = Vec::new();
    file::to_rgb(&render_frame(&v.trace, 0, &v.opts), &mut first);
    assert!(
        first != want,
        "first and last frames should differ (the time bar grows)"
    );
    // save_png of an explicit step, replacing the file
    save_png(&v.trace, 0, &v.opts, &v.path).unwrap();
    assert_eq!(listing(&v.dir), vec!["last.PNG"]);
}

#[test]
fn bad_requests_fail_and_leave_nothing() {
    let dir = Scratch::new("bad");
    let t = moving_square(10, 1.0);
    let opts = RenderOptions::default();

    let err = save_video(&t, &opts, dir.join("movie.avi")).unwrap_err();
    assert!(
        matches!(&err, RenderError::UnsupportedExtension { ext, .. } if ext == "avi"),
        "{err:?}"
    );
    let msg = err.to_string();
    assert!(
        msg.contains("movie.avi") && msg.contains("avi") && msg.contains(".gif"),
        "{msg}"
    );
    let err = save_video(&t, &opts, dir.join("movie")).unwrap_err();
    assert!(
        matches!(&err, RenderError::UnsupportedExtension { ext, .. } if ext.is_empty()),
        "{err:?}"
    );

    let err = save_png(&t, 10, &opts, dir.join("x.png")).unwrap_err();
    assert!(
        matches!(err, RenderError::StepOutOfRange { step: 10, len: 10, .. }),
        "{err:?}"
    );

    let err = save_video(&Trace::default(), &opts, dir.join("e.gif")).unwrap_err();
    assert!(matches!(err, RenderError::InvalidTrace { .. }), "{err:?}");
    let mut centres_only = t.clone();
    centres_only.outlines.clear();
    let err = save_video(&centres_only, &opts, dir.join("c.gif")).unwrap_err();
    assert!(
        err.to_string().contains("c.gif") && err.to_string().contains("polygons"),
        "{err}"
    );

    let zero_fps = RenderOptions {
        fps: 0.0,
        ..opts.clone()
    };
    let zero_width = RenderOptions {
        width: 0,
        ..opts.clone()
    };
    for (bad, field) in [(zero_fps, "fps"), (zero_width, "width")] {
        let err = save_video(&t, &bad, dir.join(format!("{field}.gif"))).unwrap_err();
        assert!(
            matches!(&err, RenderError::InvalidOptions(m) if m.contains(field)),
            "{err:?}"
        );
    }

    let missing = dir.join("no-such-dir").join("v.gif");
    let err = save_video(&t, &opts, &missing).unwrap_err();
    assert!(
        matches!(err, RenderError::Io { .. }) && err.to_string().contains("v.gif"),
        "{err}"
    );

    assert!(listing(&dir).is_empty(), "left behind: {:?}", listing(&dir));
}

#[test]
fn mp4_needs_ffmpeg() {
    let Saved { dir, path, result, .. } = save_moving_square("v.mp4", 60, (161, 91));
    if ffmpeg_available() {
        let info = result.unwrap();
        assert_eq!((info.format, info.frames), (VideoFormat::Mp4, 25));
        let bytes = std::fs::read(&path).unwrap();
        assert_eq!(&bytes[4..8], b"ftyp");
        assert_eq!(listing(&dir), vec!["v.mp4"]);
    } else {
        let err = result.unwrap_err();
        match &err {
            RenderError::EncoderUnavailable(m) => {
                assert!(
                    m.contains("ffmpeg on PATH") && m.contains(".gif") && m.contains("v.mp4"),
                    "{m}"
                )
            }
            other => panic!("expected EncoderUnavailable, got {other:?}"),
        }
        assert!(listing(&dir).is_empty());
    }
}

#[test]
fn options_deserialize_with_defaults() {
    let o: RenderOptions = serde_json::from_str(r#"{"width": 320, "draw_lidar": false}"#).unwrap();
    assert_eq!(
        o,
        RenderOptions {
            width: 320,
            draw_lidar: false,
            ..RenderOptions::default()
        }
    );
    assert_eq!(RenderOptions::default().fps, 25.0);
    assert!(serde_json::from_str::<RenderOptions>(r#"{"widht": 1}"#).is_err());
}

#[test]
fn layers_are_chosen_by_name() {
    let d = RenderOptions::default();
    let none = d.with_layers("none").unwrap();
    assert!(!none.draw_sensors && !none.draw_lidar && !none.draw_overlay && !none.draw_ticks && !none.draw_legend);
    let some = d.with_layers("trail, overlay").unwrap();
    assert!(some.draw_trail && some.draw_overlay && !some.draw_sensors && !some.draw_ticks);
    let all = d.with_layers("all").unwrap();
    assert!(all.draw_trail && all.draw_legend && all.draw_lidar);
    let err = d.with_layers("sensors,glitter").unwrap_err().to_string();
    assert!(err.contains("draw: unknown layer 'glitter'"), "{err}");
}
