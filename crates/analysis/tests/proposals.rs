//! The labelling page's rule-of-thumb classes on real robots: the shipped evolved biped walks
//! with its feet planted (a footprint touch area above 0, which the contact flags alone gave as 0),
//! is "limbed", not "elongated", and "walking", not "jumping".

use vsrlab_analysis::diversity::{propose_behaviour, propose_shape};
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::morphology::MorphologyDescriptors;
use vsrlab_tasks::{Robot, Task, TaskSpec, Trace, TraceLevel};

/// The full trace of one episode.
fn replay(robot: &dyn Robot, task: &dyn Task, seed: u64, level: TraceLevel) -> Option<Trace> {
    vsrlab_tasks::episode::run(robot, task, seed, level).ok()?.trace
}

#[test]
fn the_evolved_biped_is_a_planted_walker() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/biped-distributed.robot.json"
    );
    let robot = vsrlab_tasks::files::load_robot(path.as_ref()).unwrap();
    let task = TaskSpec::parse("locomotion:flat")
        .unwrap()
        .with_settings(&[("duration", serde_json::json!(20.0))])
        .unwrap();
    let trace = replay(&robot, task.task(), 0, TraceLevel::Full).unwrap();
    let f = RobotFeatures::from_trace(&trace, &FeatureParams::default());
    let d = MorphologyDescriptors::of(&robot.body);
    assert!(f.gait.touch_area > 0.0, "feet are planted: {:?}", f.gait);
    assert!(f.airborne < 0.15, "{}", f.airborne);
    assert_eq!(propose_shape(&d), "limbed");
    assert_eq!(propose_behaviour(&f), "walking");
}

#[test]
fn a_biped_that_stays_in_place_is_not_walking() {
    let robot = vsrlab_tasks::RobotSpec::from_short_forms("biped-4x3", "2021", "uniform-a+t-0", "constant:0").unwrap();
    let task = TaskSpec::parse("locomotion:flat")
        .unwrap()
        .with_settings(&[("duration", serde_json::json!(10.0))])
        .unwrap();
    let trace = replay(&robot, task.task(), 0, TraceLevel::Full).unwrap();
    let f = RobotFeatures::from_trace(&trace, &FeatureParams::default());
    assert!(f.displacement.abs() < 0.5, "{}", f.displacement);
    assert_eq!(propose_behaviour(&f), "other");
}
