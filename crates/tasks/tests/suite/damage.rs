//! Mid-episode damage: broken voxels stop actuating at the damage time, never before, the same
//! voxels for the same seed, with any brain.

use vsrlab_tasks::episode::{self, run_observed};
use vsrlab_tasks::{Damage, Locomotion, RobotSpec, TraceLevel};

fn task(damage: Option<Damage>) -> Locomotion {
    Locomotion {
        duration: 3.0,
        damage,
        ..Locomotion::default()
    }
}

/// Per step, the actuation of every voxel (10 voxels of a biped).
fn actuations(robot: &RobotSpec, task: &Locomotion, seed: u64) -> Vec<Vec<f64>> {
    let trace = episode::run(robot, task, seed, TraceLevel::Full)
        .unwrap()
        .trace
        .unwrap();
    trace.values("actuation").chunks(10).map(<[f64]>::to_vec).collect()
}

#[test]
fn broken_voxels_stop_at_the_damage_time_and_not_before() {
    let damage = Damage {
        at: 1.0,
        probability: 0.5,
    };
    let mask = damage.mask(10, 4);
    assert!(mask.iter().any(|&b| b) && mask.iter().any(|&b| !b), "{mask:?}");
    for brain in ["phase", "mlp", "hebbian"] {
        let robot = RobotSpec::from_short_forms("biped-4x3", "2021", "uniform-a+vxy+t-0", brain).unwrap();
        let intact = actuations(&robot, &task(None), 4);
        let damaged = actuations(&robot, &task(Some(damage)), 4);
        // t = (k + 1)/60: the steps before t = 1 s are untouched
        for k in 0..59 {
            assert_eq!(intact[k], damaged[k], "{brain}: step {k} changed before the damage");
        }
        for step in &damaged[59..] {
            for (v, a) in step.iter().enumerate() {
                if mask[v] {
                    assert_eq!(*a, 0.0, "{brain}: broken voxel {v} actuates");
                }
            }
        }
        let moving = damaged[59..].iter().any(|s| (0..10).any(|v| !mask[v] && s[v] != 0.0));
        assert!(moving, "{brain}: intact voxels still actuate");
        assert_eq!(
            damaged,
            actuations(&robot, &task(Some(damage)), 4),
            "{brain}: not deterministic"
        );
    }
}

#[test]
fn damage_at_the_end_or_with_probability_zero_changes_nothing() {
    let robot = RobotSpec::from_short_forms("biped-4x3", "2021", "uniform-a+vxy+t-0", "mlp").unwrap();
    let plain = episode::run(&robot, &task(None), 2, TraceLevel::None).unwrap();
    for damage in [
        Damage {
            at: 10.0,
            probability: 1.0,
        },
        Damage {
            at: 0.0,
            probability: 0.0,
        },
    ] {
        let out = episode::run(&robot, &task(Some(damage)), 2, TraceLevel::None).unwrap();
        assert_eq!(out.fitness, plain.fitness, "{damage:?}");
    }
}

#[test]
fn the_observer_sees_every_step_and_the_hebbian_weights_move() {
    let robot = RobotSpec::from_short_forms("biped-4x3", "2021", "uniform-a+vxy+t-0", "hebbian").unwrap();
    let mut seen = Vec::new();
    let out = run_observed(&robot, &task(None), 0, TraceLevel::None, &mut |t, agent| {
        let w = agent
            .brain()
            .and_then(vsrlab_brain::plastic_weights)
            .expect("a hebbian brain has plastic weights");
        seen.push((t, w.iter().map(|x| x.abs()).sum::<f64>()));
    })
    .unwrap();
    assert_eq!(seen.len() as u64, out.steps);
    assert!(seen[seen.len() - 1].1 > 0.0, "weights start at 0 and must move");
    assert_eq!(
        episode::run(&robot, &task(None), 0, TraceLevel::None).unwrap().fitness,
        out.fitness
    );
}

#[test]
fn a_bad_damage_is_refused_naming_the_field() {
    let robot = RobotSpec::from_short_forms("biped-4x3", "2021", "uniform-a+vxy+t-0", "phase").unwrap();
    let err = episode::run(
        &robot,
        &task(Some(Damage {
            at: 1.0,
            probability: 2.0,
        })),
        0,
        TraceLevel::None,
    )
    .unwrap_err();
    assert!(err.to_string().contains("task.damage.probability"), "{err}");
    let toml_err = serde_json::from_str::<Locomotion>(r#"{"damage": {"at": 30, "p": 0.5}}"#).unwrap_err();
    assert!(toml_err.to_string().contains("p"), "{toml_err}");
}

mod random {
    use proptest::prelude::*;
    use vsrlab_tasks::{episode, Damage, Locomotion, RobotSpec, Terrain, TraceLevel};

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(12))]

        /// Random Hebbian rules (scaled up to 100), random bodies, sensors, terrains and damage:
        /// the episode stays finite.
        #[test]
        fn hebbian_robots_with_damage_stay_finite(
            body in prop_oneof![Just("biped-4x3"), Just("worm-7x1"), Just("comb-7x2"), Just("box-3x3")],
            sensors in prop_oneof![Just("high_biped-0.01-f"), Just("low_worm-0-t"), Just("uniform-a+vxy+t-0.01")],
            brain in prop_oneof![Just("hebbian"), Just("hebbian:l2"), Just("hebbian:incoming"), Just("hebbian:dew")],
            scale in prop_oneof![Just(1.0f64), Just(100.0f64)],
            seed in 0u64..1000,
            at in 0.0f64..20.0,
            probability in 0.0f64..=1.0,
        ) {
            let mut robot = RobotSpec::from_short_forms(body, "2021", sensors, brain).unwrap();
            let scaled: Vec<f64> = robot.brain.parameters().iter().map(|p| p * scale).collect();
            robot.brain = robot.brain.with_parameters(&scaled).unwrap();
            let task = Locomotion {
                duration: 20.0,
                terrain: "hilly-3-30".parse::<Terrain>().unwrap(),
                damage: Some(Damage { at, probability }),
                ..Locomotion::default()
            };
            let out = episode::run(&robot, &task, seed, TraceLevel::Full).unwrap();
            prop_assert!(out.fitness.iter().all(|f| f.is_finite()));
            let trace = out.trace.unwrap();
            prop_assert!(trace.outlines.iter().all(|p| p.is_finite()));
            prop_assert!(trace.values("actuation").iter().all(|a| a.is_finite() && a.abs() <= 1.0));
        }
    }
}
