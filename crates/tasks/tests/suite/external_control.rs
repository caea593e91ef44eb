//! The step-at-a-time episode ([`Episode`]) driven by a controller outside the robot: it is the
//! episode loop of `episode::run`, so outside actions equal to the brain's give the same outcome
//! bit for bit, and bad actions are refused.

use vsrlab_tasks::kinds::voxel::short_forms::DEFAULT_SENSORS;
use vsrlab_tasks::{episode, Episode, PsaRobot, Robot, RobotSpec, TaskSpec, TraceLevel};

fn task(text: &str, duration: f64) -> TaskSpec {
    TaskSpec::parse(text)
        .unwrap()
        .with_settings(&[("duration", serde_json::json!(duration))])
        .unwrap()
}

/// Runs `robot` once with its own brain, once with outside actions always equal to `value` (the
/// first step with the brain: its actuation only takes effect after the first physics step).
fn both_ways(robot: &dyn Robot, task: &TaskSpec, value: f64) -> (vsrlab_tasks::Outcome, vsrlab_tasks::Outcome) {
    let inside = episode::run(robot, task.task(), 4, TraceLevel::None).unwrap();
    let mut outside = Episode::new(robot, task.task().rigid().unwrap(), 4, TraceLevel::None).unwrap();
    outside.step(None).unwrap();
    let actions = vec![value; outside.agent().action_count()];
    while !outside.is_over() {
        outside.step(Some(&actions)).unwrap();
    }
    (inside, outside.finish())
}

#[test]
fn outside_actions_equal_to_the_brain_give_the_same_voxel_episode() {
    let robot = RobotSpec::from_short_forms("biped-4x3", "2021", DEFAULT_SENSORS, "constant:0.7").unwrap();
    let (inside, outside) = both_ways(&robot, &task("locomotion:hilly-1-10", 3.0), 0.7);
    assert_eq!(inside.steps, outside.steps);
    assert_eq!(inside.metrics, outside.metrics);
    assert!(inside.metrics["distance"].abs() > 0.0);
}

/// A PSA driven from outside: repeatable, and its actions matter (with controlled pressure an
/// actuation adds Δp, so the brain-equivalence above does not hold for the doubled first step).
#[test]
fn an_outside_driven_psa_is_repeatable_and_follows_its_actions() {
    let robot = PsaRobot::from_short_forms("psa:small", "constant:0").unwrap();
    let spec = task("locomotion:flat", 2.0);
    let drive = |value: f64| {
        let mut e = Episode::new(&robot, spec.task().rigid().unwrap(), 4, TraceLevel::None).unwrap();
        let actions = vec![value; e.agent().action_count()];
        while !e.is_over() {
            e.step(Some(&actions)).unwrap();
        }
        e.finish().metrics
    };
    assert_eq!(drive(0.3), drive(0.3));
    assert_ne!(drive(0.3)["distance"], drive(-0.3)["distance"]);
}

#[test]
fn other_actions_give_another_episode_and_readings_follow_the_world() {
    let robot = RobotSpec::from_short_forms("biped-4x3", "2021", DEFAULT_SENSORS, "constant:0").unwrap();
    let spec = task("locomotion:flat", 2.0);
    let mut e = Episode::new(&robot, spec.task().rigid().unwrap(), 0, TraceLevel::None).unwrap();
    e.sense();
    let first = e.agent().readings().to_vec();
    assert!(!first.is_empty());
    let n = e.agent().action_count();
    assert_eq!(n, 10, "a 4x3 biped has 10 voxels");
    let mut k = 0;
    while !e.is_over() {
        let a: Vec<f64> = (0..n).map(|i| ((k + i) as f64 * 0.3).sin()).collect();
        e.step(Some(&a)).unwrap();
        k += 1;
    }
    assert_ne!(e.agent().readings(), first.as_slice());
    let driven = e.finish();
    let still = episode::run(&robot, spec.task(), 0, TraceLevel::None).unwrap();
    assert_ne!(driven.metrics["distance"], still.metrics["distance"]);
}

#[test]
fn actions_of_the_wrong_length_are_refused_with_the_counts() {
    let robot = RobotSpec::from_short_forms("biped-4x3", "2021", DEFAULT_SENSORS, "phase").unwrap();
    let spec = task("locomotion:flat", 1.0);
    let mut e = Episode::new(&robot, spec.task().rigid().unwrap(), 0, TraceLevel::None).unwrap();
    let err = e.step(Some(&[0.0; 3])).unwrap_err().to_string();
    assert!(
        err.contains("actions: 3 values") && err.contains("10 actuators"),
        "{err}"
    );
}
