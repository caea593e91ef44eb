//! Physical invariants of assembled robots, checked on random bodies and actuations (proptest).

use proptest::prelude::*;
use vsrlab_body::{Morphology, Preset, VoxelParams, Vsr};
use vsrlab_physics::{Vec2, World, WorldBuilder, WorldSettings};

fn body_strategy() -> impl Strategy<Value = Morphology> {
    (1usize..=5, 1usize..=5, proptest::collection::vec(any::<bool>(), 25))
        .prop_filter_map("connected", |(w, h, bits)| {
            Morphology::from_fn(w, h, |x, y| bits[y * 5 + x] || (x == 0 && y == 0)).ok()
        })
}

fn floating_world(m: &Morphology, preset: Preset) -> (World, Vsr) {
    let settings = WorldSettings {
        gravity: Vec2::ZERO,
        ..Default::default()
    };
    let mut params = VoxelParams::preset(preset);
    params.linear_damping = 0.0;
    params.angular_damping = 0.0;
    let mut b = WorldBuilder::new(settings);
    let vsr = Vsr::assemble(&mut b, m, &params, Vec2::new(0.0, 0.0), 1);
    (b.build().unwrap(), vsr)
}

fn momentum(w: &World, vsr: &Vsr) -> Vec2 {
    // every voxel has the same mass, so the mean voxel velocity is proportional to momentum
    (0..vsr.voxel_count()).fold(Vec2::ZERO, |acc, i| acc + vsr.voxel_state(w, i).velocity)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// With no gravity, damping or ground, internal springs cannot move the centre of mass.
    #[test]
    fn internal_forces_conserve_momentum_and_centre(m in body_strategy(), acts in proptest::collection::vec(-1.0f64..1.0, 50), preset in prop_oneof![Just(Preset::Y2021), Just(Preset::Y2022)]) {
        let (mut w, vsr) = floating_world(&m, preset);
        let c0 = vsr.center(&w);
        let mut values = vec![0.0; vsr.voxel_count()];
        for (k, a) in acts.iter().enumerate() {
            for (i, v) in values.iter_mut().enumerate() {
                *v = if (i + k) % 2 == 0 { *a } else { -*a };
            }
            vsr.actuate(&mut w, &values);
            w.step().unwrap();
        }
        let p = momentum(&w, &vsr);
        prop_assert!(p.length() < 1e-9 * vsr.voxel_count() as f64, "momentum drift {p:?}");
        // the voxel centre mean equals the mass centre for equal-mass voxels... up to corner
        // squares shared at welded vertices, which are rigid: allow tiny numerical drift
        let c1 = vsr.center(&w);
        prop_assert!((c1 - c0).length() < 1e-6, "centre moved from {c0:?} to {c1:?}");
    }

    /// Mass is the voxel mass times the number of voxels, whatever the shape.
    #[test]
    fn mass_is_conserved_by_assembly(m in body_strategy(), preset in prop_oneof![Just(Preset::Y2021), Just(Preset::Y2022)]) {
        let (w, vsr) = floating_world(&m, preset);
        let expected = VoxelParams::preset(preset).voxel_mass * vsr.voxel_count() as f64;
        prop_assert!((w.total_mass() - expected).abs() < 1e-9 * expected);
    }

    /// A passive body left alone in zero gravity stays at rest (no spurious energy).
    #[test]
    fn passive_bodies_stay_at_rest(m in body_strategy()) {
        let (mut w, vsr) = floating_world(&m, Preset::Y2021);
        for _ in 0..120 {
            w.step().unwrap();
        }
        prop_assert!(w.kinetic_energy() < 1e-12, "kinetic energy {}", w.kinetic_energy());
        for i in 0..vsr.voxel_count() {
            prop_assert!((vsr.voxel_state(&w, i).area_ratio - 1.0).abs() < 1e-9);
        }
    }
}
