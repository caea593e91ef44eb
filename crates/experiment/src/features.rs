//! Simple, documented shape and behaviour features of an evaluated robot, for the speciated
//! evolver (SE-s, SE-b) and MAP-Elites (thesis §3.3.2, thesis-code-facts.md §3.4–3.5).
//!
//! These are the runner's own versions, kept small on purpose; an analysis crate may later
//! provide the thesis' full pipeline. What each computes and where it departs from the thesis:
//!
//! | feature | here | thesis / original code |
//! | --- | --- | --- |
//! | [`voxel_count`] (d_num) | voxels of the decoded body | same |
//! | [`elongation`] (d_elong) | eccentricity √(1 − λ₂/λ₁) of the ellipse with the same second central moments as the voxel cells (cells as points, like scikit-image `regionprops`) | same as the TELO notebook; the thesis text describes the minimal enclosing ellipse instead |
//! | [`compactness`] (d_compact) | voxels ÷ grid points (cell coordinates) inside or on the convex hull of the voxel cells; 1 for a degenerate hull (a line or a point) | same as the TELO notebook |
//! | [`dynamic_pose`] (SE-s) | 16×16 "average posture": per step, every voxel's axis-aligned box is mapped onto a 16×16 grid spanning the robot's box enlarged to a square; a cell is on iff it was covered in more than half of the steps | same rule as 2D-VSR-Sim's `Outcome` (a300845); taken over every recorded step, the transient included |
//! | [`center_spectrum`] (SE-b) | magnitude spectrum of \|Δy\| of the robot's centre, zero-padded to a power of two, averaged into 100 bins of 0.1 Hz over (0, 10] Hz | the original computes bin i's frequency as (1/Δt)/2 · i/(N/2 + 1) instead of the exact i/(N Δt): close but not identical |

use vsrlab_body::Morphology;
use vsrlab_physics::Vec2;

/// Side of the dynamic-pose grid.
pub const POSE_SIDE: usize = 16;
/// Number of bins of the centre-of-mass spectrum.
pub const SPECTRUM_BINS: usize = 100;
/// Highest frequency (Hz) covered by the spectrum.
pub const SPECTRUM_MAX_FREQUENCY: f64 = 10.0;

/// d_num: the number of voxels.
pub fn voxel_count(body: &Morphology) -> f64 {
    body.voxel_count() as f64
}

/// d_elong: eccentricity of the ellipse with the same second central moments as the voxel cells,
/// in [0, 1]: 0 for a disc-like (or single-voxel) body, 1 for a straight line of voxels.
pub fn elongation(body: &Morphology) -> f64 {
    let cells: Vec<(f64, f64)> = body.voxels().map(|(x, y)| (x as f64, y as f64)).collect();
    let n = cells.len() as f64;
    let (mx, my) = cells.iter().fold((0.0, 0.0), |(a, b), &(x, y)| (a + x / n, b + y / n));
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for &(x, y) in &cells {
        a += (x - mx) * (x - mx) / n;
        b += (x - mx) * (y - my) / n;
        c += (y - my) * (y - my) / n;
    }
    let half_trace = (a + c) / 2.0;
    let root = (((a - c) / 2.0).powi(2) + b * b).sqrt();
    let (major, minor) = (half_trace + root, (half_trace - root).max(0.0));
    if major <= 0.0 {
        0.0
    } else {
        (1.0 - minor / major).clamp(0.0, 1.0).sqrt()
    }
}

/// d_compact: voxels ÷ grid points inside or on the convex hull of the voxel cells, in (0, 1];
/// 1 when the hull is degenerate (a single voxel or a straight line).
pub fn compactness(body: &Morphology) -> f64 {
    let points: Vec<(i64, i64)> = body.voxels().map(|(x, y)| (x as i64, y as i64)).collect();
    let hull = convex_hull(&points);
    if hull.len() < 3 {
        return 1.0;
    }
    let (x0, x1) = (
        hull.iter().map(|p| p.0).min().unwrap_or(0),
        hull.iter().map(|p| p.0).max().unwrap_or(0),
    );
    let (y0, y1) = (
        hull.iter().map(|p| p.1).min().unwrap_or(0),
        hull.iter().map(|p| p.1).max().unwrap_or(0),
    );
    let mut inside = 0usize;
    for y in y0..=y1 {
        for x in x0..=x1 {
            let on_or_inside = (0..hull.len()).all(|i| {
                let (a, b) = (hull[i], hull[(i + 1) % hull.len()]);
                cross(a, b, (x, y)) >= 0
            });
            inside += usize::from(on_or_inside);
        }
    }
    points.len() as f64 / inside.max(1) as f64
}

/// The three morphology descriptors of the thesis: [d_num, d_elong, d_compact].
pub fn morphology_descriptors(body: &Morphology) -> [f64; 3] {
    [voxel_count(body), elongation(body), compactness(body)]
}

