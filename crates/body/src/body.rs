//! [`Body`]: what the rest of vsrlab needs of a robot's body once it is in a world.
//!
//! The episode loop, the tasks, the sensors and the renderer see a body only through this trait,
//! so a body that is not a voxel grid (a membrane around a gas, a ball-and-beam structure) is one
//! new type that implements it. [`crate::Vsr`], the 2D-VSR-Sim voxel body, is the first one.

use crate::robot::VoxelState;
use vsrlab_physics::{Vec2, World};

/// An assembled body: actuated units, sensing units and an outline, all read from the world.
pub trait Body: Send + Sync {
    /// Number of actuation values the body takes each step (one per voxel for a VSR).
    fn actuator_count(&self) -> usize;

    /// Applies one actuation per actuator (values in [-1, 1]); takes effect at the next step.
    fn actuate(&self, world: &mut World, values: &[f64]);

    /// The body's centre (a VSR: the unweighted mean of its voxel centres, each the mean of its
    /// corner bodies: the mass centre, as 2D-VSR-Sim's `Robot.center`).
    fn center(&self, world: &World) -> Vec2;

    /// The point whose displacement locomotion measures: [`Body::center`] unless a body says
    /// otherwise. A VSR measures, as 2D-VSR-Sim's `Outcome` does (v1.10 on), the mean of its
    /// voxels' outer-polygon centres, which moves when corners turn even if the mass centre
    /// does not.
    fn outcome_center(&self, world: &World) -> Vec2 {
        self.center(world)
    }

    /// Number of sensing units: the places sensors sit on (a VSR: its voxels).
    fn sensing_units(&self) -> usize;

    /// What the sensors of unit `i` read at the current step.
    fn unit_state(&self, world: &World, i: usize) -> VoxelState;

    /// Corner count of each polygon of [`Body::outline`], in order; the same at every step.
    fn outline_corners(&self) -> Vec<usize>;

    /// Appends the corners of every outline polygon (see [`Body::outline_corners`]) to `out`:
    /// what a renderer draws and what shape descriptors measure.
    fn outline(&self, world: &World, out: &mut Vec<Vec2>);

    /// Axis-aligned bounding box (min, max) of the outline.
    fn bounding_box(&self, world: &World) -> (Vec2, Vec2) {
        let mut corners = Vec::new();
        self.outline(world, &mut corners);
        let mut min = Vec2::new(f64::INFINITY, f64::INFINITY);
        let mut max = -min;
        for p in corners {
            min = min.min(p);
            max = max.max(p);
        }
        (min, max)
    }
}
