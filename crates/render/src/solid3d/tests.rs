//! Tests of 3D frames: synthetic traces of a few cubes, drawn and read back pixel by pixel.

use super::scene::SolidScene;
use super::shading::{self, FIXED_VOXEL, FLOOR_DARK, FLOOR_LIGHT, SKY};
use super::vec3::Vec3;
use crate::draw::Rgba;
use crate::{render_frame, save_png, save_video, RenderError, RenderOptions, VideoFormat};
use tiny_skia::Pixmap;
use vsrlab_physics::Vec2;
use vsrlab_tasks::{channels, Probe, Trace};

/// The lattice's voxel edge (m).
const SIDE: f64 = 0.01;
/// Half an edge: a voxel resting on the floor has its centre at z = 0.
const H: f64 = SIDE / 2.0;
const RED: u32 = 0xcc3333;
const BLUE: u32 = 0x3355cc;
/// No rotation.
const UPRIGHT: [f64; 4] = [1.0, 0.0, 0.0, 0.0];

/// A voxel at one step: centre and orientation.
type Pose = ([f64; 3], [f64; 4]);

/// A trace of moving voxels with these poses at each step (100 Hz), these fills (none when empty)
/// and these fixed voxels.
fn trace_of(steps: &[Vec<Pose>], fills: &[u32], fixed: &[[f64; 3]]) -> Trace {
    let dt = 0.01;
    let mut trace = Trace {
        dt,
        side_length: SIDE,
        times: (0..steps.len()).map(|k| k as f64 * dt).collect(),
        ..Trace::default()
    };
    for poses in steps {
        let n = poses.len() as f64;
        let (x, y) = poses
            .iter()
            .fold((0.0, 0.0), |(x, y), (p, _)| (x + p[0] / n, y + p[1] / n));
        trace.centers.push(Vec2::new(x, y));
        let xyz: Vec<f64> = poses.iter().flat_map(|(p, _)| *p).collect();
        let quat: Vec<f64> = poses.iter().flat_map(|(_, q)| *q).collect();
        trace.step(&channels::VOXEL_XYZ, &xyz);
        trace.step(&channels::VOXEL_QUAT, &quat);
        trace.step(&channels::VOXEL_EDGE, &vec![SIDE; poses.len()]);
    }
    if !fills.is_empty() {
        let fills: Vec<f64> = fills.iter().map(|&c| f64::from(c)).collect();
        trace.fixed(&channels::UNIT_FILL, 1, &fills);
    }
    if !fixed.is_empty() {
        trace.fixed(&channels::FIXED_VOXELS, 3, &fixed.concat());
    }
    trace
}

/// The fixed voxel of [`pair`]: behind the pair, to the left.
const WALL: [f64; 3] = [-3.0 * SIDE, 3.0 * SIDE, 0.0];

/// Two voxels side by side on the floor (red at the origin, blue at +x) and a fixed one; at the
/// second step the blue one has jumped up by half an edge.
fn pair() -> Trace {
    let step = |lift: f64| vec![([0.0, 0.0, 0.0], UPRIGHT), ([SIDE, 0.0, lift], UPRIGHT)];
    trace_of(&[step(0.0), step(H)], &[RED, BLUE], &[WALL])
}

/// Options without the 2D layers and without text.
fn plain() -> RenderOptions {
    RenderOptions {
        width: 320,
        height: 240,
        draw_overlay: false,
        ..RenderOptions::default()
    }
}

fn rgb(pm: &Pixmap, (x, y): (f32, f32)) -> [u8; 3] {
    let c = pm.pixel(x as u32, y as u32).expect("inside the frame");
    assert_eq!(c.alpha(), 255, "frames are opaque");
    [c.red(), c.green(), c.blue()]
}

/// Pixel of world point `p` in the frame of `step`.
fn project(trace: &Trace, step: usize, p: Vec3) -> (f32, f32) {
    let scene = SolidScene::of(trace, &plain(), true).expect("a 3D trace");
    scene.camera_at(step).project(p).expect("in front of the camera")
}

/// Whether `c` is `expected` give or take one step per channel.
fn is(c: [u8; 3], expected: Rgba) -> bool {
    (0..3).all(|i| c[i].abs_diff(expected[i]) <= 1)
}

