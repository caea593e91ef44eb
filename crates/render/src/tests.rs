//! Tests of the file outputs.

use crate::palette::Palette;
use crate::testutil::*;
use crate::*;
use std::path::Path;

/// A fresh empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vsrlab-render-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
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
    let dir = scratch("gif");
    let t = moving_square(121, 3.0);
    let opts = RenderOptions {
        width: 160,
        height: 90,
        ..RenderOptions::default()
    };
    let path = dir.join("walk.gif");
    let info = save_video(&t, &opts, &path).unwrap();
    assert_eq!(info.format, VideoFormat::Gif);
    assert_eq!(info.frames, 61);
    assert_eq!((info.width, info.height), (160, 90));
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    assert_eq!(info.bytes, bytes.len() as u64);
    let (frames, screen, delays) = decode_gif(&path);
    assert_eq!(frames, 61);
    assert_eq!(delays.iter().map(|&d| u32::from(d)).sum::<u32>(), 203, "{delays:?}");
    // what the player shows at the end is the last frame (drawn without anti-aliasing), quantized
    let scene = crate::draw::Scene::new(&t, &opts, false);
    let mut last = scene.new_pixmap();
    scene.draw(120, &mut last);
    let mut want = Vec::new();
    Palette::get().quantize(last.data(), &mut want);
    let colors: std::collections::HashSet<&u8> = want.iter().collect();
    assert!(colors.len() >= 5, "too few colours: {colors:?}");
    assert!(!screen.contains(&Palette::get().transparent));
    assert!(screen == want, "composited GIF differs from the last frame");
    assert_eq!(listing(&dir), vec!["walk.gif"], "temporary files left behind");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn png_is_the_last_frame() {
    let dir = scratch("png");
    let t = moving_square(30, 3.0);
    let opts = RenderOptions {
        width: 200,
        height: 120,
        ..RenderOptions::default()
    };
    let path = dir.join("last.PNG");
    let info = save_video(&t, &opts, &path).unwrap();
    assert_eq!((info.format, info.frames), (VideoFormat::Png, 1));
    let dec = png::Decoder::new(std::fs::File::open(&path).unwrap());
    let mut reader = dec.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let frame = reader.next_frame(&mut buf).unwrap();
    assert_eq!(
        (frame.width, frame.height, frame.color_type),
        (200, 120, png::ColorType::Rgb)
    );
    let mut want = Vec::new();
    file::to_rgb(&render_frame(&t, 29, &opts), &mut want);
    assert!(buf[..frame.buffer_size()] == want[..]);
    let mut first = Vec::new();
    file::to_rgb(&render_frame(&t, 0, &opts), &mut first);
    assert!(
        first != want,
        "first and last frames should differ (the time bar grows)"
    );
    // save_png of an explicit step, replacing the file
    save_png(&t, 0, &opts, &path).unwrap();
    assert_eq!(listing(&dir), vec!["last.PNG"]);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_requests_fail_and_leave_nothing() {
    let dir = scratch("bad");
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

    let err = save_video(
        &t,
        &RenderOptions {
            fps: 0.0,
            ..opts.clone()
        },
        dir.join("f.gif"),
    )
    .unwrap_err();
    assert!(
        matches!(&err, RenderError::InvalidOptions(m) if m.contains("fps")),
        "{err:?}"
    );
    let err = save_video(
        &t,
        &RenderOptions {
            width: 0,
            ..opts.clone()
        },
        dir.join("w.gif"),
    )
    .unwrap_err();
    assert!(
        matches!(&err, RenderError::InvalidOptions(m) if m.contains("width")),
        "{err:?}"
    );

    let missing = dir.join("no-such-dir").join("v.gif");
    let err = save_video(&t, &opts, &missing).unwrap_err();
    assert!(
        matches!(err, RenderError::Io { .. }) && err.to_string().contains("v.gif"),
        "{err}"
    );

    assert!(listing(&dir).is_empty(), "left behind: {:?}", listing(&dir));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn mp4_needs_ffmpeg() {
    let dir = scratch("mp4");
    let t = moving_square(60, 3.0);
    let opts = RenderOptions {
        width: 161,
        height: 91,
        ..RenderOptions::default()
    };
    let path = dir.join("v.mp4");
    let result = save_video(&t, &opts, &path);
    if ffmpeg_available() {
        let info = result.unwrap();
        assert_eq!((info.format, info.frames), (VideoFormat::Mp4, 30));
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
    std::fs::remove_dir_all(&dir).unwrap();
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
    assert_eq!(RenderOptions::default().fps, 30.0);
    assert!(serde_json::from_str::<RenderOptions>(r#"{"widht": 1}"#).is_err());
}
