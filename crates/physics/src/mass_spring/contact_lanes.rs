//! The contacts of up to [`LANES`] worlds of one shape, found together: one broad phase over the
//! union of the worlds' boxes, slot by slot, and each candidate pair's corners tested against the
//! other quad's box in every world at once. Nearly every candidate (neighbouring cells of one
//! body) has no corner inside in any world; the rare corner that is gets the scalar world's exact
//! test ([`corner_contact`]) in its own world.
//!
//! The forces are not added as they are found: the union's pairs come in another order than a
//! world's own sweep. A world's sweep visits its pairs in the order of their earlier slot, then
//! their later slot, slots ordered by (left side of the box, slot index) in that world, and a pair
//! tests its lower slot's corners first, corner by corner. Each contact keeps that key, and each
//! world's contacts are added in key order: the bits of [`super::contact::compute_contact_forces`]
//! in every world.

use super::bodies::Bodies;
use super::broad_phase::{less, BroadPhase};
use super::contact::{corner_contact, ContactForces};
use super::lanes::LANES;
use super::quad_geometry::Aabb;
use super::MassSpringWorld;
use std::cmp::Ordering;

/// The slot boxes and corners of the worlds in lanes, the union's broad phase, and the contacts
/// found in a substep.
#[derive(Debug, Clone)]
pub(crate) struct ContactLanes {
    broad: BroadPhase,
    union: Vec<Aabb>,
    slots: Vec<SlotLanes>,
    /// Slots of all-fixed bodies (terrain), and of the others.
    fixed_slots: Vec<u32>,
    moving_slots: Vec<u32>,
    /// Whose fixed points each lane's fixed slots hold ([`MassSpringWorld::fixed_points`]).
    fixed_loaded: [Option<u64>; LANES],
    /// Counts the changes of the fixed slots' union, for the broad phase's sorting.
    fixed_version: u64,
    /// Per candidate pair `(a, b)`: the corners of `a` in `b`'s box and of `b` in `a`'s, by lane.
    candidates: Vec<[u32; 2]>,
    found: Vec<Found>,
}

/// One slot's box and corners, each coordinate lane by lane (a lane without a stepping world
/// holds what it last held, masked out).
#[derive(Debug, Clone, Copy)]
struct SlotLanes {
    min_x: [f64; LANES],
    min_y: [f64; LANES],
    max_x: [f64; LANES],
    max_y: [f64; LANES],
    x: [[f64; LANES]; 4],
    y: [[f64; LANES]; 4],
}

/// A contact of one world, with its place in that world's own order.
#[derive(Debug, Clone, Copy)]
struct Found {
    lane: usize,
    /// (left side, slot) of the pair's earlier and later slot in the world's sweep order.
    first: (f64, u32),
    second: (f64, u32),
    /// 0 when the corner is the lower slot's, 1 when the higher slot's.
    direction: u8,
    corner: u8,
    forces: ContactForces,
}

impl ContactLanes {
    /// Contact lanes for worlds of `model`'s shape.
    pub fn new(model: &MassSpringWorld) -> Self {
        let bodies = &model.bodies;
        let slots = bodies.boxes.len();
        let (mut fixed_slots, mut moving_slots) = (Vec::new(), Vec::new());
        for b in 0..bodies.len() {
            let list = if bodies.all_fixed[b] {
                &mut fixed_slots
            } else {
                &mut moving_slots
            };
            list.extend(bodies.slots(b).map(|s| s as u32));
        }
        let empty = SlotLanes {
            min_x: [f64::INFINITY; LANES],
            min_y: [f64::INFINITY; LANES],
            max_x: [f64::NEG_INFINITY; LANES],
            max_y: [f64::NEG_INFINITY; LANES],
            x: [[0.0; LANES]; 4],
            y: [[0.0; LANES]; 4],
        };
        ContactLanes {
            broad: BroadPhase::new(&model.bodies),
            union: vec![Aabb::EMPTY; slots],
            slots: vec![empty; slots],
            fixed_slots,
            moving_slots,
            fixed_loaded: [None; LANES],
            fixed_version: 0,
            candidates: Vec::new(),
            found: Vec::new(),
        }
    }

