//! A link of N episodes at once (issue 52, population lanes): the same beam between the same two
//! voxels of one body shape in every lane, each lane with its own positions, orientations, rest
//! length and mode. It does exactly what `Link::update` (link.rs) does, lane by lane: where
//! the lanes' branches differ (small- or large-angle mode, the rotation-vector and alignment
//! series, damping before the first update), both ways are computed and each lane keeps its own.
//! A test holds every lane to the scalar link's bits.

use crate::axis::Axis;
use crate::lanes::{Q, V3};
use crate::link::{Link, HYSTERESIS, SMALL_EXTENSION, SMALL_TURN};
use crate::material::LinkConstants;
use vsrlab_lanes::{and, any, not, or, LaneMask, Lanes};

/// One end of the link in every lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EndLanes<L: Lanes> {
    pub pos: V3<L>,
    pub orient: Q<L>,
    pub damping: L,
}

impl<L: Lanes> EndLanes<L> {
    /// Every lane at the origin, unrotated, undamped.
    #[inline(always)]
    pub fn zero() -> Self {
        EndLanes {
            pos: V3::splat(glam::DVec3::ZERO),
            orient: Q::splat(glam::DQuat::IDENTITY),
            damping: L::splat(0.0),
        }
    }

    /// Sets lane `lane` to `end`.
    #[inline(always)]
    pub fn set_lane(&mut self, lane: usize, end: &crate::link::End) {
        self.pos.set_lane(lane, end.pos);
        self.orient.set_lane(lane, end.orient);
        self.damping.set(lane, end.damping);
    }
}

/// A link's constants (shared by the lanes) and each lane's state.
#[derive(Debug, Clone)]
pub(crate) struct LinkLanes<L: Lanes> {
    pub axis: Axis,
    pub k: LinkConstants,
    pub area: f64,
    pub rest: L,
    small_angle: L::Mask,
    velocity_valid: L::Mask,
    d_old: V3<L>,
    theta1_old: V3<L>,
    theta2_old: V3<L>,
    /// Results of the last update, in each voxel's own frame.
    pub force_neg: V3<L>,
    pub force_pos: V3<L>,
    pub moment_neg: V3<L>,
    pub moment_pos: V3<L>,
    pub strain: L,
}

impl<L: Lanes> LinkLanes<L> {
    /// A new link in every lane (small-angle mode, no damping history).
    pub fn new(axis: Axis, k: LinkConstants, area: f64, rest: L) -> Self {
        let zero = V3::splat(glam::DVec3::ZERO);
        LinkLanes {
            axis,
            k,
            area,
            rest,
            small_angle: L::Mask::splat(true),
            velocity_valid: L::Mask::splat(false),
            d_old: zero,
            theta1_old: zero,
            theta2_old: zero,
            force_neg: zero,
            force_pos: zero,
            moment_neg: zero,
            moment_pos: zero,
            strain: L::splat(0.0),
        }
    }

    /// One lane per link of `links` (as many as lanes), which share an axis and constants: their
    /// rest lengths and carried state (mode, damping history), as `update` reads them.
    #[inline(always)]
    pub fn gather(links: &[&Link]) -> Self {
        let first = links[0];
        let mut laned = LinkLanes::new(first.axis, first.k, first.area, L::splat(0.0));
        for (lane, l) in links.iter().enumerate() {
            laned.rest.set(lane, l.rest);
            laned.small_angle.set(lane, l.small_angle);
            laned.velocity_valid.set(lane, l.velocity_valid);
            laned.d_old.set_lane(lane, l.d_old);
            laned.theta1_old.set_lane(lane, l.theta1_old);
            laned.theta2_old.set_lane(lane, l.theta2_old);
        }
        laned
    }

    /// Sets lane `lane`'s rest length, carried state and results to `from`'s lane `lane` (a lane
    /// restarted from the world's first state).
    pub fn copy_lane(&mut self, lane: usize, from: &Self) {
        self.rest.set(lane, from.rest.get(lane));
        self.small_angle.set(lane, from.small_angle.get(lane));
        self.velocity_valid.set(lane, from.velocity_valid.get(lane));
        for (to, from) in [
            (&mut self.d_old, &from.d_old),
            (&mut self.theta1_old, &from.theta1_old),
            (&mut self.theta2_old, &from.theta2_old),
            (&mut self.force_neg, &from.force_neg),
            (&mut self.force_pos, &from.force_pos),
            (&mut self.moment_neg, &from.moment_neg),
            (&mut self.moment_pos, &from.moment_pos),
        ] {
            to.set_lane(lane, from.lane(lane));
        }
        self.strain.set(lane, from.strain.get(lane));
    }

