//! A voxel's state and what stays fixed about it.

use glam::{DQuat, DVec3};

/// The degrees of freedom a voxel can have fixed: translations then rotations.
pub(crate) type DofMask = [bool; 6];

/// One voxel.
#[derive(Debug, Clone)]
pub(crate) struct Voxel {
    pub material: usize,
    pub index: [i32; 3],
    pub pos: DVec3,
    pub orient: DQuat,
    pub momentum: DVec3,
    pub angular_momentum: DVec3,
    pub temperature: f64,
    /// Rest edge at this temperature, `s (1 + cte T)`, kept with the temperature.
    pub size: f64,
    /// The dt of its last step (internal damping divides by it).
    pub dt_prev: f64,
    /// Static friction holds it (voxels start static).
    pub is_static: bool,
    pub fixed: DofMask,
    pub external_force: DVec3,
    pub external_moment: DVec3,
    /// Its links: (link index, whether this voxel is the link's negative end).
    pub links: Vec<(usize, bool)>,
}

impl Voxel {
    pub fn new(material: usize, index: [i32; 3], lattice: f64) -> Voxel {
        Voxel {
            material,
            index,
            pos: nominal(index, lattice),
            orient: DQuat::IDENTITY,
            momentum: DVec3::ZERO,
            angular_momentum: DVec3::ZERO,
            temperature: 0.0,
            size: lattice,
            dt_prev: 0.0,
            is_static: true,
            fixed: [false; 6],
            external_force: DVec3::ZERO,
            external_moment: DVec3::ZERO,
            links: Vec::new(),
        }
    }

    /// Whether every degree of freedom is fixed.
    pub fn all_fixed(&self) -> bool {
        self.fixed.iter().all(|&f| f)
    }
}

/// A voxel's rest edge on a lattice of size `lattice` at `temperature`: `s (1 + cte T)`.
pub(crate) fn rest_edge(lattice: f64, cte: f64, temperature: f64) -> f64 {
    lattice * (1.0 + cte * temperature)
}

/// The lattice position of index `i`: the voxel's centre at rest.
pub(crate) fn nominal(i: [i32; 3], lattice: f64) -> DVec3 {
    DVec3::new(f64::from(i[0]), f64::from(i[1]), f64::from(i[2])) * lattice
}