/// `0xRRGGBB` as an opaque colour.
fn color(c: u32) -> Rgba {
    [(c >> 16) as u8, (c >> 8) as u8, c as u8, 255]
}

/// The shade of a face of colour `c` with outward normal (x, y, z).
fn shade(c: Rgba, x: f64, y: f64, z: f64) -> Rgba {
    shading::shaded(c, Vec3::new(x, y, z))
}

#[test]
fn a_voxel_shows_its_colour_with_the_top_lighter_than_the_front_and_side() {
    let t = pair();
    let pm = render_frame(&t, 0, &plain());
    let red = color(RED);
    let top = rgb(&pm, project(&t, 0, Vec3::new(0.0, 0.0, H)));
    let front = rgb(&pm, project(&t, 0, Vec3::new(0.0, -H, 0.0)));
    assert!(is(top, shade(red, 0.0, 0.0, 1.0)), "top {top:?}");
    assert!(is(front, shade(red, 0.0, -1.0, 0.0)), "front {front:?}");
    assert_ne!(top, front, "the top and the front are shaded differently");
    // the blue voxel's right side, facing the camera less, is darker still
    let side = rgb(&pm, project(&t, 0, Vec3::new(SIDE + H, 0.0, 0.0)));
    assert!(is(side, shade(color(BLUE), 1.0, 0.0, 0.0)), "side {side:?}");
    // around the voxel's centre, one of its three visible faces
    let (cx, cy) = project(&t, 0, Vec3::default());
    let faces = [(0.0, 0.0, 1.0), (0.0, -1.0, 0.0), (1.0, 0.0, 0.0)].map(|(x, y, z)| shade(red, x, y, z));
    let near_centre = (-4..=4).flat_map(|dx| (-4..=4).map(move |dy| (cx + dx as f32, cy + dy as f32)));
    let seen = near_centre
        .filter(|&p| faces.iter().any(|&f| is(rgb(&pm, p), f)))
        .count();
    assert!(seen > 20, "only {seen} red pixels around the centre");
}

#[test]
fn fixed_voxels_are_grey() {
    let t = pair();
    let pm = render_frame(&t, 0, &plain());
    let top = rgb(&pm, project(&t, 0, Vec3::new(WALL[0], WALL[1], H)));
    assert!(is(top, shade(FIXED_VOXEL, 0.0, 0.0, 1.0)), "{top:?}");
}

#[test]
fn a_nearer_voxel_covers_a_farther_one_in_either_order() {
    // `near` floats between the camera and `far`: on the line of sight through far's centre
    let (az, el) = (
        super::camera::AZIMUTH_DEG.to_radians(),
        super::camera::ELEVATION_DEG.to_radians(),
    );
    let run = 2.0 * SIDE;
    let near = [run * az.cos(), run * az.sin(), run * el.tan()];
    let far = [0.0, 0.0, 0.0];
    let alone = trace_of(&[vec![(far, UPRIGHT)]], &[RED], &[]);
    let at = project(&alone, 0, Vec3::default());
    let c = rgb(&render_frame(&alone, 0, &plain()), at);
    assert!(c[0] > c[2] + 60, "alone, the far voxel is seen: {c:?}");
    for order in [[(far, RED), (near, BLUE)], [(near, BLUE), (far, RED)]] {
        let poses: Vec<Pose> = order.iter().map(|&(p, _)| (p, UPRIGHT)).collect();
        let fills: Vec<u32> = order.iter().map(|&(_, c)| c).collect();
        let t = trace_of(&[poses], &fills, &[]);
        let at = project(&t, 0, Vec3::default());
        let c = rgb(&render_frame(&t, 0, &plain()), at);
        assert!(c[2] > c[0] + 60, "the near (blue) voxel covers the far one: {c:?}");
    }
}