    /// Writes lane `lane`'s results and carried state back to its link.
    #[inline(always)]
    pub fn scatter(&self, lane: usize, link: &mut Link) {
        link.force_neg = self.force_neg.lane(lane);
        link.force_pos = self.force_pos.lane(lane);
        link.moment_neg = self.moment_neg.lane(lane);
        link.moment_pos = self.moment_pos.lane(lane);
        link.strain = self.strain.get(lane);
        link.small_angle = self.small_angle.get(lane);
        link.velocity_valid = self.velocity_valid.get(lane);
        link.d_old = self.d_old.lane(lane);
        link.theta1_old = self.theta1_old.lane(lane);
        link.theta2_old = self.theta2_old.lane(lane);
    }

    /// The relative configuration, as `Link::orient`, lane by lane.
    #[inline(always)]
    fn orient(&mut self, a: &EndLanes<L>, b: &EndLanes<L>) -> (V3<L>, Q<L>, Q<L>) {
        let d = to_x(self.axis, b.pos.sub(a.pos));
        let q1 = quat_to_x(self.axis, a.orient);
        let q2 = quat_to_x(self.axis, b.orient);
        let rot = q1.conjugate();
        let d = rotate(rot, d);
        let q2 = rot.mul(q2);
        let turn = (d.z.abs() + d.y.abs()) / d.x;
        let extension = (L::splat(1.0) - d.x / self.rest).abs();
        let small = self.small_angle;
        let enter = and(
            not(small),
            and(turn.lt(L::splat(SMALL_TURN)), extension.lt(L::splat(SMALL_EXTENSION))),
        );
        let leave = and(
            small,
            or(
                turn.gt(L::splat(SMALL_TURN * HYSTERESIS)),
                extension.gt(L::splat(SMALL_EXTENSION * HYSTERESIS)),
            ),
        );
        let changed = or(enter, leave);
        // enter and leave exclude each other (one needs the large mode, the other the small)
        self.small_angle = or(enter, and(small, not(leave)));
        self.velocity_valid = and(self.velocity_valid, not(changed));
        let small = self.small_angle;
        // small-angle lanes
        let small_d = V3 {
            x: d.x - self.rest,
            ..d
        };
        let identity = Q::splat(glam::DQuat::IDENTITY);
        if !any(not(small)) {
            return (small_d, identity, q2);
        }
        // large-angle lanes
        let align = align_to_x(d);
        let large_q2 = align.mul(q2);
        let large_d = V3 {
            x: d.length() - self.rest,
            y: L::splat(0.0),
            z: L::splat(0.0),
        };
        (
            V3::select(small, small_d, large_d),
            Q::select(small, identity, align),
            Q::select(small, q2, large_q2),
        )
    }

