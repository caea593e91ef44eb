//! dyn4j's contact semantics inside the soft solver (`contact_model = "dyn4j"`): a candidate of
//! docs/fidelity.md that keeps the soft solver's bodies (welded parts merged) and sub-stepped soft
//! springs, and replaces its soft, speculative contacts with the original's: contacts only between
//! overlapping shapes (parting as soon as they stop overlapping), rigid normal impulses with
//! dyn4j's restitution target, Coulomb friction, every impulse warm started from the last step's
//! point with the same features (which anchors a sticking contact), a Baumgarte position pass
//! after the velocities, and dyn4j's continuous collision against static geometry.
//!
//! The contacts are the sequential-impulse solver's own ([`sequential::Contacts`],
//! [`sequential::Ccd`]): only where they are called differs.

use super::contact::ContactConstraint;
use super::sequential::{self, Params};
use super::world::Bodies;

/// The contacts of a soft world that follows dyn4j's contact semantics.
#[derive(Debug, Clone)]
pub(crate) struct Dyn4jContacts {
    contacts: sequential::Contacts,
    ccd: sequential::Ccd,
    /// The order of the sweeps: the contacts as collected (reused buffer).
    order: Vec<u32>,
}

impl Dyn4jContacts {
    pub fn new(ccd: sequential::Ccd) -> Dyn4jContacts {
        Dyn4jContacts {
            contacts: sequential::Contacts::default(),
            ccd,
            order: Vec::new(),
        }
    }

    /// Takes over the detected contacts, carrying over the impulses of points found again.
    pub fn collect(&mut self, detected: &[ContactConstraint], bodies: &Bodies, p: &Params) {
        let oldest_first = p.version == super::settings::Dyn4jVersion::V4_2_1;
        self.contacts.collect(detected, bodies, p.warm_starting, oldest_first);
        self.order.clear();
        self.order.extend(0..self.contacts.pairs().count() as u32);
    }

    /// Before the velocities are integrated: remembers the poses continuous collision starts from.
    pub fn remember_start(&mut self, bodies: &Bodies) {
        self.ccd.remember_start(bodies);
    }

    /// Effective masses and restitution targets from the state at the start of the solve, then
    /// the carried-over impulses applied again.
    pub fn initialize(&mut self, bodies: &mut Bodies, p: &Params) {
        self.contacts.initialize(bodies, p, &self.order);
    }

    /// One velocity sweep over the contacts (friction, then the normal impulses).
    pub fn solve_velocities(&mut self, bodies: &mut Bodies) {
        self.contacts.solve_velocities(bodies, &self.order);
    }

    /// After the positions are integrated: up to `position_iterations` Baumgarte sweeps, then
    /// continuous collision against static geometry.
    pub fn finish(
        &mut self,
        bodies: &mut Bodies,
        detected: &[ContactConstraint],
        static_of: fn(u64) -> u32,
        p: &Params,
    ) {
        for _ in 0..p.position_iterations {
            if self.contacts.solve_positions(bodies, p, &self.order) {
                break;
            }
        }
        if p.continuous_collision {
            self.ccd.solve(bodies, detected, static_of, p);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::dynamics::settings::{ContactModel, WorldSettings};
    use crate::{PartDesc, Polygon, Vec2, WorldBuilder};

    /// A 2×1 pair of welded squares dropped on ground whose top is at y = 5; the pair's lowest
    /// point after 3 s and its largest speed then.
    fn drop_pair(contact_model: ContactModel) -> (f64, f64) {
        let mut b = WorldBuilder::new(WorldSettings {
            contact_model,
            ..WorldSettings::default()
        });
        b.add_static_polygon(Polygon::rect(Vec2::new(0.0, -20.0), 50.0, 25.0), 0.2, 0.0);
        let square = |x: f64| {
            PartDesc::new(Vec2::new(x, 7.0), Polygon::square(Vec2::ZERO, 1.0))
                .density(1.0)
                .friction(1.0)
                .restitution(0.1)
        };
        let (l, r) = (b.add_part(square(0.0)), b.add_part(square(1.0)));
        b.weld(l, r);
        let mut w = b.build().unwrap();
        for _ in 0..180 {
            w.step().unwrap();
        }
        let low = [l, r]
            .iter()
            .flat_map(|&p| [-0.5, 0.5].map(|x| w.part_point(p, Vec2::new(x, -0.5)).y))
            .fold(f64::INFINITY, f64::min);
        (low, w.part_velocity(l).length().max(w.part_velocity(r).length()))
    }

    #[test]
    fn dyn4j_contacts_rest_overlapping_by_about_the_slop_and_soft_ones_do_not() {
        let (low, speed) = drop_pair(ContactModel::Dyn4j);
        let overlap = 5.0 - low;
        // the position pass leaves the slop (0.005) of overlap, as dyn4j does
        assert!(overlap > 0.0 && overlap < 3.0 * 0.005, "overlap {overlap}");
        assert!(speed < 0.01, "speed {speed}");
        let (low, _) = drop_pair(ContactModel::Soft);
        assert!(
            (5.0 - low).abs() < 0.005 && (5.0 - low - overlap).abs() > 1e-4,
            "soft rests at {low}"
        );
    }
}
