//! Broad phase: which pairs of boundary quads may touch, by sweep and prune along x.
//!
//! The boundary quads (slots) are kept sorted by the left side of their boxes; each substep the
//! order is repaired by insertion sort (nearly sorted after a small step) and swept once. The
//! sorted order is unique for given boxes (ties broken by slot index), so the pairs, and the order
//! in which contact forces are summed, depend only on the state: stepping stays deterministic.

use super::bodies::Bodies;

/// The sorted slots and the candidate pairs of the current substep, kept between substeps.
#[derive(Debug, Clone)]
pub(crate) struct BroadPhase {
    /// Every slot, ordered by (left side of its box, slot index).
    order: Vec<u32>,
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
        let order = (0..slot_body.len() as u32).collect();
        Self {
            order,
            slot_body,
            pairs: Vec::new(),
        }
    }

    /// Finds every pair of slots whose boxes overlap (closed test), leaving out pairs whose bodies
    /// are both all fixed, in sweep order. Allocates nothing once the pair list has grown to its
    /// largest size.
    pub fn update(&mut self, bodies: &Bodies) {
        self.sort(bodies);
        self.pairs.clear();
        let boxes = &bodies.boxes;
        for (k, &a) in self.order.iter().enumerate() {
            let ba = &boxes[a as usize];
            let fixed_a = bodies.all_fixed[self.slot_body[a as usize] as usize];
            for &b in &self.order[k + 1..] {
                let bb = &boxes[b as usize];
                if bb.min_x > ba.max_x {
                    break;
                }
                if bb.min_y > ba.max_y
                    || ba.min_y > bb.max_y
                    || (fixed_a && bodies.all_fixed[self.slot_body[b as usize] as usize])
                {
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

    /// Insertion sort of the slots by (left side, index): linear when little moved.
    fn sort(&mut self, bodies: &Bodies) {
        let key = |s: u32| (bodies.boxes[s as usize].min_x, s);
        for i in 1..self.order.len() {
            let s = self.order[i];
            let k = key(s);
            let mut j = i;
            while j > 0 && less(k, key(self.order[j - 1])) {
                self.order[j] = self.order[j - 1];
                j -= 1;
            }
            self.order[j] = s;
        }
    }
}

/// Strict order on (coordinate, index); coordinates are finite (the world undoes non-finite
/// substeps before boxes are updated).
fn less(a: (f64, u32), b: (f64, u32)) -> bool {
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

    /// The sweep finds exactly the overlapping pairs a brute-force double loop finds, on random
    /// boxes, and again after the boxes move.
    #[test]
    fn the_sweep_finds_the_brute_force_pairs() {
        let mut state = 7u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
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
