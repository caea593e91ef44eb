//! A 2D point-mass and spring engine reproducing the physics of EvoGym's simulator (Bhatia et
//! al., 2021): point masses joined by stiff springs whose rest lengths track goal lengths,
//! integrated with classical RK4 at a small fixed time step, with penalty contacts.
//!
//! What it knows: points (mass, position, velocity, fixed or free); springs (stiffness, initial
//! rest length, a loose band and optional tight limits on their length); actuators (a target per
//! step that sets the goal length of the springs they drive); bodies made of quads, whose boundary
//! sides other points are pushed out through; a ground half-plane. Terrain is made of fixed points.
//!
//! Each substep ([`MassSpringWorld::step`] runs `substeps` of them):
//! 1. contact forces between quads from the current state (held through the substep);
//! 2. every rest length becomes the current length plus `tracking_rate` × (goal − length);
//! 3. one RK4 step of springs, drag, gravity, contact forces and ground;
//! 4. lengths pushed back toward their loose bands (all at once), then tight limits (in order);
//! 5. a non-finite state is undone and reported; a watched body folded into itself is reported.
//!
//! Guarantees: `step` allocates nothing; the same world stepped the same way gives bit-identical
//! states (no hashing, no threads, fixed order); it never panics on bad input and never lets a
//! NaN through unreported. `docs/evogym-model.md` lists the source of every constant and rule.

mod actuators;
mod bodies;
mod broad_phase;
mod builder;
mod contact;
mod contact_lanes;
mod error;
mod forces;
mod ground;
mod handles;
mod integrator;
mod lane_shape;
mod lanes;
mod overlap;
mod points;
mod projection;
mod quad_geometry;
mod rk4_lanes;
mod runs;
mod settings;
mod spring_lanes;
mod springs;
mod stage_points;
mod validate;
mod world;

#[cfg(test)]
mod lane_scenarios;
#[cfg(test)]
mod scenarios;

pub use builder::{BodyDesc, MassSpringBuilder, PointDesc, QuadDesc, SpringDesc};
pub use error::MassSpringError;
pub use handles::{ActuatorId, BodyId, PointId, QuadId, SpringId};
pub use lanes::{LaneReports, MassSpringLanes, LANES};
pub use settings::{ContactSettings, GroundPlane, MassSpringSettings};
pub use world::{MassSpringWorld, StepReport};
