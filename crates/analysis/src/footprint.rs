//! Footprints and the main footprint n-gram (thesis §3.3.3.2 "footprints"; thesis-code-facts
//! §3.6).
//!
//! - **Footprint of a step**: 8 boolean segments over the robot's current x-extent (min..max x of
//!   all voxel corners). For every voxel touching the ground, its corners lying within
//!   [`FootprintParams::contact_tolerance`] (in voxel sides) of its lowest corner, measured as
//!   height above the terrain, mark segments `round((x − min)/(max − min) · 7)` from the leftmost
//!   to the rightmost such corner. (2D-VSR-Sim marked the box of every touching corner *body*; a
//!   trace knows contacts per voxel, so the corners nearest the ground stand in for the bodies.)
//! - **Quantised footprints**: windows [t₀ + kΔ, t₀ + (k+1)Δ), Δ = 0.5 s, from the first
//!   observation; a segment is on iff it was on in more than half of the window's steps. Only
//!   complete windows count (the trace must reach the window's end).
//! - **Main n-gram** M* (thesis text): among the n-grams of quantised footprints, 2 ≤ n ≤ 10,
//!   occurring at least twice without overlapping (counted greedily from the left), the one with
//!   the largest overall duration (occurrences × n); ties go to the shorter n-gram, then to the
//!   one appearing first.
//! - **Five features** of M*: duration n·Δ (s), average touch area (mean fraction of segments on
//!   over its footprints), number of occurrences, mode of the intervals between the starts of
//!   subsequent occurrences (s; ties → the shorter interval), and the rate of intervals equal to
//!   that mode. No n-gram repeats → all five are 0.

use crate::pose::java_round;
use serde::{Deserialize, Serialize};
use vsrlab_physics::Vec2;
use vsrlab_tasks::Trace;

/// Number of segments of a footprint.
pub const SEGMENTS: usize = 8;

/// A footprint: bit i set = segment i (from the left) touches the ground.
pub type Footprint = u8;

/// Footprint settings; the defaults are the thesis'.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FootprintParams {
    /// Δt_footprint (s): the quantisation window.
    pub window: f64,
    /// Shortest n-gram.
    pub min_n: usize,
    /// Longest n-gram (10 = 5 s / 0.5 s).
    pub max_n: usize,
    /// Corners of a touching voxel up to this many voxel sides above its lowest corner count.
    pub contact_tolerance: f64,
    /// A voxel whose lowest corner is within this many voxel sides of the terrain counts as
    /// touching even when its contact flag is off at that step (our engine's flags flicker while
    /// a foot rests on the ground, where dyn4j's persist); 0 uses the flags only.
    #[serde(default)]
    pub resting_clearance: f64,
}

impl Default for FootprintParams {
    fn default() -> Self {
        FootprintParams {
            window: 0.5,
            min_n: 2,
            max_n: 10,
            contact_tolerance: 0.25,
            resting_clearance: 0.05,
        }
    }
}

/// The main footprint n-gram and its features.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct Gait {
    /// The footprints of M* (empty when no n-gram repeats).
    pub ngram: Vec<Footprint>,
    /// Duration of M*: n · Δt_footprint (s).
    pub duration: f64,
    /// Mean fraction of segments touching over the footprints of M*.
    pub touch_area: f64,
    /// Non-overlapping occurrences of M* in the footprint sequence.
    pub occurrences: usize,
    /// Mode of the intervals between the starts of subsequent occurrences (s).
    pub mode_interval: f64,
    /// Fraction of those intervals equal to the mode.
    pub purity: f64,
}

impl Gait {
    /// The five features (duration, touch area, occurrences, mode interval, purity).
    pub fn features(&self) -> [f64; 5] {
        [
            self.duration,
            self.touch_area,
            self.occurrences as f64,
            self.mode_interval,
            self.purity,
        ]
    }

    /// Names of [`Gait::features`].
    pub const FEATURE_NAMES: [&'static str; 5] = [
        "gait_duration",
        "gait_touch_area",
        "gait_occurrences",
        "gait_mode_interval",
        "gait_purity",
    ];

