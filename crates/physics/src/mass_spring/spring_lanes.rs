//! The springs' work of a substep in population lanes (one lane per episode of one world shape):
//! rest lengths tracking their goals, the spring forces of an RK4 stage, and the two length
//! projections. Each is the scalar computation of `springs.rs` and `projection.rs` lane by lane;
//! where the scalar code skips a spring (zero length, no excess), every lane computes and keeps
//! its old value where the scalar code would have skipped, so each lane has the scalar bits.

use super::lane_shape::LaneShape;
use vsrlab_lanes::{any, not, or, Lanes};

/// The per-episode spring state: rest lengths, goals and the lengths last tracked; and each
/// spring's pull in the current RK4 stage.
#[derive(Debug, Clone)]
pub(crate) struct SpringLanes<L> {
    pub rest: Vec<L>,
    pub goal: Vec<L>,
    pub tracked: Vec<L>,
    pub pull: Vec<Pull<L>>,
}

/// A point's x and y in lanes, side by side (`[point][field][lane]`): a spring's gather of its
/// ends and the sums into their forces touch one cache line per end instead of two.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(crate) struct Xy<L> {
    pub x: L,
    pub y: L,
}

impl<L: Lanes> Xy<L> {
    /// Zero in every lane.
    pub fn zero() -> Self {
        Xy {
            x: L::splat(0.0),
            y: L::splat(0.0),
        }
    }
}

/// A spring's pull on its first end, and its length (zero: no pull).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Pull<L> {
    x: L,
    y: L,
    length: L,
}

impl<L: Lanes> Pull<L> {
    /// No pull yet.
    pub fn zero() -> Self {
        let z = L::splat(0.0);
        Pull { x: z, y: z, length: z }
    }
}

/// The length of (dx, dy) as `quad_geometry::norm` computes it.
#[inline(always)]
fn norm<L: Lanes>(dx: L, dy: L) -> L {
    (dx * dx + dy * dy).sqrt()
}

/// Whether `mask` holds in every lane.
#[inline(always)]
fn all<M: vsrlab_lanes::LaneMask>(mask: M) -> bool {
    !any(not(mask))
}

/// `value` where `keep` holds, else `changed`.
#[inline(always)]
fn unless<L: Lanes>(keep: L::Mask, value: L, changed: L) -> L {
    L::select(keep, value, changed)
}

impl<L: Lanes> SpringLanes<L> {
    /// `Springs::track_goals` in lanes: every active spring's rest length becomes its length plus
    /// `rate` × (goal − length), the length kept in `tracked`.
    #[inline(always)]
    pub fn track_goals(&mut self, shape: &LaneShape, x: &[L], y: &[L], rate: f64) {
        for s in 0..shape.springs.len() {
            let (a, b) = (shape.a[s] as usize, shape.b[s] as usize);
            let len = norm(x[a] - x[b], y[a] - y[b]);
            self.tracked[s] = len;
            self.rest[s] = len + (self.goal[s] - len) * rate;
        }
    }

    /// `Springs::add_forces` (or, with `TRACKED`, `add_forces_at_tracked`) in lanes for the
    /// springs of RK4 stage `stage`: first every spring's pull (independent of one another, so
    /// the divisions and square roots overlap), then the sums at the ends in spring order.
    #[inline(always)]
    pub fn add_forces<const TRACKED: bool>(
        &mut self,
        shape: &LaneShape,
        stage: usize,
        at: &[Xy<L>],
        force: &mut [Xy<L>],
    ) {
        for r in shape.spring_stage[stage].ranges() {
            for s in r {
                let (a, b) = (at[shape.a[s] as usize], at[shape.b[s] as usize]);
                let (dx, dy) = (a.x - b.x, a.y - b.y);
                let len = if TRACKED { self.tracked[s] } else { norm(dx, dy) };
                let k = (len - self.rest[s]) * shape.stiffness[s] / len;
                self.pull[s] = Pull {
                    x: dx * k,
                    y: dy * k,
                    length: len,
                };
            }
        }
        for r in shape.spring_stage[stage].ranges() {
            for s in r {
                let (a, b) = (shape.a[s] as usize, shape.b[s] as usize);
                let Pull { x: px, y: py, length } = self.pull[s];
                let skip = length.eq(L::splat(0.0));
                let fa = force[a];
                if !any(skip) {
                    // the usual case: every lane adds (no choice to make)
                    force[a] = Xy {
                        x: fa.x - px,
                        y: fa.y - py,
                    };
                    let fb = force[b]; // read after `a`'s write, as the scalar code adds them
                    force[b] = Xy {
                        x: fb.x + px,
                        y: fb.y + py,
                    };
                    continue;
                }
                force[a] = Xy {
                    x: unless(skip, fa.x, fa.x - px),
                    y: unless(skip, fa.y, fa.y - py),
                };
                let fb = force[b];
                force[b] = Xy {
                    x: unless(skip, fb.x, fb.x + px),
                    y: unless(skip, fb.y, fb.y + py),
                };
            }
        }
    }
}

