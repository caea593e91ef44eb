//! Voxel–voxel collisions of N episodes at once (population lanes), as `collision.rs` computes
//! them in each lane. One candidate list serves every lane: the union of the pairs each lane's own
//! list would hold, rebuilt for every lane as soon as one lane needs it. A pair not in a lane's
//! own list cannot touch in that lane (collision.rs), so testing more pairs gives the same
//! forces; the pairs are visited in the same sorted order, and a lane adds a pair's force only
//! where that pair touches in it, so each lane sums exactly the scalar world's terms in the
//! scalar world's order.

use crate::collision::{ENVELOPE_RADIUS, SIZE_HEADROOM};
use crate::lanes::V3;
use vsrlab_lanes::{and, any, not, or, LaneMask, Lanes};

/// A voxel as the laned collision pass sees it: each lane's start-of-step state, and the
/// constants its material gives every lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ColliderLanes<L: Lanes> {
    pub pos: V3<L>,
    pub velocity: V3<L>,
    /// Rest edge in each lane.
    pub size: L,
    /// Penalty stiffness `2 E s`.
    pub stiffness: f64,
    /// Collision damping coefficient.
    pub damping: f64,
}

/// The shared candidate list, each lane's build state, and this step's forces and touches.
#[derive(Debug, Clone)]
pub(crate) struct CollisionLanes<L: Lanes> {
    /// Surface voxels (fewer than six links), and whether each is fixed in every DOF.
    surface: Vec<usize>,
    fixed: Vec<bool>,
    /// Pairs of voxels that may not collide: directly linked (lower index first).
    linked: Vec<(usize, usize)>,
    /// Candidate pairs of every lane, sorted.
    pairs: Vec<(usize, usize)>,
    /// Positions of the surface voxels when the list was built, every lane.
    built_at: Vec<V3<L>>,
    /// Largest rest edge each lane's list allows for (0: never built).
    built_size: L,
    /// Contact force on each voxel this step.
    pub forces: Vec<V3<L>>,
    /// Whether each voxel touches another this step, in each lane.
    pub touching: Vec<L::Mask>,
    /// The pairs that touch this step in some lane (in the pairs' order), and in which lanes.
    pub contacts: Vec<(usize, usize, L::Mask)>,
}

impl<L: Lanes> CollisionLanes<L> {
    /// The pass for `voxels` voxels of which `surface` collide, `fixed` says which of them are
    /// fixed in every DOF, and `linked` lists the directly linked pairs.
    pub fn new(voxels: usize, surface: Vec<usize>, fixed: Vec<bool>, mut linked: Vec<(usize, usize)>) -> Self {
        linked.iter_mut().for_each(|p| *p = (p.0.min(p.1), p.0.max(p.1)));
        linked.sort_unstable();
        CollisionLanes {
            surface,
            fixed,
            linked,
            pairs: Vec::new(),
            built_at: Vec::new(),
            built_size: L::splat(0.0),
            forces: vec![V3::splat(glam::DVec3::ZERO); voxels],
            touching: vec![L::Mask::splat(false); voxels],
            contacts: Vec::new(),
        }
    }

    /// Forgets lane `lane`'s contacts and list, as a world that has not stepped has none (a
    /// lane restarted): its list is rebuilt at the next step.
    pub fn forget_lane(&mut self, lane: usize) {
        self.built_size.set(lane, 0.0);
        self.forces.iter_mut().for_each(|f| f.set_lane(lane, glam::DVec3::ZERO));
        self.touching.iter_mut().for_each(|t| t.set(lane, false));
        self.contacts.iter_mut().for_each(|(_, _, hit)| hit.set(lane, false));
    }

    /// Sets every voxel's contact force of this step (`forces`) and which voxels touch.
    #[inline(always)]
    pub fn add_forces(&mut self, colliders: &[ColliderLanes<L>], lattice: f64) {
        let zero = V3::splat(glam::DVec3::ZERO);
        self.forces.iter_mut().for_each(|f| *f = zero);
        self.touching.iter_mut().for_each(|t| *t = L::Mask::splat(false));
        self.contacts.clear();
        if self.surface.len() < 2 {
            return;
        }
        let margin = 0.5 * lattice;
        let mut largest = L::splat(0.0);
        for l in 0..L::LANES {
            largest.set(
                l,
                self.surface
                    .iter()
                    .map(|&v| colliders[v].size.get(l))
                    .fold(0.0, f64::max),
            );
        }
        if self.needs_rebuild(colliders, margin, largest) {
            self.rebuild(colliders, margin, largest + SIZE_HEADROOM * lattice);
        }
        for &(a, b) in &self.pairs {
            let Some((hit, f)) = contact_force(&colliders[a], &colliders[b]) else {
                continue;
            };
            self.forces[a] = V3::select(hit, self.forces[a].sub(f), self.forces[a]);
            self.forces[b] = V3::select(hit, self.forces[b].add(f), self.forces[b]);
            self.touching[a] = or(self.touching[a], hit);
            self.touching[b] = or(self.touching[b], hit);
            self.contacts.push((a, b, hit));
        }
    }

