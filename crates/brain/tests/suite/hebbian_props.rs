//! Property tests of the Hebbian controller: whatever the rules, the learning rate, the
//! normalisation and the readings, its actuations stay in [−1, 1] and its weights stay finite;
//! the update does not depend on anything but the rules and this step's activations.

use proptest::prelude::*;
use vsrlab_body::Morphology;
use vsrlab_brain::BrainShape;
use vsrlab_brain::{BrainKind, BrainSpec, HebbianModel, HebbianSpec, Normalisation};

fn spec(model: HebbianModel, normalisation: Normalisation, eta: f64, evolve_eta: bool) -> HebbianSpec {
    HebbianSpec {
        model,
        normalisation,
        eta,
        evolve_eta,
        ..HebbianSpec::default()
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_rules_and_readings_never_give_non_finite_state(
        model in prop_oneof![Just(HebbianModel::Full), Just(HebbianModel::Incoming), Just(HebbianModel::Dew)],
        l2 in any::<bool>(),
        evolve_eta in any::<bool>(),
        eta in 0.0f64..1.0,
        scale in prop_oneof![Just(1.0f64), Just(100.0f64)],
        seed in any::<u64>(),
        readings in proptest::collection::vec(-10.0f64..10.0, 8 * 50),
    ) {
        let evolve_eta = evolve_eta && model != HebbianModel::Dew;
        let normalisation = if l2 { Normalisation::L2 } else { Normalisation::None };
        let body = Morphology::named("worm-4x1").unwrap();
        let rpv = [2, 2, 2, 2];
        let template = BrainSpec::Hebbian(spec(model, normalisation, eta, evolve_eta));
        let n = template.parameter_count(&BrainShape::grid(&body, &rpv)).unwrap();
        let random = template.with_random_parameters(seed, &BrainShape::grid(&body, &rpv)).unwrap();
        let scaled: Vec<f64> = random.parameters().iter().map(|p| p * scale).collect();
        let brain = template.with_parameters(&scaled).unwrap();
        prop_assert_eq!(brain.parameters().len(), n);
        let mut c = brain.build(&BrainShape::grid(&body, &rpv)).unwrap();
        let mut a = [0.0; 4];
        // 50 distinct reading vectors, cycled for 2 000 steps (33 s)
        for k in 0..2000 {
            let r = &readings[(k % 50) * 8..(k % 50 + 1) * 8];
            c.control(k as f64 / 60.0, r, &mut a);
            prop_assert!(a.iter().all(|x| x.is_finite() && x.abs() <= 1.0), "step {}: {:?}", k, a);
        }
        if model == HebbianModel::Dew {
            prop_assert!(vsrlab_brain::plastic_weights(&c).is_none(), "fixed weights are not adaptive");
            return Ok(());
        }
        let w = vsrlab_brain::plastic_weights(&c).unwrap();
        prop_assert!(w.iter().all(|x| x.is_finite()));
        if l2 {
            // every neuron's incoming vector has unit norm (or is still all zero)
            let sizes = [8usize, 8, 4];
            let mut at = 0;
            for l in 0..2 {
                for _ in 0..sizes[l + 1] {
                    let row = &w[at..at + sizes[l] + 1];
                    let norm = row.iter().map(|x| x * x).sum::<f64>().sqrt();
                    prop_assert!(norm == 0.0 || (norm - 1.0).abs() < 1e-9, "norm {}", norm);
                    at += sizes[l] + 1;
                }
            }
        }
    }
}

#[test]
fn the_parameter_counts_follow_the_documented_formulas() {
    // sizes [n_in, n_in, n_voxels]: W = n_in·(n_in + 1) + n_voxels·(n_in + 1)
    let biped = Morphology::named("biped-4x3").unwrap();
    let worm = Morphology::named("worm-7x1").unwrap();
    let w = |n_in: usize, voxels: usize| n_in * (n_in + 1) + voxels * (n_in + 1);
    for (body, n_in) in [
        (&biped, 29usize),
        (&biped, 20),
        (&biped, 8),
        (&worm, 31),
        (&worm, 28),
        (&worm, 3),
    ] {
        let voxels = body.voxel_count();
        let mut rpv = vec![0; voxels];
        rpv[0] = n_in;
        let count = |s: &HebbianSpec| s.parameter_count(&BrainShape::grid(body, &rpv)).unwrap();
        assert_eq!(
            count(&spec(HebbianModel::Full, Normalisation::None, 0.01, false)),
            4 * w(n_in, voxels)
        );
        assert_eq!(
            count(&spec(HebbianModel::Full, Normalisation::None, 0.01, true)),
            5 * w(n_in, voxels)
        );
        assert_eq!(
            count(&spec(HebbianModel::Incoming, Normalisation::None, 0.01, false)),
            4 * (n_in + voxels)
        );
        assert_eq!(
            count(&spec(HebbianModel::Dew, Normalisation::None, 0.01, false)),
            w(n_in, voxels)
        );
    }
    // the thesis's worm with 3 inputs has a hidden layer of 3 neurons
    let worm_low = spec(HebbianModel::Full, Normalisation::None, 0.01, false);
    let mut rpv = vec![0; 7];
    rpv[2] = 1;
    rpv[3] = 1;
    rpv[4] = 1;
    assert_eq!(
        worm_low.parameter_count(&BrainShape::grid(&worm, &rpv)).unwrap(),
        4 * (3 * 4 + 7 * 4)
    );
}
