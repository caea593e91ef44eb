//! Voxel–voxel collisions as voxcraft-sim computes them (`docs/voxelyze-model.md` §8.2): every
//! pair of surface voxels (fewer than six links) whose envelope spheres of radius 0.625·b
//! overlap, unless the two are directly linked or both fixed, pushes apart with a penalty spring
//! (harmonic mean of the two floor stiffnesses 2·E·s) and a dashpot on the approach speed (mean
//! of the two collision damping coefficients). No friction between voxels.
//!
//! voxcraft-sim tests every pair every step. The same pairs are found here from a candidate list
//! (a Verlet list): pairs whose centres were closer than the contact reach (of spheres grown by
//! a headroom) plus twice a margin when it was built, rebuilt once any voxel has moved more than
//! the margin or a rest size has outgrown the headroom. A pair left out cannot touch before the
//! rebuild, so the forces are those of testing every pair.

use glam::DVec3;

/// Envelope sphere radius per rest edge (voxcraft-sim's `COLLISION_ENVELOPE_RADIUS`).
pub(crate) const ENVELOPE_RADIUS: f64 = 0.625;

/// Growth of the largest rest edge (per lattice size) that the list allows for before it is
/// rebuilt: thermal actuation changes rest sizes every step.
pub(crate) const SIZE_HEADROOM: f64 = 0.2;

/// A voxel as the collision pass sees it: start-of-step state and constants.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Collider {
    pub pos: DVec3,
    pub velocity: DVec3,
    /// Rest edge `s (1 + cte T)`.
    pub size: f64,
    /// Penalty stiffness `2 E s`.
    pub stiffness: f64,
    /// Collision damping coefficient `ζ_c · 2 √(m E s)`.
    pub damping: f64,
}

/// The candidate pairs and the state they were built from; buffers reused between steps.
#[derive(Debug, Clone, Default)]
pub(crate) struct Collisions {
    /// Surface voxels that take part (fewer than six links, not every pair fixed).
    surface: Vec<usize>,
    /// Whether each surface voxel is fixed in every degree of freedom.
    fixed: Vec<bool>,
    /// Candidate pairs (indices of voxels).
    pairs: Vec<(usize, usize)>,
    /// Positions of the surface voxels when the list was built.
    built_at: Vec<DVec3>,
    /// Largest rest edge the list allows for (0: never built).
    built_size: f64,
    /// Surface voxels by x, for the sweep.
    order: Vec<usize>,
    /// Contacts now touching (for sensors), reset every step.
    pub touching: Vec<bool>,
    /// The pairs in contact this step (lower index first, in order).
    pub contacts: Vec<(usize, usize)>,
}

impl Collisions {
    /// Takes the surface voxels and which of them are fixed; the list is built at the next step.
    pub fn set_surface(&mut self, surface: Vec<usize>, fixed: Vec<bool>, voxels: usize) {
        self.surface = surface;
        self.fixed = fixed;
        self.built_size = 0.0;
        self.built_at.clear();
        self.touching = vec![false; voxels];
    }

    /// Adds every contact force of this step to `forces` (one per voxel); `linked` says whether
    /// two voxels share a link. Marks touching voxels.
    pub fn add_forces(
        &mut self,
        colliders: &[Collider],
        lattice: f64,
        linked: impl Fn(usize, usize) -> bool,
        forces: &mut [DVec3],
    ) {
        self.touching.iter_mut().for_each(|t| *t = false);
        self.contacts.clear();
        if self.surface.len() < 2 {
            return;
        }
        let margin = 0.5 * lattice;
        let largest = self.surface.iter().map(|&v| colliders[v].size).fold(0.0, f64::max);
        if self.needs_rebuild(colliders, margin, largest) {
            self.rebuild(colliders, margin, largest + SIZE_HEADROOM * lattice, &linked);
        }
        for &(a, b) in &self.pairs {
            if let Some(f) = contact_force(&colliders[a], &colliders[b]) {
                forces[a] -= f;
                forces[b] += f;
                self.contacts.push((a, b));
                self.touching[a] = true;
                self.touching[b] = true;
            }
        }
    }

    fn needs_rebuild(&self, colliders: &[Collider], margin: f64, largest: f64) -> bool {
        if self.built_size == 0.0 || largest > self.built_size {
            return true;
        }
        let limit = margin * margin;
        self.surface
            .iter()
            .zip(&self.built_at)
            .any(|(&v, &at)| colliders[v].pos.distance_squared(at) > limit)
    }

    /// Candidate pairs: centres within the reach of spheres of edge `largest` plus twice the
    /// margin, found by sorting along x and sweeping.
    fn rebuild(&mut self, colliders: &[Collider], margin: f64, largest: f64, linked: &impl Fn(usize, usize) -> bool) {
        let reach = 2.0 * ENVELOPE_RADIUS * largest + 2.0 * margin;
        self.built_size = largest;
        self.built_at.clear();
        self.built_at.extend(self.surface.iter().map(|&v| colliders[v].pos));
        self.order.clear();
        self.order.extend(0..self.surface.len());
        let (surface, built_at) = (&self.surface, &self.built_at);
        self.order.sort_unstable_by(|&i, &j| {
            built_at[i]
                .x
                .total_cmp(&built_at[j].x)
                .then(surface[i].cmp(&surface[j]))
        });
        self.pairs.clear();
        for (k, &i) in self.order.iter().enumerate() {
            for &j in &self.order[k + 1..] {
                if built_at[j].x - built_at[i].x > reach {
                    break;
                }
                let (a, b) = (surface[i].min(surface[j]), surface[i].max(surface[j]));
                let close = built_at[i].distance_squared(built_at[j]) <= reach * reach;
                if close && !(self.fixed[i] && self.fixed[j]) && !linked(a, b) {
                    self.pairs.push((a, b));
                }
            }
        }
        // the same order of forces whatever the sort met first: deterministic sums
        self.pairs.sort_unstable();
    }
}

