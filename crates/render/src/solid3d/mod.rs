//! Frames of 3D voxel episodes (traces with `voxel_xyz`): a small software renderer. A fixed
//! perspective camera follows the body from the front side and above; each voxel is a cube whose
//! visible faces are filled with its colour under Lambert shading and outlined, all faces painted
//! far to near over a checkerboard floor and the sky.

mod camera;
mod cube;
mod floor;
mod painter;
mod quat;
mod scene;
mod shading;
mod vec3;

pub(crate) use scene::{has_every_step, is_solid, SolidScene};

#[cfg(test)]
mod tests;