    /// Computes the forces and moments on both ends in every lane, as `Link::update`.
    #[inline(always)]
    pub fn update(&mut self, a: &EndLanes<L>, b: &EndLanes<L>) {
        let (d, q1, q2) = self.orient(a, b);
        let small = self.small_angle;
        let zero = V3::splat(glam::DVec3::ZERO);
        let large = any(not(small));
        let theta1 = match large {
            true => V3::select(small, zero, to_rotation_vector(q1)),
            false => zero,
        };
        let theta2 = to_rotation_vector(q2);
        // the constants in every lane, so that each term reads as in `Link::update`
        let k = self.k;
        let [e, a2, b1, b2, b3] = [k.e, k.a2, k.b1, k.b2, k.b3].map(L::splat);
        let [sqrt_a1, sqrt_a2, sqrt_b1, sqrt_b2, sqrt_b3] =
            [k.sqrt_a1, k.sqrt_a2, k.sqrt_b1, k.sqrt_b2, k.sqrt_b3].map(L::splat);
        let (half, two) = (L::splat(0.5), L::splat(2.0));
        self.strain = d.x / self.rest;
        let axial = e * self.strain * self.area;
        let fn_ = V3 {
            x: axial,
            y: b1 * d.y - b2 * (theta1.z + theta2.z),
            z: b1 * d.z + b2 * (theta1.y + theta2.y),
        };
        let fp = V3 {
            x: -fn_.x,
            y: -fn_.y,
            z: -fn_.z,
        };
        let mn = V3 {
            x: a2 * (theta2.x - theta1.x),
            y: -b2 * d.z - b3 * (two * theta1.y + theta2.y),
            z: b2 * d.y - b3 * (two * theta1.z + theta2.z),
        };
        let mp = V3 {
            x: a2 * (theta1.x - theta2.x),
            y: -b2 * d.z - b3 * (theta1.y + two * theta2.y),
            z: b2 * d.y - b3 * (theta1.z + two * theta2.z),
        };
        // damping, in the lanes whose last update was in the same mode
        let dd = d.sub(self.d_old).scale(L::splat(0.5));
        let t1 = theta1.sub(self.theta1_old).scale(L::splat(0.5));
        let t2 = theta2.sub(self.theta2_old).scale(L::splat(0.5));
        let c = V3 {
            x: sqrt_a1 * dd.x,
            y: sqrt_b1 * dd.y - sqrt_b2 * (t1.z + t2.z),
            z: sqrt_b1 * dd.z + sqrt_b2 * (t1.y + t2.y),
        };
        let twist = sqrt_a2 * (t2.x - t1.x);
        let damped_mn = mn.sub(
            V3 {
                x: -twist,
                y: sqrt_b2 * dd.z + sqrt_b3 * (two * t1.y + t2.y),
                z: -sqrt_b2 * dd.y + sqrt_b3 * (two * t1.z + t2.z),
            }
            .scale(half * a.damping),
        );
        let damped_mp = mp.sub(
            V3 {
                x: twist,
                y: sqrt_b2 * dd.z + sqrt_b3 * (t1.y + two * t2.y),
                z: -sqrt_b2 * dd.y + sqrt_b3 * (t1.z + two * t2.z),
            }
            .scale(half * b.damping),
        );
        let valid = self.velocity_valid;
        let fn_ = V3::select(valid, fn_.add(c.scale(a.damping)), fn_);
        let fp = V3::select(valid, fp.sub(c.scale(b.damping)), fp);
        let mn = V3::select(valid, damped_mn, mn);
        let mp = V3::select(valid, damped_mp, mp);
        self.velocity_valid = L::Mask::splat(true);
        (self.d_old, self.theta1_old, self.theta2_old) = (d, theta1, theta2);
        let (fn_, mn) = match large {
            true => (
                V3::select(small, fn_, rotate_inverse(q1, fn_)),
                V3::select(small, mn, rotate_inverse(q1, mn)),
            ),
            false => (fn_, mn),
        };
        let fp = rotate_inverse(q2, fp);
        let mp = rotate_inverse(q2, mp);
        self.force_neg = back_from_x(self.axis, fn_);
        self.force_pos = back_from_x(self.axis, fp);
        self.moment_neg = back_from_x(self.axis, mn);
        self.moment_pos = back_from_x(self.axis, mp);
    }
}

/// `Axis::to_x` in every lane.
#[inline(always)]
fn to_x<L: Lanes>(axis: Axis, v: V3<L>) -> V3<L> {
    match axis {
        Axis::X => v,
        Axis::Y => V3 {
            x: v.y,
            y: -v.x,
            z: v.z,
        },
        Axis::Z => V3 {
            x: v.z,
            y: v.y,
            z: -v.x,
        },
    }
}

/// `Axis::back_from_x` in every lane.
#[inline(always)]
fn back_from_x<L: Lanes>(axis: Axis, v: V3<L>) -> V3<L> {
    match axis {
        Axis::X => v,
        Axis::Y => V3 {
            x: -v.y,
            y: v.x,
            z: v.z,
        },
        Axis::Z => V3 {
            x: -v.z,
            y: v.y,
            z: v.x,
        },
    }
}

/// `Axis::quat_to_x` in every lane.
#[inline(always)]
fn quat_to_x<L: Lanes>(axis: Axis, q: Q<L>) -> Q<L> {
    let v = to_x(axis, V3 { x: q.x, y: q.y, z: q.z });
    Q {
        x: v.x,
        y: v.y,
        z: v.z,
        w: q.w,
    }
}

/// `quat::rotate` in every lane.
#[inline(always)]
fn rotate<L: Lanes>(q: Q<L>, v: V3<L>) -> V3<L> {
    sandwich(q, v, q.conjugate())
}

/// `quat::rotate_inverse` in every lane.
#[inline(always)]
fn rotate_inverse<L: Lanes>(q: Q<L>, v: V3<L>) -> V3<L> {
    sandwich(q.conjugate(), v, q)
}