/// The force on voxel `b` from voxel `a` (voxel `a` takes its opposite), if their envelopes
/// overlap: `u (k δ + c (v_a − v_b)·u)` with `u` the unit vector from `a` to `b`.
pub(crate) fn contact_force(a: &Collider, b: &Collider) -> Option<DVec3> {
    let offset = b.pos - a.pos;
    let reach = ENVELOPE_RADIUS * (a.size + b.size);
    // most candidate pairs are apart: tell from the squared distance, without its square root,
    // with a margin far above the rounding of `reach²` so that only pairs whose distance is
    // surely beyond `reach` are left out (the test below would leave them out too)
    let squared = offset.length_squared();
    if squared > reach * reach * (1.0 + 1e-9) {
        return None;
    }
    let distance = squared.sqrt();
    let overlap = reach - distance;
    if overlap <= 0.0 || distance == 0.0 {
        return None;
    }
    let u = offset / distance;
    let stiffness = 2.0 / (1.0 / a.stiffness + 1.0 / b.stiffness);
    let damping = 0.5 * (a.damping + b.damping);
    Some(u * (stiffness * overlap + damping * (a.velocity - b.velocity).dot(u)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, vx: f64) -> Collider {
        Collider {
            pos: DVec3::new(x, 0.0, 0.0),
            velocity: DVec3::new(vx, 0.0, 0.0),
            size: 0.01,
            stiffness: 200.0,
            damping: 0.0,
        }
    }

    #[test]
    fn overlapping_spheres_push_apart_with_the_harmonic_stiffness() {
        let a = at(0.0, 0.0);
        let b = Collider {
            stiffness: 600.0,
            ..at(0.01, 0.0)
        };
        // reach 0.0125, overlap 0.0025, k = 2 / (1/200 + 1/600) = 300
        let f = contact_force(&a, &b).unwrap();
        assert!((f.x - 300.0 * 0.0025).abs() < 1e-12, "{f}");
        assert_eq!((f.y, f.z), (0.0, 0.0));
        assert!(contact_force(&a, &at(0.0126, 0.0)).is_none());
    }

    #[test]
    fn the_squared_distance_prefilter_leaves_out_only_pairs_apart() {
        // around the reach (0.0125 between two 0.01 voxels), to the last bits
        let reach = ENVELOPE_RADIUS * 0.02;
        let mut x = reach * (1.0 - 1e-6);
        let mut touching = 0;
        while x < reach * (1.0 + 1e-6) {
            let (a, b) = (at(0.0, 0.0), at(x, 0.0));
            let exact = reach - (b.pos - a.pos).length() > 0.0;
            assert_eq!(contact_force(&a, &b).is_some(), exact, "{x}");
            touching += usize::from(exact);
            x = f64::from_bits(x.to_bits() + (1 << 20));
        }
        assert!(touching > 0);
    }

    #[test]
    fn the_dashpot_resists_approach_and_separation() {
        let damped = |x, vx| Collider {
            damping: 2.0,
            ..at(x, vx)
        };
        let approaching = contact_force(&damped(0.0, 1.0), &damped(0.012, 0.0)).unwrap();
        let still = contact_force(&damped(0.0, 0.0), &damped(0.012, 0.0)).unwrap();
        let leaving = contact_force(&damped(0.0, -1.0), &damped(0.012, 0.0)).unwrap();
        assert!((approaching.x - still.x - 2.0).abs() < 1e-12);
        assert!((still.x - leaving.x - 2.0).abs() < 1e-12);
    }

    #[test]
    fn linked_and_doubly_fixed_pairs_never_collide_and_the_list_matches_every_pair() {
        // four voxels on a line 0.011 apart: 0-1 linked, 2 and 3 both fixed
        let colliders: Vec<Collider> = (0..4).map(|i| at(0.011 * f64::from(i), 0.0)).collect();
        let mut c = Collisions::default();
        c.set_surface(vec![0, 1, 2, 3], vec![false, false, true, true], 4);
        let mut forces = vec![DVec3::ZERO; 4];
        c.add_forces(&colliders, 0.01, |a, b| (a, b) == (0, 1), &mut forces);
        // only 1-2 touches (0-1 linked, 2-3 both fixed, others too far)
        let f12 = contact_force(&colliders[1], &colliders[2]).unwrap();
        assert_eq!(forces, vec![DVec3::ZERO, -f12, f12, DVec3::ZERO]);
        assert_eq!(c.touching, vec![false, true, true, false]);
        assert_eq!(c.contacts, vec![(1, 2)]);
    }

    #[test]
    fn a_pair_that_comes_into_reach_between_rebuilds_is_found() {
        // 0.02 apart: no contact, but within the list's reach (0.0125 + 2 × 0.005)
        let mut colliders = vec![at(0.0, 0.0), at(0.02, 0.0)];
        let mut c = Collisions::default();
        c.set_surface(vec![0, 1], vec![false, false], 2);
        let mut forces = vec![DVec3::ZERO; 2];
        c.add_forces(&colliders, 0.01, |_, _| false, &mut forces);
        assert_eq!(forces, vec![DVec3::ZERO; 2]);
        // each moves 0.004 towards the other (less than the margin: no rebuild) and they touch
        colliders[0].pos.x += 0.004;
        colliders[1].pos.x -= 0.004;
        c.add_forces(&colliders, 0.01, |_, _| false, &mut forces);
        let f = contact_force(&colliders[0], &colliders[1]).unwrap();
        assert!(f.x > 0.0);
        assert_eq!(forces, vec![-f, f]);
    }
}
