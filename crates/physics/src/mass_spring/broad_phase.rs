//! Broad phase: which pairs of boundary quads may touch, by sweep and prune along x.
//!
//! The boundary quads (slots) are ordered by the left side of their boxes, ties broken by slot
//! index, and swept once per substep: each slot is paired with the slots after it whose left
//! side is not beyond its right side. The order is unique for given boxes, so the pairs, and the
//! order in which contact forces are summed, depend only on the state: stepping stays
//! deterministic.
//!
//! The slots of all-fixed bodies (terrain) keep their boxes, so they are sorted once and kept
//! apart from the moving slots, which are repaired by insertion sort each substep (nearly sorted
//! after a small step). The sweep walks the two lists merged, which is the order of all slots,
//! and skips what cannot give a pair (two fixed slots): the same pairs in the same order as a
//! sweep over every slot, at the cost of the moving slots.

use super::bodies::Bodies;
use super::quad_geometry::Aabb;

/// The sorted slots and the candidate pairs of the current substep, kept between substeps.
#[derive(Debug, Clone)]
pub(crate) struct BroadPhase {
    /// Slots of all-fixed bodies, ordered by (left side of the box, slot index).
    fixed_order: Vec<u32>,
    /// The boxes version (`Bodies::fixed_boxes_version`) `fixed_order` was sorted for.
    sorted_for: Option<u64>,
    /// Slots of the other bodies, ordered by (left side of the box, slot index).
    moving_order: Vec<u32>,
    /// The body of each slot.
    slot_body: Vec<u32>,
    /// Candidate pairs `(lower slot, higher slot)` in sweep order.
    pairs: Vec<(u32, u32)>,
}

impl BroadPhase {
    /// A broad phase over the slots of `bodies`.
    pub fn new(bodies: &Bodies) -> Self {
        let mut slot_body = Vec::new();
        for b in 0..bodies.len() {
            slot_body.extend(bodies.slots(b).map(|_| b as u32));
        }
        let fixed = |s: &u32| bodies.all_fixed[slot_body[*s as usize] as usize];
        let (fixed_order, moving_order) = (0..slot_body.len() as u32).partition(fixed);
        Self {
            fixed_order,
            sorted_for: None,
            moving_order,
            slot_body,
            pairs: Vec::new(),
        }
    }

    /// Finds every pair of slots whose boxes overlap (closed test), leaving out pairs whose bodies
    /// are both all fixed, in sweep order. Allocates nothing once the pair list has grown to its
    /// largest size.
    pub fn update(&mut self, bodies: &Bodies) {
        self.update_over(&bodies.boxes, Some(bodies.fixed_boxes_version));
    }

    /// [`BroadPhase::update`] over the slot boxes `boxes` (of one world, or the union of several
    /// worlds' boxes slot by slot); `fixed_version` is the world's `fixed_boxes_version`, `None`
    /// when the fixed slots must be sorted again (boxes of several worlds).
    pub fn update_over(&mut self, boxes: &[Aabb], fixed_version: Option<u64>) {
        self.sort(boxes, fixed_version);
        self.pairs.clear();
        let key = |s: u32| (boxes[s as usize].min_x, s);
        let (fixed, moving) = (&self.fixed_order, &self.moving_order);
        let (mut i, mut j) = (0, 0);
        while i < fixed.len() || j < moving.len() {
            let fixed_first = j == moving.len() || (i < fixed.len() && less(key(fixed[i]), key(moving[j])));
            let (a, after_fixed, after_moving) = match fixed_first {
                // a fixed slot pairs only with the moving slots after it
                true => (fixed[i], &fixed[fixed.len()..], &moving[j..]),
                false => (moving[j], &fixed[i..], &moving[j + 1..]),
            };
            (i, j) = if fixed_first { (i + 1, j) } else { (i, j + 1) };
            let ba = &boxes[a as usize];
            // the slots after `a`, merged in order, up to the first whose left side is beyond it
            let (mut p, mut q) = (0, 0);
            loop {
                let b = match (after_fixed.get(p), after_moving.get(q)) {
                    (Some(&f), Some(&m)) if less(key(f), key(m)) => {
                        p += 1;
                        f
                    }
                    (_, Some(&m)) => {
                        q += 1;
                        m
                    }
                    (Some(&f), None) => {
                        p += 1;
                        f
                    }
                    (None, None) => break,
                };
                let bb = &boxes[b as usize];
                if bb.min_x > ba.max_x {
                    break;
                }
                if bb.min_y > ba.max_y || ba.min_y > bb.max_y {
                    continue;
                }
                self.pairs.push((a.min(b), a.max(b)));
            }
        }
    }