/// `quat::sandwich` in every lane: the same terms in the same order.
#[inline(always)]
pub(crate) fn sandwich<L: Lanes>(a: Q<L>, v: V3<L>, b: Q<L>) -> V3<L> {
    let tx = a.w * v.x + a.y * v.z - a.z * v.y;
    let ty = a.w * v.y - a.x * v.z + a.z * v.x;
    let tz = a.w * v.z + a.x * v.y - a.y * v.x;
    let tw = -(a.x * v.x) - a.y * v.y - a.z * v.z;
    V3 {
        x: tw * b.x + tx * b.w + ty * b.z - tz * b.y,
        y: tw * b.y - tx * b.z + ty * b.w + tz * b.x,
        z: tw * b.z + tx * b.y - ty * b.x + tz * b.w,
    }
}

/// `quat::to_rotation_vector` in every lane: both series computed, each lane takes its own.
#[inline(always)]
pub(crate) fn to_rotation_vector<L: Lanes>(q: Q<L>) -> V3<L> {
    let identity = or(q.w.ge(L::splat(1.0)), q.w.le(L::splat(-1.0)));
    let (one, two) = (L::splat(1.0), L::splat(2.0));
    let s = one - q.w * q.w;
    let series = s.lt(L::splat(2.4e-3));
    let near = two * ((two - two * q.w) / s).sqrt();
    let scale = match any(and(not(series), not(identity))) {
        true => L::select(series, near, two * q.w.acos() / s.sqrt()),
        false => near,
    };
    let v = V3 {
        x: q.x * scale,
        y: q.y * scale,
        z: q.z * scale,
    };
    V3::select(identity, V3::splat(glam::DVec3::ZERO), v)
}

/// `quat::align_to_x(d, IDENTITY)` in every lane: the zero vector, the first-order branch, the
/// half-turn and the general rotation, each lane taking its own.
#[inline(always)]
fn align_to_x<L: Lanes>(d: V3<L>) -> Q<L> {
    let zero = L::splat(0.0);
    let is_zero = and(d.x.eq(zero), and(d.y.eq(zero), d.z.eq(zero)));
    let (ry, rz) = (d.y / d.x, d.z / d.x);
    let limit = L::splat(1.732e-2);
    let nearly = and(and(ry.abs().lt(limit), rz.abs().lt(limit)), d.x.ne(zero));
    let half = L::splat(0.5);
    let (y, z) = (half * rz, -half * ry);
    let first_order = Q {
        x: zero,
        y,
        z,
        w: L::splat(1.0) - half * (y * y + z * z),
    };
    if !any(and(not(nearly), not(is_zero))) {
        return Q::select(is_zero, Q::splat(glam::DQuat::IDENTITY), first_order);
    }
    let length = d.length();
    let n = V3 {
        x: d.x / length,
        y: d.y / length,
        z: d.z / length,
    };
    let theta = n.x.clamp(-1.0, 1.0).acos();
    let half_turn = theta.gt(L::splat(std::f64::consts::PI - 1e-7));
    let half = theta / 2.0;
    let (sin, cos) = half.sin_cos();
    let s = sin / (n.y * n.y + n.z * n.z).sqrt();
    let general = Q {
        x: zero,
        y: n.z * s,
        z: -n.y * s,
        w: cos,
    };
    let flipped = Q::splat(glam::DQuat::from_xyzw(0.0, 0.0, 1.0, 0.0));
    let turned = Q::select(half_turn, flipped, general);
    let aligned = Q::select(nearly, first_order, turned);
    Q::select(is_zero, Q::splat(glam::DQuat::IDENTITY), aligned)
}

#[cfg(feature = "bench")]
pub use bench::benchmark;

/// The timings of `--example lanes3d` (feature `bench`: the 8-lane and AVX-512 forms are
/// compiled only for it).
#[cfg(feature = "bench")]
mod bench {
    use super::*;

