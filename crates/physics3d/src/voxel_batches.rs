//! The voxels of one world integrated four at a time (issue 52, item 4: SIMD inside one
//! episode). Free voxels (no fixed degree of freedom) of one material form batches of four; each
//! step `World::step_voxels` gathers a batch's state and loads into AVX2 lanes, runs the laned
//! update (`VoxelLanes::step`, each lane the bits of `World::step_voxel`), and writes the state
//! back. Voxels left over, voxels with fixed degrees of freedom, and every voxel on a CPU without
//! AVX2 step one by one.

use crate::voxel::Voxel;

use crate::batching::in_fours;
pub(crate) use crate::batching::BATCH;
/// Which voxels step together.
#[derive(Debug, Clone, Default)]
pub(crate) struct VoxelBatches {
    /// Four free voxels each, and their material.
    pub batches: Vec<(usize, [usize; BATCH])>,
    /// The voxels in no batch.
    pub single: Vec<usize>,
}

impl VoxelBatches {
    /// Batches for `voxels`: the free ones grouped by material in voxel order, four at a time;
    /// the rest step alone. No batches when `lanes` is false (a CPU without AVX2).
    pub fn plan(voxels: &[Voxel], lanes: bool) -> VoxelBatches {
        let free = |v: &Voxel| lanes && !v.fixed.iter().any(|&f| f);
        let (batches, single) = in_fours(voxels.iter().map(|v| free(v).then_some(v.material)));
        VoxelBatches { batches, single }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::{Dof, VoxelId, World, WorldSettings};
    use crate::Material;
    use glam::DVec3;

    /// Random bodies of two materials (4³ and 5³ boxes, 70 % filled, collisions on, one voxel
    /// with fixed rotations), heated at random: the world with link and voxel batches keeps the
    /// bits of the same world stepping every link and voxel one by one.
    #[test]
    fn a_world_in_batches_gives_the_bits_of_one_stepping_one_by_one() {
        let mut next = crate::validation::uniform(0x5EED);
        for side in [4, 5] {
            let cells = crate::validation::random_piece(&mut next, side, 0.7);
            let mut batched = World::new(WorldSettings::default()).unwrap();
            let soft = batched.add_material(Material::affordance()).unwrap();
            let stiff = batched
                .add_material(Material {
                    youngs_modulus: 3.0 * Material::affordance().youngs_modulus,
                    ..Material::affordance()
                })
                .unwrap();
            let ids: Vec<VoxelId> = cells
                .iter()
                .enumerate()
                .map(|(i, &c)| batched.add_voxel(if i % 3 == 0 { stiff } else { soft }, c).unwrap())
                .collect();
            batched.set_fixed(ids[1], &[Dof::Rx, Dof::Ry], true);
            let mut alone = batched.clone();
            alone.one_by_one();
            let dt = 0.9 * batched.recommended_time_step();
            for step in 0..(0.05 / dt) as usize {
                if step % 40 == 0 {
                    for &v in &ids {
                        let t = 20.0 * (2.0 * next() - 1.0);
                        batched.set_temperature(v, t);
                        alone.set_temperature(v, t);
                    }
                }
                batched.step(dt).unwrap();
                alone.step(dt).unwrap();
            }
            for &v in &ids {
                let bits = |p: DVec3| p.to_array().map(f64::to_bits);
                assert_eq!(bits(batched.position(v)), bits(alone.position(v)), "{side}³");
                assert_eq!(bits(batched.velocity(v)), bits(alone.velocity(v)), "{side}³");
                assert_eq!(batched.orientation(v), alone.orientation(v), "{side}³");
            }
            // the bodies moved (not a world at rest compared with itself)
            assert!(ids.iter().any(|&v| batched.displacement(v).length() > 1e-4));
        }
    }

    #[test]
    fn free_voxels_of_one_material_go_in_fours_and_the_rest_alone() {
        let mut voxels: Vec<Voxel> = (0..11).map(|i| Voxel::new(i % 2, [i as i32, 0, 0], 0.01)).collect();
        voxels[4].fixed[2] = true;
        let plan = VoxelBatches::plan(&voxels, true);
        // material 0: 0 2 6 8 | 10 (4 is fixed); material 1: 1 3 5 7 | 9
        assert_eq!(plan.batches, vec![(0, [0, 2, 6, 8]), (1, [1, 3, 5, 7])]);
        assert_eq!(plan.single, vec![4, 10, 9]);
        let none = VoxelBatches::plan(&voxels, false);
        assert!(none.batches.is_empty() && none.single.len() == 11);
        assert_eq!(voxels[0].pos, DVec3::ZERO);
    }
}
