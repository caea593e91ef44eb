//! Small `Copy` handles to the elements of a mass-spring world, given out by the builder.

use serde::{Deserialize, Serialize};

macro_rules! handle {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
        pub struct $name(pub(crate) u32);

        impl $name {
            /// Position of the element in the world's slices (order of creation).
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }
    };
}

handle!(
    /// A point mass.
    PointId
);
handle!(
    /// A spring between two points.
    SpringId
);
handle!(
    /// A body: a group of quads that collide as one object.
    BodyId
);
handle!(
    /// A quadrilateral of four points inside a body.
    QuadId
);
handle!(
    /// An actuator: one target value per step drives the goal length of its springs.
    ActuatorId
);