    /// Whether some lane's list is stale: never built, outgrown, or a voxel moved beyond the
    /// margin since the build.
    #[inline(always)]
    fn needs_rebuild(&self, colliders: &[ColliderLanes<L>], margin: f64, largest: L) -> bool {
        let built = self.built_size;
        if (0..L::LANES).any(|l| built.get(l) == 0.0 || largest.get(l) > built.get(l)) {
            return true;
        }
        // a plain loop, not `Iterator::any`: its `try_fold` was not inlined into the AVX2 step,
        // so each lane operation inside it ran as a call (2 % of a population's time)
        let limit = L::splat(margin * margin);
        for (&v, at) in self.surface.iter().zip(&self.built_at) {
            let d = colliders[v].pos.sub(*at);
            let squared = d.x * d.x + d.y * d.y + d.z * d.z;
            if any(squared.gt(limit)) {
                return true;
            }
        }
        false
    }

    /// Every lane's candidate pairs (collision.rs's sweep along x in that lane), joined.
    fn rebuild(&mut self, colliders: &[ColliderLanes<L>], margin: f64, largest: L) {
        self.built_size = largest;
        self.built_at.clear();
        self.built_at.extend(self.surface.iter().map(|&v| colliders[v].pos));
        self.pairs.clear();
        let mut order: Vec<usize> = Vec::with_capacity(self.surface.len());
        for l in 0..L::LANES {
            let size = largest.get(l);
            let reach = 2.0 * ENVELOPE_RADIUS * size + 2.0 * margin;
            let at = |i: usize| self.built_at[i].lane(l);
            order.clear();
            order.extend(0..self.surface.len());
            order.sort_unstable_by(|&i, &j| at(i).x.total_cmp(&at(j).x).then(self.surface[i].cmp(&self.surface[j])));
            for (k, &i) in order.iter().enumerate() {
                for &j in &order[k + 1..] {
                    if at(j).x - at(i).x > reach {
                        break;
                    }
                    let (a, b) = (
                        self.surface[i].min(self.surface[j]),
                        self.surface[i].max(self.surface[j]),
                    );
                    let close = at(i).distance_squared(at(j)) <= reach * reach;
                    if close && !(self.fixed[i] && self.fixed[j]) && self.linked.binary_search(&(a, b)).is_err() {
                        self.pairs.push((a, b));
                    }
                }
            }
        }
        self.pairs.sort_unstable();
        self.pairs.dedup();
    }
}

/// `collision::contact_force` in every lane: the lanes where the envelopes overlap, and the force
/// on `b` there; `None` when they overlap in no lane.
#[inline(always)]
fn contact_force<L: Lanes>(a: &ColliderLanes<L>, b: &ColliderLanes<L>) -> Option<(L::Mask, V3<L>)> {
    let offset = b.pos.sub(a.pos);
    let reach = (a.size + b.size) * ENVELOPE_RADIUS;
    let squared = offset.x * offset.x + offset.y * offset.y + offset.z * offset.z;
    let near = not(squared.gt(reach * reach * (1.0 + 1e-9)));
    if !any(near) {
        return None;
    }
    let distance = squared.sqrt();
    let overlap = reach - distance;
    let zero = L::splat(0.0);
    let hit = and(near, and(overlap.gt(zero), not(distance.eq(zero))));
    if !any(hit) {
        return None;
    }
    let u = V3 {
        x: offset.x / distance,
        y: offset.y / distance,
        z: offset.z / distance,
    };
    let stiffness = 2.0 / (1.0 / a.stiffness + 1.0 / b.stiffness);
    let damping = 0.5 * (a.damping + b.damping);
    let dv = a.velocity.sub(b.velocity);
    let approach = dv.x * u.x + dv.y * u.y + dv.z * u.z;
    let magnitude = overlap * stiffness + approach * damping;
    Some((
        hit,
        V3 {
            x: u.x * magnitude,
            y: u.y * magnitude,
            z: u.z * magnitude,
        },
    ))
}