    /// Computes the contact forces of this substep into each stepping world's
    /// `points.contact_fx/fy`, as [`super::contact::compute_contact_forces`] would in each alone;
    /// returns each world's number of contacts.
    pub fn compute(&mut self, worlds: &mut [&mut MassSpringWorld], stepping: &[bool; LANES]) -> [usize; LANES] {
        self.load(worlds, stepping);
        self.broad.update_over(&self.union, Some(self.fixed_version));
        self.found.clear();
        let mut contacts = [0; LANES];
        let Some(first) = (0..worlds.len()).find(|&l| stepping[l]) else {
            return contacts;
        };
        let bodies = &worlds[first].bodies;
        self.find_candidates(bodies, lane_bits(stepping));
        for (&(sa, sb), &inside) in self.broad.pairs().iter().zip(&self.candidates) {
            if inside == [0, 0] {
                continue;
            }
            let weight = if self.broad.same_body(sa, sb) { 2.0 } else { 1.0 };
            let (qa, qb) = (
                bodies.boundary[sa as usize] as usize,
                bodies.boundary[sb as usize] as usize,
            );
            for (direction, inside) in [(0, inside[0]), (1, inside[1])] {
                let (main_quad, other_quad) = if direction == 0 { (qa, qb) } else { (qb, qa) };
                for bit in (0..4 * LANES).filter(|b| inside & (1 << b) != 0) {
                    let (corner, lane) = (bit / LANES, bit % LANES);
                    let w = &worlds[lane];
                    let settings = &w.settings.contact;
                    let Some(forces) =
                        corner_contact(&w.bodies, &w.points, settings, main_quad, other_quad, corner, weight)
                    else {
                        continue;
                    };
                    contacts[lane] += 1;
                    let key = |s: u32| (self.slots[s as usize].min_x[lane], s);
                    let (first, second) = match less(key(sa), key(sb)) {
                        true => (key(sa), key(sb)),
                        false => (key(sb), key(sa)),
                    };
                    self.found.push(Found {
                        lane,
                        first,
                        second,
                        direction,
                        corner: corner as u8,
                        forces,
                    });
                }
            }
        }
        self.found.sort_unstable_by(in_world_order);
        for (l, world) in worlds.iter_mut().enumerate().filter(|&(l, _)| stepping[l]) {
            world.points.contact_fx.fill(0.0);
            world.points.contact_fy.fill(0.0);
            for found in self.found.iter().filter(|f| f.lane == l) {
                found.forces.add_to(&mut world.points);
            }
        }
        contacts
    }

    /// Each candidate pair's corners inside the other quad's box, both ways
    /// ([`corners_inside`]), in AVX2 instructions where the CPU has them.
    fn find_candidates(&mut self, bodies: &Bodies, lanes: u32) {
        self.candidates.clear();
        self.candidates.resize(self.broad.pairs().len(), [0, 0]);
        let (pairs, slots, out) = (self.broad.pairs(), &self.slots, &mut self.candidates);
        #[cfg(target_arch = "x86_64")]
        if is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2
            return unsafe { candidates_avx2(pairs, slots, bodies, lanes, out) };
        }
        candidates::<false>(pairs, slots, bodies, lanes, out);
    }

    /// Gathers every stepping world's slot boxes and corners into lanes, and their union: the
    /// moving slots at every substep, the fixed ones when a lane's world has other fixed points.
    fn load(&mut self, worlds: &[&mut MassSpringWorld], stepping: &[bool; LANES]) {
        let mut fixed_changed = false;
        for (l, world) in worlds.iter().enumerate().filter(|&(l, _)| stepping[l]) {
            if self.fixed_loaded[l] != Some(world.fixed_points) {
                self.fixed_loaded[l] = Some(world.fixed_points);
                fixed_changed = true;
                gather(&mut self.slots, &self.fixed_slots, l, world);
            }
            gather(&mut self.slots, &self.moving_slots, l, world);
        }
        if fixed_changed {
            // the union over every lane loaded so far, stepping or not: a superset does no harm
            self.fixed_version += 1;
            let loaded = self.fixed_loaded.map(|id| id.is_some());
            for &s in &self.fixed_slots {
                self.union[s as usize] = self.slots[s as usize].union_over(&loaded);
            }
        }
        for &s in &self.moving_slots {
            self.union[s as usize] = self.slots[s as usize].union_over(stepping);
        }
    }
}

impl SlotLanes {
    /// The union of the boxes of lanes `which`.
    fn union_over(&self, which: &[bool; LANES]) -> Aabb {
        (0..LANES)
            .filter(|&l| which[l])
            .fold(Aabb::EMPTY, |u, l| u.union(self.lane_box(l)))
    }

