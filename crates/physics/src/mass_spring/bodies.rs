//! Bodies: groups of quads that collide as one object. Only boundary quads (those with at least
//! one boundary side) take part in contacts and in the self-overlap check.

use super::quad_geometry::Aabb;

/// Quads, their boundary sides, and per-body lists of boundary quads with their boxes.
#[derive(Debug, Clone)]
pub(crate) struct Bodies {
    /// Corners of each quad, in cyclic order.
    pub quad_points: Vec<[u32; 4]>,
    /// Side `i` joins corners `i` and `i + 1`; a boundary side is stored as its endpoints ordered
    /// so that the normal `(-dy, dx)` of a→b points out of the quad.
    pub quad_sides: Vec<[Option<(u32, u32)>; 4]>,
    /// Every side of each quad as (from, to), directed as the crossing test walks it.
    pub walked_sides: Vec<[(u32, u32); 4]>,
    /// Body `b`'s boundary quads are `boundary[offsets[b]..offsets[b + 1]]` (a slot each).
    pub offsets: Vec<u32>,
    pub boundary: Vec<u32>,
    /// Bodies whose points are all fixed: nothing to compute between two of them.
    pub all_fixed: Vec<bool>,
    /// Bodies checked for self-overlap after every substep.
    pub watched: Vec<bool>,
    /// Per body, a row-major matrix over its slots: whether two boundary quads were touching or
    /// overlapping when the world was built (neighbours never count as overlapping).
    pub neighbour_offsets: Vec<usize>,
    pub neighbours: Vec<bool>,
    /// Box of each slot, and of each body (union of its slots).
    pub boxes: Vec<Aabb>,
    pub body_boxes: Vec<Aabb>,
    /// Counts the updates that may have changed the boxes of all-fixed bodies (which only
    /// [`Bodies::update_boxes`] with `all` does): the broad phase sorts their slots again then.
    pub fixed_boxes_version: u64,
}

impl Bodies {
    /// Number of bodies.
    pub fn len(&self) -> usize {
        self.watched.len()
    }

    /// Slots of body `b`.
    pub fn slots(&self, b: usize) -> std::ops::Range<usize> {
        self.offsets[b] as usize..self.offsets[b + 1] as usize
    }

    /// Whether slots `i` and `j` of body `b` (counted from the body's first slot) are neighbours.
    pub fn are_neighbours(&self, b: usize, i: usize, j: usize) -> bool {
        let n = self.slots(b).len();
        self.neighbours[self.neighbour_offsets[b] + i * n + j]
    }

    /// Whether `other` has the same quads, sides, bodies and boundary slots (the topology the
    /// contacts read; boxes and neighbours aside).
    pub fn same_quads(&self, other: &Bodies) -> bool {
        self.quad_points == other.quad_points
            && self.quad_sides == other.quad_sides
            && self.walked_sides == other.walked_sides
            && self.offsets == other.offsets
            && self.boundary == other.boundary
            && self.all_fixed == other.all_fixed
    }

    /// Recomputes the boxes of every body that can move (`all = true`: of every body).
    pub fn update_boxes(&mut self, x: &[f64], y: &[f64], all: bool) {
        self.fixed_boxes_version += u64::from(all);
        for b in 0..self.len() {
            if self.all_fixed[b] && !all {
                continue;
            }
            let mut body_box = Aabb::EMPTY;
            for slot in self.slots(b) {
                let q = self.quad_points[self.boundary[slot] as usize];
                let bx = Aabb::of_quad(q.map(|p| x[p as usize]), q.map(|p| y[p as usize]));
                self.boxes[slot] = bx;
                body_box = body_box.union(bx);
            }
            self.body_boxes[b] = body_box;
        }
    }

    /// Fills the neighbour matrices from the current boxes, with tolerance `tol`.
    pub fn find_neighbours(&mut self, tol: f64) {
        self.neighbour_offsets.clear();
        self.neighbours.clear();
        for b in 0..self.len() {
            self.neighbour_offsets.push(self.neighbours.len());
            let slots = self.slots(b);
            for i in slots.clone() {
                for j in slots.clone() {
                    self.neighbours.push(self.boxes[i].overlaps_within(&self.boxes[j], tol));
                }
            }
        }
    }
}