/// `projection::excess` in lanes: how far `len` is outside `initial × [1 − band, 1 + band]`.
#[inline(always)]
fn excess<L: Lanes>(len: L, initial: f64, band: f64) -> L {
    let (high, low) = (initial * (1.0 + band), initial * (1.0 - band));
    let below = L::select(len.lt(L::splat(low)), len - low, L::splat(0.0));
    L::select(len.gt(L::splat(high)), len - high, below)
}

/// The push of one projection, `e / (2 len) × correction`, and whether the scalar code skips it.
#[inline(always)]
fn push<L: Lanes>(len: L, e: L, correction: f64) -> (L, L::Mask) {
    let skip = or(e.eq(L::splat(0.0)), len.eq(L::splat(0.0)));
    (e / (len * 2.0) * correction, skip)
}

/// `Projection::project_bands` in lanes: every spring touching a free point pushed back toward its
/// loose band, all at once (shifts summed, then applied to the free points).
#[inline(always)]
pub(crate) fn project_bands<L: Lanes>(
    shape: &LaneShape,
    (shift_x, shift_y): (&mut [L], &mut [L]),
    (x, y): (&mut [L], &mut [L]),
    correction: f64,
) {
    shift_x.fill(L::splat(0.0));
    shift_y.fill(L::splat(0.0));
    for s in shape.touching_free.indices() {
        let (a, b) = (shape.a[s] as usize, shape.b[s] as usize);
        let (dx, dy) = (x[a] - x[b], y[a] - y[b]);
        let len = norm(dx, dy);
        let (k, skip) = push(len, excess(len, shape.initial[s], shape.band[s]), correction);
        if all(skip) {
            continue; // the usual case: within the band in every lane
        }
        let (px, py) = (dx * k, dy * k);
        shift_x[a] = unless(skip, shift_x[a], shift_x[a] - px);
        shift_y[a] = unless(skip, shift_y[a], shift_y[a] - py);
        shift_x[b] = unless(skip, shift_x[b], shift_x[b] + px);
        shift_y[b] = unless(skip, shift_y[b], shift_y[b] + py);
    }
    for r in shape.free.ranges() {
        for i in r {
            x[i] = x[i] + shift_x[i];
            y[i] = y[i] + shift_y[i];
        }
    }
}

/// `Projection::project_limits` in lanes: the tight limits one after another, in their order
/// (those without a free end, which move nothing, left out).
#[inline(always)]
pub(crate) fn project_limits<L: Lanes>(shape: &LaneShape, (x, y): (&mut [L], &mut [L]), correction: f64) {
    for &(s, band) in &shape.limits {
        let s = s as usize;
        let (a, b) = (shape.a[s] as usize, shape.b[s] as usize);
        let (dx, dy) = (x[a] - x[b], y[a] - y[b]);
        let len = norm(dx, dy);
        let (k, skip) = push(len, excess(len, shape.initial[s], band), correction);
        if all(skip) {
            continue;
        }
        let (px, py) = (dx * k, dy * k);
        if !shape.fixed[a] {
            x[a] = unless(skip, x[a], x[a] - px);
            y[a] = unless(skip, y[a], y[a] - py);
        }
        if !shape.fixed[b] {
            x[b] = unless(skip, x[b], x[b] + px);
            y[b] = unless(skip, y[b], y[b] + py);
        }
    }
}
