//! Property test of the attention controller: whatever the genes and the readings, its actuations
//! stay in [−1, 1] and its attention matrices in [−1, 1] (plain) or finite (slow: α·A + η·A′ is a
//! sum of bounded terms, at most 1/(1 − η) with η < 1, growing linearly when η = 1).

use proptest::prelude::*;
use vsrlab_body::Morphology;
use vsrlab_brain::BrainShape;
use vsrlab_brain::BrainSpec;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_genes_and_readings_never_give_non_finite_state(
        form in prop_oneof![Just("attention"), Just("attention:hetero"), Just("attention:slow"), Just("attention:2"), Just("local-mlp:1")],
        body in prop_oneof![Just("biped-4x3"), Just("comb-7x2"), Just("worm-3x1")],
        scale in prop_oneof![Just(1.0f64), Just(1000.0f64)],
        seed in any::<u64>(),
        readings in proptest::collection::vec(-100.0f64..100.0, 4 * 11 * 20),
    ) {
        let m = Morphology::named(body).unwrap();
        let n = m.voxel_count();
        let rpv = vec![4; n];
        let random = BrainSpec::parse(form).unwrap().with_random_parameters(seed, &BrainShape::grid(&m, &rpv)).unwrap();
        let scaled: Vec<f64> = random.parameters().iter().map(|p| p * scale).collect();
        let mut c = random.with_parameters(&scaled).unwrap().build(&BrainShape::grid(&m, &rpv)).unwrap();
        let mut a = vec![0.0; n];
        for k in 0..1000 {
            let start = (k % 20) * 44;
            c.control(k as f64 / 60.0, &readings[start..start + 4 * n], &mut a);
            prop_assert!(a.iter().all(|x| x.is_finite() && x.abs() <= 1.0), "step {}: {:?}", k, a);
        }
        if let Some((side, matrices)) = vsrlab_brain::controllers::attention::attention_matrices(&c) {
            prop_assert_eq!(side, 4);
            prop_assert_eq!(matrices.len(), n * 16);
            prop_assert!(matrices.iter().all(|x| x.is_finite()));
            if form != "attention:slow" {
                prop_assert!(matrices.iter().all(|x| x.abs() <= 1.0));
            }
        }
    }
}