    /// Times link updates of one scalar link per episode against laned links of 4 and 8 episodes
    /// (`--example lanes3d`): nanoseconds per link update and episode for each, on `updates`
    /// updates of random bends (both modes met), with every lane checked against the scalar bits.
    /// Returns `(scalar, four lanes, eight lanes)`.
    pub fn benchmark(updates: usize) -> (f64, f64, f64) {
        let scalar = time_scalar(updates);
        #[cfg(target_arch = "x86_64")]
        if vsrlab_lanes::avx::available() {
            let four = time_lanes::<vsrlab_lanes::avx::Avx<4>>(updates);
            let eight = time_lanes::<vsrlab_lanes::avx::Avx<8>>(updates);
            return (scalar, four, eight);
        }
        let four = time_lanes::<vsrlab_lanes::F64s<4>>(updates);
        let eight = time_lanes::<vsrlab_lanes::F64s<8>>(updates);
        (scalar, four, eight)
    }

    /// The ends of update `i` in lane `l`: a deterministic spread of bends and stretches.
    fn bench_end(i: usize, l: usize, positive: bool) -> crate::link::End {
        let phase = (i * 7 + l * 13) as f64;
        let bend = [0.002, 0.02, 0.3][(i / 64) % 3] * (1.0 + 0.1 * l as f64);
        let wobble = glam::DVec3::new((phase * 0.37).sin(), (phase * 0.71).cos(), (phase * 0.13).sin()) * bend;
        let at = if positive {
            glam::DVec3::new(0.01, 0.0, 0.0)
        } else {
            glam::DVec3::ZERO
        };
        crate::link::End {
            pos: at + wobble * 0.01,
            orient: crate::quat::from_rotation_vector(wobble),
            damping: 1.0,
        }
    }

    fn time_scalar(updates: usize) -> f64 {
        let k = LinkConstants::new(1e6, 1e6, 0.01);
        let ends: Vec<_> = (0..updates)
            .map(|i| (bench_end(i, 0, false), bench_end(i, 0, true)))
            .collect();
        let mut link = crate::link::Link::new(0, 1, Axis::X, k, 1e-4, 0.01);
        let start = std::time::Instant::now();
        for (a, b) in &ends {
            link.update(a, b);
            std::hint::black_box(&link.force_pos);
        }
        start.elapsed().as_secs_f64() * 1e9 / updates as f64
    }

    fn time_lanes<L: Lanes>(updates: usize) -> f64 {
        let k = LinkConstants::new(1e6, 1e6, 0.01);
        let lanes_of = |i: usize, positive: bool| {
            let mut e = EndLanes {
                pos: V3::splat(glam::DVec3::ZERO),
                orient: Q::splat(glam::DQuat::IDENTITY),
                damping: L::splat(0.0),
            };
            for l in 0..L::LANES {
                let end = bench_end(i, l, positive);
                e.pos.set_lane(l, end.pos);
                e.orient.set_lane(l, end.orient);
                e.damping.set(l, end.damping);
            }
            e
        };
        let ends: Vec<_> = (0..updates).map(|i| (lanes_of(i, false), lanes_of(i, true))).collect();
        let mut link = LinkLanes::<L>::new(Axis::X, k, 1e-4, L::splat(0.01));
        let start = std::time::Instant::now();
        update_all(&mut link, &ends);
        start.elapsed().as_secs_f64() * 1e9 / (updates * L::LANES) as f64
    }