#[test]
fn the_floor_is_below_the_body_and_the_sky_above_the_horizon() {
    let t = pair();
    let opts = plain();
    let pm = render_frame(&t, 0, &opts);
    let between = |c: [u8; 3]| c[0] == c[1] && c[1] == c[2] && (FLOOR_DARK[0]..=FLOOR_LIGHT[0]).contains(&c[0]);
    for x in 0..opts.width {
        let c = rgb(&pm, (x as f32, opts.height as f32 - 1.0));
        assert!(between(c), "the bottom row is floor, not {c:?} at {x}");
    }
    // in front of the red voxel, the middle of a square
    let under = rgb(&pm, project(&t, 0, Vec3::new(0.5 * SIDE, -1.5 * SIDE, -H)));
    assert!(is(under, FLOOR_LIGHT) || is(under, FLOOR_DARK), "{under:?}");
    let sky = rgb(&pm, (opts.width as f32 / 2.0, 6.0));
    assert!(is(sky, SKY), "{sky:?}");
    // both colours of the checkerboard show
    let row = opts.height as f32 - 20.0;
    let colours: Vec<[u8; 3]> = (0..opts.width).map(|x| rgb(&pm, (x as f32, row))).collect();
    assert!(colours.iter().any(|&c| is(c, FLOOR_LIGHT)) && colours.iter().any(|&c| is(c, FLOOR_DARK)));
}

#[test]
fn frames_differ_where_voxels_moved() {
    let t = pair();
    let (a, b) = (render_frame(&t, 0, &plain()), render_frame(&t, 1, &plain()));
    let differ = a.pixels().iter().zip(b.pixels()).filter(|(p, q)| p != q).count();
    assert!(differ > 200, "only {differ} pixels changed");
    // where the blue voxel's top was, it now shows its front
    let before = rgb(&a, project(&t, 0, Vec3::new(SIDE, -H, -H / 2.0)));
    let after = rgb(&b, project(&t, 1, Vec3::new(SIDE, -H, -H / 2.0)));
    assert_ne!(before, after);
    assert_eq!(
        render_frame(&t, 1, &plain()).data(),
        b.data(),
        "drawing is deterministic"
    );
}

/// Pixels where a pure red voxel shows (red well above green).
fn red_mask(pm: &Pixmap) -> Vec<bool> {
    pm.pixels()
        .iter()
        .map(|p| p.red() > p.green().saturating_add(60))
        .collect()
}

#[test]
fn a_turned_voxel_has_another_silhouette() {
    let (s, c) = std::f64::consts::FRAC_PI_8.sin_cos();
    let single = |q: [f64; 4]| trace_of(&[vec![([0.0, 0.0, 0.0], q)]], &[0xff0000], &[]);
    let upright = red_mask(&render_frame(&single(UPRIGHT), 0, &plain()));
    let turned = red_mask(&render_frame(&single([c, 0.0, 0.0, s]), 0, &plain()));
    let area = upright.iter().filter(|&&m| m).count();
    let changed = upright.iter().zip(&turned).filter(|(a, b)| a != b).count();
    assert!(area > 1000, "the voxel covers {area} pixels");
    assert!(changed > area / 20, "only {changed} of {area} pixels changed");
    // a quarter turn about z gives back the same cube
    let quarter = red_mask(&render_frame(
        &single([c * c - s * s, 0.0, 0.0, 2.0 * s * c]),
        0,
        &plain(),
    ));
    let same = upright.iter().zip(&quarter).filter(|(a, b)| a != b).count();
    assert!(same < area / 100, "{same} pixels differ after a quarter turn");
}

#[test]
fn without_fills_voxels_take_the_default_colour_tinted_by_actuation() {
    let mut t = trace_of(&vec![vec![([0.0, 0.0, 0.0], UPRIGHT)]; 2], &[], &[]);
    t.step(&channels::ACTUATION, &[0.0]);
    t.step(&channels::ACTUATION, &[-1.0]);
    let top = project(&t, 0, Vec3::new(0.0, 0.0, H));
    let rest = rgb(&render_frame(&t, 0, &plain()), top);
    assert!(
        is(rest, shade(shading::voxel_color(None, None), 0.0, 0.0, 1.0)),
        "{rest:?}"
    );
    let contracted = rgb(&render_frame(&t, 1, &plain()), top);
    assert!(contracted[0] > rest[0] + 40, "{contracted:?} vs {rest:?}");
}

#[test]
fn the_image_size_is_respected_and_bad_values_do_not_panic() {
    let mut t = pair();
    let opts = RenderOptions {
        width: 200,
        height: 300,
        ..RenderOptions::default()
    };
    let pm = render_frame(&t, 5, &opts);
    assert_eq!((pm.width(), pm.height()), (200, 300));
    for v in t.values_mut(channels::VOXEL_QUAT.name) {
        *v = f64::NAN;
    }
    t.values_mut(channels::VOXEL_XYZ.name)[0] = f64::INFINITY;
    t.values_mut(channels::VOXEL_EDGE.name)[1] = -1.0;
    let _ = render_frame(&t, 0, &opts);
    let _ = render_frame(&t, 1, &opts);
}