    /// The box in lane `l`.
    fn lane_box(&self, l: usize) -> Aabb {
        Aabb {
            min_x: self.min_x[l],
            min_y: self.min_y[l],
            max_x: self.max_x[l],
            max_y: self.max_y[l],
        }
    }
}

/// Copies `world`'s boxes and corners of `which` slots into lane `l`.
fn gather(slots: &mut [SlotLanes], which: &[u32], l: usize, world: &MassSpringWorld) {
    let (bodies, points) = (&world.bodies, &world.points);
    for &s in which {
        let (slot, b) = (&mut slots[s as usize], bodies.boxes[s as usize]);
        (slot.min_x[l], slot.min_y[l], slot.max_x[l], slot.max_y[l]) = (b.min_x, b.min_y, b.max_x, b.max_y);
        let quad = bodies.quad_points[bodies.boundary[s as usize] as usize];
        for (k, &p) in quad.iter().enumerate() {
            slot.x[k][l] = points.x[p as usize];
            slot.y[k][l] = points.y[p as usize];
        }
    }
}

/// Bit `corner * LANES + lane` set for every corner of the stepping lanes.
fn lane_bits(stepping: &[bool; LANES]) -> u32 {
    let lanes = (0..LANES).fold(0u32, |m, l| m | (u32::from(stepping[l]) << l));
    (0..4).fold(0, |m, k| m | (lanes << (k * LANES)))
}

/// Bit `corner * LANES + lane` set, in every lane, for each corner of quad `m` that is also a
/// corner of quad `o` (never inside it).
#[inline(always)]
fn shared(m: [u32; 4], o: [u32; 4]) -> u32 {
    let mut mask = 0;
    for (k, p) in m.iter().enumerate() {
        let shared = (*p == o[0]) | (*p == o[1]) | (*p == o[2]) | (*p == o[3]);
        mask |= (u32::from(shared) * ((1 << LANES) - 1)) << (k * LANES);
    }
    mask
}

/// For each pair `(a, b)`: which corners of `a` lie in `b`'s box and which of `b` in `a`'s, lane
/// by lane ([`corners_inside`], or with `AVX` [`corners_inside_avx`]: the same bits), in the
/// lanes `lanes` ([`lane_bits`]).
#[inline(always)]
fn candidates<const AVX: bool>(
    pairs: &[(u32, u32)],
    slots: &[SlotLanes],
    bodies: &Bodies,
    lanes: u32,
    out: &mut [[u32; 2]],
) {
    for (&(a, b), found) in pairs.iter().zip(out) {
        let (qa, qb) = (
            bodies.boundary[a as usize] as usize,
            bodies.boundary[b as usize] as usize,
        );
        let (pa, pb) = (bodies.quad_points[qa], bodies.quad_points[qb]);
        let (sa, sb) = (&slots[a as usize], &slots[b as usize]);
        let (in_b, in_a) = match AVX {
            // SAFETY: `AVX` is set only by `candidates_avx2`, which runs on CPUs with AVX2
            #[cfg(target_arch = "x86_64")]
            true => unsafe { (corners_inside_avx(sa, sb), corners_inside_avx(sb, sa)) },
            _ => (corners_inside(sa, sb), corners_inside(sb, sa)),
        };
        *found = [in_b & !shared(pa, pb) & lanes, in_a & !shared(pb, pa) & lanes];
    }
}

/// [`candidates`] compiled with AVX2, its corner tests in AVX.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn candidates_avx2(
    pairs: &[(u32, u32)],
    slots: &[SlotLanes],
    bodies: &Bodies,
    lanes: u32,
    out: &mut [[u32; 2]],
) {
    candidates::<true>(pairs, slots, bodies, lanes, out)
}

// One AVX register holds the lanes of a coordinate.
#[cfg(target_arch = "x86_64")]
const _: () = assert!(LANES == 4);

