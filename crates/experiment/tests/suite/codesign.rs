//! Property: whatever the body and however wild the policy, a co-design evaluation never yields a
//! non-finite number. Random material grids (with or without actuators, in pieces or whole) on
//! every EvoGym task, PPO with a random seed and an initial spread of actions up to e² ≈ 7.4 (far
//! outside EvoGym's [0.6, 1.6]): each evaluation either fails with a reason, or gives a finite
//! fitness, learning curve and training rewards, and its saved robot replays to finite numbers.

use proptest::prelude::*;
use vsrlab_experiment::codesign::{kept_body, learn, learned_robot, Episode, LearnError};
use vsrlab_learning::{PpoConfig, PpoError};
use vsrlab_tasks::kinds::evogym::{EvoGymTask, Material};

const TASKS: [EvoGymTask; 4] = [
    EvoGymTask::Walker,
    EvoGymTask::BridgeWalker,
    EvoGymTask::BeamToppler,
    EvoGymTask::CaveCrawler,
];

fn material(code: u8) -> Material {
    Material::from_code(u64::from(code)).expect("codes 0-4")
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]

    #[test]
    fn evaluations_are_finite_or_fail_with_a_reason(
        side in 2usize..=5,
        codes in proptest::collection::vec(0u8..5, 25),
        task in 0usize..4,
        seed in any::<u64>(),
        log_std in -2.0f64..2.0,
    ) {
        let cells: Vec<Material> = codes[..side * side].iter().map(|&c| material(c)).collect();
        let Ok(body) = kept_body(side, side, cells) else {
            // nothing present or no actuator: refused before any simulation
            return Ok(());
        };
        let episode = Episode { task: TASKS[task], steps: 30 };
        let ppo = PpoConfig {
            iterations: 2,
            environments: 2,
            steps_per_environment: 20,
            hidden: vec![8],
            initial_log_std: log_std,
            ..PpoConfig::default()
        };
        match learn(&body, episode, &ppo, true, seed) {
            // a failure is the simulation's report (a step refused, a value not finite), never
            // settings or sizes that the training should have accepted
            Err(reason) => prop_assert!(
                matches!(
                    reason,
                    LearnError::Environment(_) | LearnError::Ppo(PpoError::Step { .. } | PpoError::NonFinite(_))
                ),
                "{}",
                reason
            ),
            Ok(learned) => {
                prop_assert!(learned.fitness.is_finite());
                prop_assert_eq!(learned.curve.len(), 3);
                prop_assert!(learned.curve.iter().chain(&learned.training).all(|r| r.is_finite()));
                let robot = learned_robot(&body, episode, &learned.ppo);
                prop_assert!(robot.brain.as_kind().parameters().iter().all(|w| w.is_finite()));
                prop_assert!(robot.validate().is_ok());
            }
        }
    }
}