    /// The laned updates, compiled for the best vector unit this CPU has (the same bits on each).
    fn update_all<L: Lanes>(link: &mut LinkLanes<L>, ends: &[(EndLanes<L>, EndLanes<L>)]) {
        #[cfg(target_arch = "x86_64")]
        {
            if is_x86_feature_detected!("avx512f") {
                // SAFETY: the CPU supports AVX-512F.
                return unsafe { update_all_avx512(link, ends) };
            }
            if is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2.
                return unsafe { update_all_avx2(link, ends) };
            }
        }
        update_all_portable(link, ends);
    }

    #[inline(always)]
    fn update_all_portable<L: Lanes>(link: &mut LinkLanes<L>, ends: &[(EndLanes<L>, EndLanes<L>)]) {
        for (a, b) in ends {
            link.update(a, b);
            std::hint::black_box(&link.force_pos);
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn update_all_avx2<L: Lanes>(link: &mut LinkLanes<L>, ends: &[(EndLanes<L>, EndLanes<L>)]) {
        update_all_portable(link, ends);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn update_all_avx512<L: Lanes>(link: &mut LinkLanes<L>, ends: &[(EndLanes<L>, EndLanes<L>)]) {
        update_all_portable(link, ends);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::{End, Link};
    use crate::quat::from_rotation_vector;
    use glam::{DQuat, DVec3};
    use vsrlab_lanes::F64s;

    const LANES: usize = 8;

    /// Random ends for every lane: small and large bends, stretches and twists, so that lanes
    /// enter and leave the small-angle mode at different updates.
    fn ends(next: &mut impl FnMut() -> f64, round: usize) -> ([End; LANES], [End; LANES]) {
        let s = 0.01;
        let bend = [0.002, 0.02, 0.3, 1.5][round % 4];
        let end = |next: &mut dyn FnMut() -> f64, at: DVec3| End {
            pos: at + DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * s * bend,
            orient: from_rotation_vector(DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5) * bend),
            damping: if round == 0 { 0.0 } else { next() * 3.0 },
        };
        let a = std::array::from_fn(|_| end(next, DVec3::ZERO));
        let b = std::array::from_fn(|_| end(next, DVec3::new(s, 0.0, 0.0)));
        (a, b)
    }

    fn lanes_of<L: Lanes>(ends: &[End; LANES], axis: Axis) -> EndLanes<L> {
        // the same configuration turned onto the link's axis
        let turn = |v: DVec3| match axis {
            Axis::X => v,
            Axis::Y => DVec3::new(-v.y, v.x, v.z),
            Axis::Z => DVec3::new(-v.z, v.y, v.x),
        };
        let mut out = EndLanes {
            pos: V3::splat(DVec3::ZERO),
            orient: Q::splat(DQuat::IDENTITY),
            damping: L::splat(0.0),
        };
        for (l, e) in ends.iter().enumerate() {
            out.pos.set_lane(l, turn(e.pos));
            out.orient.set_lane(l, e.orient);
            out.damping.set(l, e.damping);
        }
        out
    }

    fn same_bits<L: Lanes>(laned: &V3<L>, l: usize, scalar: DVec3, what: &str) {
        let lane = laned.lane(l);
        for k in 0..3 {
            assert_eq!(
                lane[k].to_bits(),
                scalar[k].to_bits(),
                "{what}, lane {l}: {lane} vs {scalar}"
            );
        }
    }

    #[test]
    fn every_lane_of_a_laned_link_gives_the_scalar_links_bits() {
        every_lane_gives_the_scalar_bits::<F64s<LANES>>();
        #[cfg(target_arch = "x86_64")]
        if vsrlab_lanes::avx::available() {
            every_lane_gives_the_scalar_bits::<vsrlab_lanes::avx::Avx<LANES>>();
        }
    }

    fn every_lane_gives_the_scalar_bits<L: Lanes>() {
        let mut next = crate::validation::uniform(0x2545_f491_4f6c_dd1d_u64);
        let k = LinkConstants::new(1e6, 3e6, 0.01);
        for axis in [Axis::X, Axis::Y, Axis::Z] {
            let rests: [f64; LANES] = std::array::from_fn(|l| 0.01 * (1.0 + 0.02 * l as f64));
            let mut scalar: Vec<Link> = rests.iter().map(|&r| Link::new(0, 1, axis, k, 1e-4, r)).collect();
            let mut rest = L::splat(0.0);
            for (l, &r) in rests.iter().enumerate() {
                rest.set(l, r);
            }
            let mut laned = LinkLanes::<L>::new(axis, k, 1e-4, rest);
            let mut large = 0;
            for round in 0..40 {
                let (a, b) = ends(&mut next, round);
                let (la, lb) = (lanes_of::<L>(&a, axis), lanes_of::<L>(&b, axis));
                laned.update(&la, &lb);
                for l in 0..LANES {
                    let (sa, sb) = (
                        End {
                            pos: la.pos.lane(l),
                            ..a[l]
                        },
                        End {
                            pos: lb.pos.lane(l),
                            ..b[l]
                        },
                    );
                    scalar[l].update(&sa, &sb);
                    large += usize::from(!laned.small_angle.get(l));
                    same_bits(&laned.force_neg, l, scalar[l].force_neg, "force on the negative end");
                    same_bits(&laned.force_pos, l, scalar[l].force_pos, "force on the positive end");
                    same_bits(&laned.moment_neg, l, scalar[l].moment_neg, "moment on the negative end");
                    same_bits(&laned.moment_pos, l, scalar[l].moment_pos, "moment on the positive end");
                    assert_eq!(laned.strain.get(l).to_bits(), scalar[l].strain.to_bits());
                }
            }
            // both modes were met, in different lanes at different updates
            assert!(large > 20 && large < 40 * LANES - 20, "{large}");
        }
    }
}