    /// The candidate pairs found by the last [`BroadPhase::update`].
    pub fn pairs(&self) -> &[(u32, u32)] {
        &self.pairs
    }

    /// Whether two slots belong to the same body.
    pub fn same_body(&self, a: u32, b: u32) -> bool {
        self.slot_body[a as usize] == self.slot_body[b as usize]
    }

    /// The fixed slots sorted when their boxes may have changed, the moving ones every time.
    fn sort(&mut self, boxes: &[Aabb], fixed_version: Option<u64>) {
        if fixed_version.is_none() || self.sorted_for != fixed_version {
            insertion_sort(&mut self.fixed_order, boxes);
            self.sorted_for = fixed_version;
        }
        insertion_sort(&mut self.moving_order, boxes);
    }
}

/// Insertion sort of slots by (left side, index): linear when little moved.
fn insertion_sort(order: &mut [u32], boxes: &[Aabb]) {
    let key = |s: u32| (boxes[s as usize].min_x, s);
    for i in 1..order.len() {
        let s = order[i];
        let k = key(s);
        let mut j = i;
        while j > 0 && less(k, key(order[j - 1])) {
            order[j] = order[j - 1];
            j -= 1;
        }
        order[j] = s;
    }
}

/// Strict order on (coordinate, index); coordinates are finite (the world undoes non-finite
/// substeps before boxes are updated).
pub(crate) fn less(a: (f64, u32), b: (f64, u32)) -> bool {
    a.0 < b.0 || (a.0 == b.0 && a.1 < b.1)
}

#[cfg(test)]
mod tests {
    use super::super::quad_geometry::Aabb;
    use super::*;

    fn bodies(boxes: &[(usize, Aabb)], fixed: &[bool]) -> Bodies {
        let mut offsets = vec![0u32];
        for b in 0..fixed.len() {
            offsets.push(boxes.iter().filter(|(body, _)| *body <= b).count() as u32);
        }
        Bodies {
            quad_points: vec![[0, 0, 0, 0]; boxes.len()],
            quad_sides: vec![[None; 4]; boxes.len()],
            walked_sides: vec![[(0, 0); 4]; boxes.len()],
            offsets,
            boundary: (0..boxes.len() as u32).collect(),
            all_fixed: fixed.to_vec(),
            watched: vec![false; fixed.len()],
            neighbour_offsets: vec![],
            neighbours: vec![],
            boxes: boxes.iter().map(|b| b.1).collect(),
            body_boxes: vec![Aabb::EMPTY; fixed.len()],
            fixed_boxes_version: 0,
        }
    }

    fn unit(x: f64, y: f64) -> Aabb {
        Aabb {
            min_x: x,
            min_y: y,
            max_x: x + 1.0,
            max_y: y + 1.0,
        }
    }

