//! Gas pressure inside a closed ring of parts: a 2D balloon.
//!
//! Each step, before gravity and external forces are integrated, every ring edge from part i to
//! part i+1 pushes outward with force p·L along its outward unit normal, half on each end. L is
//! the edge's current length ([`EdgeLength::Actual`]) or the rest length of a spring along that
//! edge ([`EdgeLength::SpringRest`], what the PSA paper's code did). The forces come from the
//! positions at the start of the step, so a pressure set after a step acts during the next one.
//! The outward side is found from the sign of the ring's shoelace area, so a ring listed clockwise
//! or counter-clockwise works the same; a ring that folds over itself (zero area) gets no force.

use super::world::Bodies;
use crate::math::Vec2;

/// Which length L an edge's force p·L uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EdgeLength {
    /// The distance between the edge's two parts now (the physically consistent choice).
    Actual,
    /// The rest length of the spring given for that edge (the original PSA code's variant).
    SpringRest,
}

/// One pressurised ring in a built world.
#[derive(Debug, Clone)]
pub(crate) struct PressureRing {
    /// Body of each ring part, in ring order.
    pub bodies: Vec<u32>,
    /// Spring slot of each edge (i → i+1) when the length is a spring's rest length.
    pub spring_slots: Vec<u32>,
    pub length: EdgeLength,
    /// Current pressure (force per unit length in 2D).
    pub pressure: f64,
}

impl PressureRing {
    /// Signed shoelace area of the polygon through the ring's bodies (positive when
    /// counter-clockwise).
    pub fn signed_area(&self, bodies: &Bodies) -> f64 {
        let n = self.bodies.len();
        let mut twice = 0.0;
        for i in 0..n {
            let a = bodies.state[self.bodies[i] as usize].pos;
            let b = bodies.state[self.bodies[(i + 1) % n] as usize].pos;
            twice += a.cross(b);
        }
        0.5 * twice
    }

    /// Adds the pressure forces to the ring's bodies. `rest(slot)` gives a spring's rest length.
    pub fn apply(&self, bodies: &mut Bodies, rest: impl Fn(u32) -> f64) {
        if self.pressure == 0.0 {
            return;
        }
        let area = self.signed_area(bodies);
        if area == 0.0 {
            return;
        }
        // for a counter-clockwise ring the outward normal of edge e is (e.y, −e.x)/|e|
        let side = area.signum();
        let n = self.bodies.len();
        for i in 0..n {
            let (ia, ib) = (self.bodies[i] as usize, self.bodies[(i + 1) % n] as usize);
            let e = bodies.state[ib].pos - bodies.state[ia].pos;
            let scaled_normal = Vec2::new(e.y, -e.x) * side; // outward, |e| long
            let force = match self.length {
                EdgeLength::Actual => scaled_normal * self.pressure,
                EdgeLength::SpringRest => {
                    let len = e.length();
                    if len <= 1e-12 {
                        continue;
                    }
                    scaled_normal * (self.pressure * rest(self.spring_slots[i]) / len)
                }
            };
            let half = force * 0.5;
            bodies.force[ia] += half;
            bodies.force[ib] += half;
        }
    }
}