/// [`corners_inside`] in AVX: four lanes per comparison (`<=`, false when either is NaN, as in
/// Rust), the lanes' bits by `movemask`.
///
/// # Safety
/// The CPU must support AVX.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx")]
#[inline]
unsafe fn corners_inside_avx(main: &SlotLanes, other: &SlotLanes) -> u32 {
    use std::arch::x86_64::{_mm256_and_pd, _mm256_cmp_pd, _mm256_loadu_pd, _mm256_movemask_pd, _CMP_LE_OQ};
    // SAFETY: each pointer is to LANES = 4 f64
    let (x0, x1, y0, y1) = unsafe {
        (
            _mm256_loadu_pd(other.min_x.as_ptr()),
            _mm256_loadu_pd(other.max_x.as_ptr()),
            _mm256_loadu_pd(other.min_y.as_ptr()),
            _mm256_loadu_pd(other.max_y.as_ptr()),
        )
    };
    let mut mask = 0;
    for k in 0..4 {
        // SAFETY: as above
        let (x, y) = unsafe { (_mm256_loadu_pd(main.x[k].as_ptr()), _mm256_loadu_pd(main.y[k].as_ptr())) };
        let in_x = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(x0, x), _mm256_cmp_pd::<_CMP_LE_OQ>(x, x1));
        let in_y = _mm256_and_pd(_mm256_cmp_pd::<_CMP_LE_OQ>(y0, y), _mm256_cmp_pd::<_CMP_LE_OQ>(y, y1));
        mask |= (_mm256_movemask_pd(_mm256_and_pd(in_x, in_y)) as u32) << (k * LANES);
    }
    mask
}

/// Bit `corner * LANES + lane` set when that corner of `main` lies in `other`'s closed box in
/// that lane: [`Aabb::contains`] lane by lane.
#[inline(always)]
fn corners_inside(main: &SlotLanes, other: &SlotLanes) -> u32 {
    let mut mask = 0;
    for k in 0..4 {
        let mut corner = 0;
        for l in 0..LANES {
            let (x, y) = (main.x[k][l], main.y[k][l]);
            let inside = (other.min_x[l] <= x) & (x <= other.max_x[l]) & (other.min_y[l] <= y) & (y <= other.max_y[l]);
            corner |= u32::from(inside) << l;
        }
        mask |= corner << (k * LANES);
    }
    mask
}

/// Contacts by world, then in that world's own order (see the module's doc).
fn in_world_order(a: &Found, b: &Found) -> Ordering {
    let slot_order = |x: (f64, u32), y: (f64, u32)| match (less(x, y), less(y, x)) {
        (true, _) => Ordering::Less,
        (_, true) => Ordering::Greater,
        _ => Ordering::Equal,
    };
    a.lane
        .cmp(&b.lane)
        .then(slot_order(a.first, b.first))
        .then(slot_order(a.second, b.second))
        .then(a.direction.cmp(&b.direction))
        .then(a.corner.cmp(&b.corner))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coordinates from a few values (so that corners lie on box sides) with NaN and infinities.
    fn values(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        let pool = [
            0.0,
            -0.0,
            0.1,
            0.2,
            0.3,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.15,
        ];
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            pool[(state >> 33) as usize % pool.len()]
        }
    }

    fn slot(next: &mut impl FnMut() -> f64) -> SlotLanes {
        let mut lanes = || std::array::from_fn(|_| next());
        SlotLanes {
            min_x: lanes(),
            min_y: lanes(),
            max_x: lanes(),
            max_y: lanes(),
            x: std::array::from_fn(|_| lanes()),
            y: std::array::from_fn(|_| lanes()),
        }
    }

    #[test]
    fn corners_inside_is_the_box_test_lane_by_lane_in_both_forms() {
        let mut next = values(7);
        let mut seen = [false; 2];
        for _ in 0..20_000 {
            let (main, other) = (slot(&mut next), slot(&mut next));
            let mask = corners_inside(&main, &other);
            for bit in 0..4 * LANES {
                let (k, l) = (bit / LANES, bit % LANES);
                let box_l = other.lane_box(l);
                let inside = box_l.contains(main.x[k][l], main.y[k][l]);
                assert_eq!(mask & (1 << bit) != 0, inside, "corner {k}, lane {l}");
                seen[usize::from(inside)] = true;
            }
            #[cfg(target_arch = "x86_64")]
            if is_x86_feature_detected!("avx") {
                // SAFETY: the CPU has AVX
                assert_eq!(unsafe { corners_inside_avx(&main, &other) }, mask);
            }
        }
        assert_eq!(seen, [true, true], "both outcomes drawn");
    }

    #[test]
    fn shared_corners_mark_every_lane() {
        let all = (1u32 << LANES) - 1;
        assert_eq!(
            shared([1, 2, 3, 4], [5, 4, 2, 9]),
            (all << LANES) | (all << (3 * LANES))
        );
        assert_eq!(shared([1, 2, 3, 4], [5, 6, 7, 8]), 0);
        assert_eq!(lane_bits(&[true, false, false, true]), 0x9999);
    }
}