/// A fresh empty directory for one test, removed when dropped.
struct Scratch(std::path::PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("vsrlab-render-solid3d-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// `pair` stretched over 0.4 s: 41 steps, the blue voxel rising and falling.
fn hopping_pair() -> Trace {
    let steps: Vec<Vec<Pose>> = (0..=40)
        .map(|k| {
            let lift = H * (k as f64 * 0.3).sin().abs();
            vec![([0.0, 0.0, 0.0], UPRIGHT), ([SIDE, 0.0, lift], UPRIGHT)]
        })
        .collect();
    trace_of(&steps, &[RED, BLUE], &[WALL])
}

#[test]
fn png_and_gif_files_are_written_for_3d_traces() {
    let dir = Scratch::new("files");
    let t = hopping_pair();
    let opts = RenderOptions {
        width: 160,
        height: 120,
        ..RenderOptions::default()
    };
    let png = dir.0.join("frame.png");
    save_png(&t, 3, &opts, &png).unwrap();
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    let gif = dir.0.join("episode.GIF");
    let info = save_video(&t, &opts, &gif).unwrap();
    assert_eq!(info.format, VideoFormat::Gif);
    assert_eq!(info.frames, crate::frame_steps(&t, opts.fps).len());
    assert!(info.frames > 1);
    let bytes = std::fs::read(&gif).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    assert_eq!(info.bytes, bytes.len() as u64);
}

#[test]
fn a_3d_trace_missing_positions_is_refused() {
    let dir = Scratch::new("refused");
    let mut t = pair();
    t.times.push(0.02);
    let err = save_png(&t, 0, &plain(), dir.0.join("x.png")).unwrap_err();
    assert!(matches!(err, RenderError::InvalidTrace { .. }), "{err}");
    assert!(err.to_string().contains("3D"), "{err}");
    let mut empty = Trace {
        times: vec![0.0],
        ..Trace::default()
    };
    empty.step(&channels::VOXEL_XYZ, &[]);
    assert!(save_png(&empty, 0, &plain(), dir.0.join("y.png")).is_err());
}

/// [`pair`] where the red-filled voxel votes "impassable" and touches the wall, and the
/// blue-filled one votes "passable", at every step.
fn voting_pair() -> Trace {
    let mut t = pair();
    for _ in 0..t.len() {
        t.step(&channels::VOTE, &[-0.9, 0.8]);
        t.step(&channels::TOUCH, &[1.0, 0.0]);
    }
    t
}

#[test]
fn votes_colour_the_voxels_and_touching_ones_get_a_yellow_border() {
    let t = voting_pair();
    let pm = render_frame(&t, 0, &plain());
    let top = |v: f64| rgb(&pm, project(&t, 0, Vec3::new(v, 0.0, H)));
    let no = shade(shading::vote_color(-0.9), 0.0, 0.0, 1.0);
    let yes = shade(shading::vote_color(0.8), 0.0, 0.0, 1.0);
    assert!(is(top(0.0), no), "{:?} vs {no:?}", top(0.0));
    assert!(is(top(SIDE), yes), "{:?} vs {yes:?}", top(SIDE));
    let yellow = |pm: &Pixmap| {
        (0..pm.width())
            .flat_map(|x| (0..pm.height()).map(move |y| (x as f32, y as f32)))
            .filter(|&p| is(rgb(pm, p), shading::TOUCH_BORDER))
            .count()
    };
    assert!(yellow(&pm) > 20, "the touching voxel's border: {} pixels", yellow(&pm));
    // without the votes layer, the fills; without the sensors layer, no border
    let plain_fills = render_frame(&t, 0, &plain().with_layers("sensors").unwrap());
    let red_top = rgb(&plain_fills, project(&t, 0, Vec3::new(0.0, 0.0, H)));
    assert!(is(red_top, shade(color(RED), 0.0, 0.0, 1.0)), "{red_top:?}");
    let no_border = render_frame(&t, 0, &plain().with_layers("votes").unwrap());
    assert_eq!(yellow(&no_border), 0);
}