    /// Uniform numbers in [0, 1) from a seed (a linear congruential generator).
    fn uniform(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    /// The sweep finds exactly the overlapping pairs a brute-force double loop finds, on random
    /// boxes, and again after the boxes move.
    #[test]
    fn the_sweep_finds_the_brute_force_pairs() {
        let mut next = uniform(7);
        let mut slots: Vec<(usize, Aabb)> = (0..60)
            .map(|i| (i / 20, unit((next() * 12.0).floor(), (next() * 4.0).floor())))
            .collect();
        slots.sort_by_key(|s| s.0);
        let mut b = bodies(&slots, &[false, true, true]);
        let mut broad = BroadPhase::new(&b);
        for round in 0..3 {
            let mut expected = Vec::new();
            for bi in 0..3 {
                for bj in bi..3 {
                    if b.all_fixed[bi] && b.all_fixed[bj] {
                        continue;
                    }
                    for sa in b.slots(bi) {
                        let from = if bi == bj { sa + 1 } else { b.slots(bj).start };
                        for sb in from..b.slots(bj).end {
                            if b.boxes[sa].overlaps(&b.boxes[sb]) {
                                expected.push((sa as u32, sb as u32));
                            }
                        }
                    }
                }
            }
            assert!(!expected.is_empty());
            expected.sort_unstable();
            broad.update(&b);
            let mut found = broad.pairs().to_vec();
            found.sort_unstable();
            assert_eq!(found, expected, "round {round}");
            for slot in b.slots(0) {
                b.boxes[slot] = unit(next() * 12.0, next() * 4.0);
            }
        }
    }

    /// The pairs, in order, of one sweep over every slot sorted by (left side, index): the order
    /// in which contact forces are summed, which the split into fixed and moving slots keeps.
    fn swept_over_all(b: &Bodies) -> Vec<(u32, u32)> {
        let body = |s: u32| (0..b.len()).find(|&k| b.slots(k).contains(&(s as usize))).unwrap();
        let key = |s: u32| (b.boxes[s as usize].min_x, s);
        let mut order: Vec<u32> = (0..b.boxes.len() as u32).collect();
        order.sort_by(|&x, &y| key(x).partial_cmp(&key(y)).unwrap());
        let mut pairs = Vec::new();
        for (k, &a) in order.iter().enumerate() {
            let ba = &b.boxes[a as usize];
            for &s in &order[k + 1..] {
                let bb = &b.boxes[s as usize];
                if bb.min_x > ba.max_x {
                    break;
                }
                let both_fixed = b.all_fixed[body(a)] && b.all_fixed[body(s)];
                if bb.min_y > ba.max_y || ba.min_y > bb.max_y || both_fixed {
                    continue;
                }
                pairs.push((a.min(s), a.max(s)));
            }
        }
        pairs
    }

    #[test]
    fn the_pairs_come_in_the_order_of_one_sweep_over_every_slot() {
        let mut next = uniform(11);
        // bodies 0 and 2 move, 1 and 3 are fixed; coordinates on a coarse grid give ties
        let mut slots: Vec<(usize, Aabb)> = (0..80)
            .map(|i| (i / 20, unit((next() * 16.0).floor() * 0.5, (next() * 4.0).floor())))
            .collect();
        slots.sort_by_key(|s| s.0);
        let mut b = bodies(&slots, &[false, true, false, true]);
        let mut broad = BroadPhase::new(&b);
        for round in 0..40 {
            broad.update(&b);
            assert_eq!(broad.pairs(), swept_over_all(&b).as_slice(), "round {round}");
            for slot in b.slots(0).chain(b.slots(2)) {
                let moved = unit((next() * 16.0).floor() * 0.5, (next() * 4.0).floor());
                b.boxes[slot] = if next() < 0.3 { moved } else { b.boxes[slot] };
            }
            // now and then the terrain moves too (a fixed point placed by hand), and says so
            if round % 10 == 9 {
                for slot in b.slots(1) {
                    b.boxes[slot] = unit((next() * 16.0).floor() * 0.5, (next() * 4.0).floor());
                }
                b.fixed_boxes_version += 1;
            }
        }
    }

    #[test]
    fn pairs_of_two_fixed_bodies_are_left_out_and_touching_boxes_count() {
        let b = bodies(
            &[(0, unit(0.0, 0.0)), (1, unit(1.0, 0.0)), (2, unit(1.0, 1.0))],
            &[true, true, false],
        );
        let mut broad = BroadPhase::new(&b);
        broad.update(&b);
        assert_eq!(broad.pairs(), &[(0, 2), (1, 2)]);
        assert!(broad.same_body(0, 0) && !broad.same_body(0, 1));
    }
}
