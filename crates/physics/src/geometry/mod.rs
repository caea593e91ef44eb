//! Geometry: shapes, bounding boxes, contact manifolds and ray casts. Knows nothing of motion.

pub mod aabb;
pub mod collide;
pub mod raycast;
pub mod shape;