fn cross(o: (i64, i64), a: (i64, i64), b: (i64, i64)) -> i64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

/// Convex hull (Andrew's monotone chain), counter-clockwise, without collinear points.
fn convex_hull(points: &[(i64, i64)]) -> Vec<(i64, i64)> {
    let mut p = points.to_vec();
    p.sort_unstable();
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let mut hull: Vec<(i64, i64)> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &(i64, i64)>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for &q in iter {
            while hull.len() >= start + 2 && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0 {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// The 16×16 average posture from per-step voxel polygons (`polygons_at(k)` of a full trace):
/// 256 values in {0, 1}, index `y·16 + x` with y = 0 the bottom row. Empty input gives zeros.
pub fn dynamic_pose<'a>(steps: impl IntoIterator<Item = &'a [[Vec2; 4]]>) -> Vec<f64> {
    let mut counts = [0u32; POSE_SIDE * POSE_SIDE];
    let mut observations = 0u32;
    let mut boxes: Vec<[f64; 4]> = Vec::new();
    for polygons in steps {
        if polygons.is_empty() {
            continue;
        }
        boxes.clear();
        boxes.extend(polygons.iter().map(|poly| {
            poly.iter().fold(
                [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
                |b, p| [b[0].min(p.x), b[1].min(p.y), b[2].max(p.x), b[3].max(p.y)],
            )
        }));
        let mut robot = boxes.iter().fold(
            [f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY],
            |r, b| [r[0].min(b[0]), r[1].min(b[1]), r[2].max(b[2]), r[3].max(b[3])],
        );
        let (w, h) = (robot[2] - robot[0], robot[3] - robot[1]);
        if !(w.is_finite() && h.is_finite()) || w <= 0.0 && h <= 0.0 {
            continue;
        }
        // Enlarge the shorter side symmetrically to a square.
        if w < h {
            robot[0] -= (h - w) / 2.0;
            robot[2] += (h - w) / 2.0;
        } else {
            robot[1] -= (w - h) / 2.0;
            robot[3] += (w - h) / 2.0;
        }
        let side = (robot[2] - robot[0]).max(robot[3] - robot[1]);
        let last = (POSE_SIDE - 1) as f64;
        let index = |v: f64, min: f64| (((v - min) / side * last).round().clamp(0.0, last)) as usize;
        let mut covered = [false; POSE_SIDE * POSE_SIDE];
        for b in &boxes {
            for y in index(b[1], robot[1])..=index(b[3], robot[1]) {
                for x in index(b[0], robot[0])..=index(b[2], robot[0]) {
                    covered[y * POSE_SIDE + x] = true;
                }
            }
        }
        for (count, &c) in counts.iter_mut().zip(&covered) {
            *count += u32::from(c);
        }
        observations += 1;
    }
    counts
        .iter()
        .map(|&c| {
            if observations > 0 && 2 * c > observations {
                1.0
            } else {
                0.0
            }
        })
        .collect()
}

/// The behaviour vector of SE-b: the spectrum of |Δy| of the robot's centre (see the module
/// docs), [`SPECTRUM_BINS`] values over (0, [`SPECTRUM_MAX_FREQUENCY`]] Hz.
pub fn center_spectrum(centers: &[Vec2], dt: f64) -> Vec<f64> {
    let deltas: Vec<f64> = centers.windows(2).map(|w| (w[1].y - w[0].y).abs()).collect();
    let mut out = vec![0.0; SPECTRUM_BINS];
    if deltas.is_empty() || dt.is_nan() || dt <= 0.0 {
        return out;
    }
    let n = deltas.len().next_power_of_two();
    let mut re = deltas;
    re.resize(n, 0.0);
    let mut im = vec![0.0; n];
    fft(&mut re, &mut im);
    let width = SPECTRUM_MAX_FREQUENCY / SPECTRUM_BINS as f64;
    let mut sums = vec![0.0; SPECTRUM_BINS];
    let mut counts = vec![0usize; SPECTRUM_BINS];
    for i in 0..=n / 2 {
        let f = i as f64 / (n as f64 * dt);
        if f <= 0.0 || f > SPECTRUM_MAX_FREQUENCY {
            continue;
        }
        // bin j covers (j·width, (j+1)·width]
        let j = ((f / width).ceil() as usize).saturating_sub(1).min(SPECTRUM_BINS - 1);
        sums[j] += re[i].hypot(im[i]);
        counts[j] += 1;
    }
    for j in 0..SPECTRUM_BINS {
        if counts[j] > 0 {
            out[j] = sums[j] / counts[j] as f64;
        }
    }
    out
}

/// In-place iterative radix-2 FFT; `re.len()` must be a power of two.
fn fft(re: &mut [f64], im: &mut [f64]) {
    let n = re.len();
    debug_assert!(n.is_power_of_two() && im.len() == n);
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= n {
        let angle = -2.0 * std::f64::consts::PI / len as f64;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let (s, c) = (angle * k as f64).sin_cos();
                let (a, b) = (start + k, start + k + len / 2);
                let (tr, ti) = (re[b] * c - im[b] * s, re[b] * s + im[b] * c);
                re[b] = re[a] - tr;
                im[b] = im[a] - ti;
                re[a] += tr;
                im[a] += ti;
            }
        }
        len <<= 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn body(rows: &str) -> Morphology {
        Morphology::parse(rows).unwrap()
    }

    #[test]
    fn descriptors_of_simple_shapes() {
        let line = body("#####");
        assert_eq!(voxel_count(&line), 5.0);
        assert!((elongation(&line) - 1.0).abs() < 1e-12);
        assert_eq!(compactness(&line), 1.0);
        let square = body("###/###/###");
        assert!(elongation(&square).abs() < 1e-6);
        assert_eq!(compactness(&square), 1.0);
        let single = body("#");
        assert_eq!(elongation(&single), 0.0);
        assert_eq!(compactness(&single), 1.0);
        // An L: hull of (0,0),(2,0),(0,2) holds 6 grid points, 5 voxels.
        let l = body("#../#../###");
        assert!((compactness(&l) - 5.0 / 6.0).abs() < 1e-12);
        // A 4×2 box: eigenvalues 1.25 and 0.25 → e = √(1 − 0.2).
        let bar = body("####/####");
        assert!((elongation(&bar) - 0.8f64.sqrt()).abs() < 1e-12);
        // A biped has a hole under its body: less compact than a box.
        assert!(compactness(&body("biped-4x3")) < 1.0);
    }

    #[test]
    fn fft_matches_a_naive_dft() {
        let x: Vec<f64> = (0..16).map(|i| ((i * 7 % 5) as f64 - 2.0) * 0.3).collect();
        let (mut re, mut im) = (x.clone(), vec![0.0; 16]);
        fft(&mut re, &mut im);
        for k in 0..16 {
            let (mut r, mut i) = (0.0, 0.0);
            for (t, v) in x.iter().enumerate() {
                let a = -2.0 * std::f64::consts::PI * (k * t) as f64 / 16.0;
                r += v * a.cos();
                i += v * a.sin();
            }
            assert!((re[k] - r).abs() < 1e-9 && (im[k] - i).abs() < 1e-9);
        }
    }

    #[test]
    fn spectrum_peaks_at_the_bouncing_frequency() {
        let dt = 1.0 / 60.0;
        // The centre bobs at 2 Hz: |Δy| has its fundamental at 4 Hz (and a DC part).
        let centers: Vec<Vec2> = (0..1800)
            .map(|k| Vec2::new(0.0, (2.0 * std::f64::consts::PI * 2.0 * k as f64 * dt).sin()))
            .collect();
        let s = center_spectrum(&centers, dt);
        assert_eq!(s.len(), SPECTRUM_BINS);
        // Zero padding leaks the large DC part into the lowest bins: look above 1 Hz.
        let peak = (10..SPECTRUM_BINS).max_by(|&a, &b| s[a].total_cmp(&s[b])).unwrap();
        assert!((38..=40).contains(&peak), "peak bin {peak}");
        assert_eq!(center_spectrum(&[], dt), vec![0.0; SPECTRUM_BINS]);
    }

    #[test]
    fn pose_of_a_static_square_robot_fills_the_grid() {
        let l = 3.0;
        let polygons: Vec<[Vec2; 4]> = (0..2)
            .flat_map(|y| (0..2).map(move |x| (x as f64 * l, y as f64 * l)))
            .map(|(x, y)| {
                [
                    Vec2::new(x, y + l),
                    Vec2::new(x + l, y + l),
                    Vec2::new(x + l, y),
                    Vec2::new(x, y),
                ]
            })
            .collect();
        let steps: Vec<&[[Vec2; 4]]> = vec![&polygons; 5];
        let pose = dynamic_pose(steps);
        assert_eq!(pose.len(), 256);
        assert!(pose.iter().all(|&v| v == 1.0));
        // A single-row robot (3 wide, 1 tall) covers only a band in the middle.
        let row: Vec<[Vec2; 4]> = polygons.iter().take(2).copied().collect();
        let pose = dynamic_pose(vec![&row[..]; 3]);
        let on = pose.iter().filter(|&&v| v == 1.0).count();
        assert!(on > 0 && on < 256 && on % 16 == 0, "{on}");
        assert!(dynamic_pose(Vec::<&[[Vec2; 4]]>::new()).iter().all(|&v| v == 0.0));
    }
}
