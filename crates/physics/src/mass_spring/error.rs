//! What can go wrong building or stepping a mass-spring world.

/// Errors of [`MassSpringBuilder::build`](super::MassSpringBuilder::build) and
/// [`MassSpringWorld::step`](super::MassSpringWorld::step). None of them panics.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MassSpringError {
    /// The world description is invalid; the message names the element and the rule it breaks.
    #[error("invalid mass-spring world: {0}")]
    Invalid(String),
    /// `step` received a number of targets different from the number of actuators.
    #[error("expected {expected} targets (one per actuator), got {got}")]
    TargetCount {
        /// Actuators in the world.
        expected: usize,
        /// Targets passed.
        got: usize,
    },
    /// A target was NaN or infinite.
    #[error("target {actuator} is not finite ({value})")]
    NonFiniteTarget {
        /// Index of the actuator.
        actuator: usize,
        /// The value passed.
        value: f64,
    },
    /// A point's position or velocity became NaN or infinite. The world was put back to the
    /// state before the failing substep.
    #[error("state became non-finite in substep {substep} at point {point}: the simulation exploded")]
    NonFinite {
        /// Substep (counted from 0 over the world's life) that produced the bad state.
        substep: u64,
        /// First offending point.
        point: usize,
    },
    /// A watched body overlaps itself: more ordered pairs of its non-neighbouring boundary quads
    /// have overlapping bounding boxes than it has boundary quads (EvoGym's "unstable"). The
    /// world keeps the state after the substep.
    #[error(
        "body {body} overlaps itself after substep {substep} ({pairs} overlapping quad pairs, \
         more than its {limit} boundary quads): unstable"
    )]
    SelfOverlap {
        /// Substep (counted from 0 over the world's life).
        substep: u64,
        /// The body.
        body: usize,
        /// Ordered pairs of non-neighbouring boundary quads whose boxes overlap.
        pairs: usize,
        /// The body's boundary-quad count, the largest number of pairs tolerated.
        limit: usize,
    },
}