    /// The n-gram as text: one group of 8 characters per footprint, `_` touching, `.` not.
    pub fn ngram_text(&self) -> String {
        self.ngram
            .iter()
            .map(|&f| footprint_text(f))
            .collect::<Vec<_>>()
            .join("|")
    }
}

/// A footprint as 8 characters, `_` touching, `.` not, leftmost segment first.
pub fn footprint_text(f: Footprint) -> String {
    (0..SEGMENTS).map(|i| if f >> i & 1 == 1 { '_' } else { '.' }).collect()
}

/// Height of the terrain polyline at x (linear interpolation, clamped at the ends); None if the
/// terrain is empty.
pub fn terrain_height(terrain: &[Vec2], x: f64) -> Option<f64> {
    let first = terrain.first()?;
    let last = terrain.last()?;
    if x <= first.x {
        return Some(first.y);
    }
    if x >= last.x {
        return Some(last.y);
    }
    let i = terrain.partition_point(|p| p.x <= x);
    let (a, b) = (terrain[i - 1], terrain[i]);
    let span = b.x - a.x;
    Some(if span > 0.0 {
        a.y + (b.y - a.y) * (x - a.x) / span
    } else {
        a.y.max(b.y)
    })
}

/// The footprint of one step.
pub fn footprint_of<P: AsRef<[Vec2]>>(
    polygons: &[P],
    touching: &[bool],
    terrain: &[Vec2],
    side_length: f64,
    tolerance: f64,
) -> Footprint {
    let xs = polygons.iter().flat_map(|p| p.as_ref().iter().map(|v| v.x));
    let (min, max) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
    if max.partial_cmp(&min) != Some(std::cmp::Ordering::Greater) {
        return 0;
    }
    let last = (SEGMENTS - 1) as f64;
    let segment = |x: f64| java_round((x - min) / (max - min) * last).clamp(0, SEGMENTS as i64 - 1) as u32;
    let mut f: Footprint = 0;
    for (poly, &touch) in polygons.iter().zip(touching) {
        if !touch {
            continue;
        }
        let poly = poly.as_ref();
        let clearance: Vec<f64> = poly
            .iter()
            .map(|v| v.y - terrain_height(terrain, v.x).unwrap_or(f64::NEG_INFINITY))
            .collect();
        let lowest = clearance.iter().copied().fold(f64::INFINITY, f64::min);
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for (v, &c) in poly.iter().zip(&clearance) {
            // Without a terrain every clearance is +∞ and every corner counts (the voxel's box).
            if c <= lowest + tolerance * side_length || !c.is_finite() {
                lo = lo.min(v.x);
                hi = hi.max(v.x);
            }
        }
        for s in segment(lo)..=segment(hi) {
            f |= 1 << s;
        }
    }
    f
}

/// Whether the polygon's lowest corner is within `clearance` of the terrain (never for a
/// clearance ≤ 0 or without terrain).
fn resting(poly: &[Vec2], terrain: &[Vec2], clearance: f64) -> bool {
    clearance > 0.0
        && poly
            .iter()
            .any(|v| terrain_height(terrain, v.x).is_some_and(|h| v.y - h <= clearance))
}

/// The footprint of every recorded step of a full trace (a voxel touches when its contact flag
/// is on or it rests within [`FootprintParams::resting_clearance`] of the terrain).
pub fn step_footprints(trace: &Trace, params: &FootprintParams) -> Vec<Footprint> {
    (0..trace.len())
        .map(|k| {
            let polys: Vec<&[Vec2]> = trace.polygons_at(k).iter().collect();
            let flags = trace.at(vsrlab_tasks::channels::TOUCH.name, k).unwrap_or(&[]);
            let touch: Vec<bool> = polys
                .iter()
                .enumerate()
                .map(|(v, poly)| {
                    flags.get(v).is_some_and(|&f| f > 0.5)
                        || resting(poly, &trace.terrain, params.resting_clearance * trace.side_length)
                })
                .collect();
            footprint_of(
                &polys,
                &touch,
                &trace.terrain,
                trace.side_length,
                params.contact_tolerance,
            )
        })
        .collect()
}

/// Quantises per-step footprints observed at `times` into windows of `window` seconds (the
/// element-wise strict-majority mode of each complete window).
pub fn quantise(times: &[f64], footprints: &[Footprint], window: f64) -> Vec<Footprint> {
    let Some(&t0) = times.first() else { return Vec::new() };
    let t_end = *times.last().unwrap();
    let slack = 1e-9 * window.max(1.0);
    let mut out = Vec::new();
    let mut k = 0usize;
    let mut i = 0usize;
    loop {
        let (start, end) = (t0 + k as f64 * window, t0 + (k + 1) as f64 * window);
        if t_end < end - slack {
            break;
        }
        let mut counts = [0usize; SEGMENTS];
        let mut n = 0usize;
        while i < times.len() && times[i] < end - slack {
            if times[i] >= start - slack {
                n += 1;
                for (s, c) in counts.iter_mut().enumerate() {
                    *c += (footprints[i] >> s & 1) as usize;
                }
            }
            i += 1;
        }
        let mut f: Footprint = 0;
        for (s, &c) in counts.iter().enumerate() {
            if 2 * c > n {
                f |= 1 << s;
            }
        }
        out.push(f);
        k += 1;
    }
    out
}

/// Start indices of the non-overlapping occurrences of `pattern` in `seq`, greedily from the left.
fn occurrences(seq: &[Footprint], pattern: &[Footprint]) -> Vec<usize> {
    let mut starts = Vec::new();
    let mut i = 0;
    while i + pattern.len() <= seq.len() {
        if &seq[i..i + pattern.len()] == pattern {
            starts.push(i);
            i += pattern.len();
        } else {
            i += 1;
        }
    }
    starts
}

/// The main footprint n-gram of a quantised footprint sequence and its five features.
pub fn main_gait(seq: &[Footprint], params: &FootprintParams) -> Gait {
    // (overall duration in windows, n, first start, starts)
    let mut best: Option<(usize, usize, usize, Vec<usize>)> = None;
    for n in params.min_n.max(1)..=params.max_n.min(seq.len()) {
        let mut seen: Vec<&[Footprint]> = Vec::new();
        for start in 0..=seq.len() - n {
            let gram = &seq[start..start + n];
            if seen.contains(&gram) {
                continue;
            }
            seen.push(gram);
            let starts = occurrences(seq, gram);
            if starts.len() < 2 {
                continue;
            }
            let overall = starts.len() * n;
            // n and start only grow, so a strict improvement keeps the tie-breaks (shorter, earlier).
            if best.as_ref().is_none_or(|b| overall > b.0) {
                best = Some((overall, n, start, starts));
            }
        }
    }
    let Some((_, n, first, starts)) = best else {
        return Gait::default();
    };
    let ngram = seq[first..first + n].to_vec();
    let intervals: Vec<usize> = starts.windows(2).map(|w| w[1] - w[0]).collect();
    let mut mode = intervals[0];
    let mut mode_count = 0;
    for &v in &intervals {
        let c = intervals.iter().filter(|&&w| w == v).count();
        if c > mode_count || (c == mode_count && v < mode) {
            mode = v;
            mode_count = c;
        }
    }
    let touch_area = ngram
        .iter()
        .map(|f| f.count_ones() as f64 / SEGMENTS as f64)
        .sum::<f64>()
        / n as f64;
    Gait {
        ngram,
        duration: n as f64 * params.window,
        touch_area,
        occurrences: starts.len(),
        mode_interval: mode as f64 * params.window,
        purity: mode_count as f64 / intervals.len() as f64,
    }
}

/// Quantised footprints and the main gait of a full trace.
pub fn gait_of(trace: &Trace, params: &FootprintParams) -> (Vec<Footprint>, Gait) {
    let steps = step_footprints(trace, params);
    let q = quantise(&trace.times, &steps, params.window);
    let g = main_gait(&q, params);
    (q, g)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::square;

    const A: Footprint = 0b0000_0011;
    const B: Footprint = 0b1100_0000;
    const C: Footprint = 0b0011_1100;
    const D: Footprint = 0;

    #[test]
    fn a_periodic_sequence_yields_its_period() {
        let p = FootprintParams::default();
        for period in [
            vec![A, B],
            vec![A, B, C],
            vec![A, D, B, D, C],
            vec![A, A, B, B, C, C, D],
        ] {
            let seq: Vec<Footprint> = period.iter().copied().cycle().take(60).collect();
            let g = main_gait(&seq, &p);
            assert_eq!(g.ngram, period, "{period:?}");
            let n = period.len();
            assert_eq!(g.occurrences, 60 / n);
            assert!((g.duration - n as f64 * 0.5).abs() < 1e-12);
            assert!((g.mode_interval - n as f64 * 0.5).abs() < 1e-12);
            assert_eq!(g.purity, 1.0);
        }
    }

    #[test]
    fn touch_area_and_purity() {
        // A B A B x A B: AB occurs 3 times, intervals 2 and 3 → mode 2 (tie → shorter), purity ½.
        let seq = [A, B, A, B, C, A, B];
        let g = main_gait(&seq, &FootprintParams::default());
        assert_eq!(g.ngram, vec![A, B]);
        assert_eq!(g.occurrences, 3);
        assert!((g.mode_interval - 1.0).abs() < 1e-12);
        assert!((g.purity - 0.5).abs() < 1e-12);
        assert!((g.touch_area - 0.25).abs() < 1e-12); // (2 + 2) / 8 / 2
        assert_eq!(g.ngram_text(), "__......|......__");
    }

    #[test]
    fn no_repetition_no_gait() {
        let g = main_gait(&[A, B, C, D], &FootprintParams::default());
        assert_eq!(g, Gait::default());
        assert_eq!(g.features(), [0.0; 5]);
    }

    #[test]
    fn non_overlapping_counting() {
        // A A A A A: "AA" occurs twice without overlap (0, 2); "AAA" once.
        assert_eq!(occurrences(&[A; 5], &[A, A]), vec![0, 2]);
        let g = main_gait(&[A; 5], &FootprintParams::default());
        assert_eq!(g.ngram, vec![A, A]);
        assert_eq!(g.occurrences, 2);
    }

    #[test]
    fn quantisation_uses_complete_windows_and_strict_majority() {
        // 10 steps per second → 5 steps per 0.5 s window; 1.0 s of trace = 2 windows + 1 step.
        let times: Vec<f64> = (0..=10).map(|k| k as f64 * 0.1).collect();
        let fp = [A, A, A, B, B, /**/ B, B, A, A, D, /**/ C];
        let q = quantise(&times, &fp, 0.5);
        // Window 0: A ×3, B ×2 → bits of A on (3 > 2.5), B's off. Window 1: B ×2, A ×2 → neither.
        assert_eq!(q, vec![A, 0]);
    }

    #[test]
    fn footprint_of_a_biped() {
        // Biped of 4 voxels on top (x 0..12, y 3..6), legs at x 0..3 and 9..12 (y 0..3), side 3,
        // flat ground at y = 0; the legs touch.
        let mut polys: Vec<_> = (0..4).map(|i| square(3.0 * i as f64, 3.0, 3.0)).collect();
        polys.push(square(0.0, 0.0, 3.0));
        polys.push(square(9.0, 0.0, 3.0));
        let touch = [false, false, false, false, true, true];
        let terrain = [Vec2::new(-100.0, 0.0), Vec2::new(100.0, 0.0)];
        let f = footprint_of(&polys, &touch, &terrain, 3.0, 0.25);
        // Left leg: x 0..3 → segments round(0) = 0 to round(3/12·7) = 2; right leg: 9..12 → 5..7.
        assert_eq!(footprint_text(f), "___..___");
        // Lifting the right leg's right corner (a tilted foot) leaves only its left corner.
        polys[5] = [
            Vec2::new(9.0, 3.0),
            Vec2::new(12.0, 4.0),
            Vec2::new(12.0, 1.0),
            Vec2::new(9.0, 0.0),
        ];
        let f = footprint_of(&polys, &touch, &terrain, 3.0, 0.25);
        assert_eq!(footprint_text(f), "___.._..");
    }

    #[test]
    fn terrain_interpolation() {
        let t = [Vec2::new(0.0, 0.0), Vec2::new(10.0, 5.0), Vec2::new(20.0, 5.0)];
        assert_eq!(terrain_height(&t, -3.0), Some(0.0));
        assert_eq!(terrain_height(&t, 4.0), Some(2.0));
        assert_eq!(terrain_height(&t, 15.0), Some(5.0));
        assert_eq!(terrain_height(&[], 1.0), None);
    }
}
