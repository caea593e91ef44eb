//! Errors on a wrong value name its field as data (a [`FieldError`]'s path), shown exactly as the
//! messages users already know.

use serde_json::json;
use vsrlab_tasks::{EpisodeError, EvaluationError, FieldError, Representation, TaskSpec};

/// The field error behind an episode error (a task's or a robot's field).
fn field(e: EpisodeError) -> FieldError {
    match e {
        EpisodeError::Field(f) => f,
        other => panic!("not a field error: {other}"),
    }
}

#[test]
fn task_settings_are_named_under_task() {
    let task = TaskSpec::default()
        .with_settings(&[("physics.dt", json!(0.0))])
        .unwrap();
    let e = field(task.task().validate().unwrap_err());
    assert_eq!(
        (e.path.as_str(), e.message.as_str()),
        ("task.physics.dt", "must be a positive number, got 0")
    );
    assert_eq!(e.to_string(), "task.physics.dt must be a positive number, got 0");

    let task = TaskSpec::default()
        .with_settings(&[("fitness", json!(["velocity", "height"]))])
        .unwrap();
    let e = field(task.task().validate().unwrap_err());
    assert_eq!(e.path, "task.fitness[1]");
    assert!(
        e.to_string().starts_with("task.fitness[1]: unknown metric 'height'"),
        "{e}"
    );
}

#[test]
fn representation_errors_are_rooted_at_representation() {
    let psa = |brain: serde_json::Value, sensors: Option<&str>| -> Representation {
        let mut table = json!({"body": {"kind": "psa", "size": "small"}, "brain": brain});
        if let Some(s) = sensors {
            table["sensors"] = json!(s);
        }
        serde_json::from_value(table).unwrap()
    };
    // the PSA robot's own check names `brain.linear_outputs`; the representation re-roots it
    let e = psa(json!({"kind": "heads", "linear_outputs": 0}), None)
        .validate()
        .unwrap_err();
    assert!(matches!(e, EvaluationError::Representation(_)), "{e:?}");
    assert!(
        e.to_string()
            .starts_with("representation.brain.linear_outputs: 0 with pressure control on"),
        "{e}"
    );
    assert_eq!(e.field_error().unwrap().path, "representation.brain.linear_outputs");

    let e = psa(json!({"kind": "heads"}), Some("uniform-a-0"))
        .validate()
        .unwrap_err();
    let f = e.field_error().unwrap();
    assert_eq!(f.path, "representation.sensors");
    assert!(f.message.starts_with("a PSA has its own sensors"), "{f}");
}

#[test]
fn a_bad_psa_table_names_its_constant_in_the_body() {
    let table = json!({"body": {"kind": "psa", "masses": 2}, "brain": {"kind": "heads"}});
    let e = serde_json::from_value::<Representation>(table).unwrap_err();
    assert!(e.to_string().contains("masses must be at least 3, got 2"), "{e}");
}

#[test]
fn a_voxel_robot_names_its_constant_or_brain_field() {
    use vsrlab_body::sensors::SensorConfig;
    use vsrlab_body::{Morphology, Preset, VoxelParams};
    use vsrlab_brain::BrainSpec;
    use vsrlab_tasks::RobotSpec;
    let robot = RobotSpec {
        body: Morphology::parse("biped-4x3").unwrap(),
        preset: Preset::Y2021,
        voxel: Some(VoxelParams {
            side_length: 0.0,
            ..VoxelParams::default()
        }),
        sensors: SensorConfig::parse("uniform-a+vxy+t-0").unwrap(),
        brain: BrainSpec::parse("phase").unwrap(),
    };
    let e = robot.validate().unwrap_err();
    assert_eq!(e.field, "voxel.side_length");
    assert_eq!(
        e.to_string(),
        "robot.voxel.side_length: must be a positive number, got 0"
    );
    let brain: BrainSpec =
        serde_json::from_value(json!({"kind": "distributed-mlp", "signals": 1, "hidden": [], "weights": [1.0]}))
            .unwrap();
    let e = RobotSpec {
        voxel: None,
        brain,
        ..robot
    }
    .validate()
    .unwrap_err();
    assert!(e.field.starts_with("brain."), "{e}");
    assert!(e.to_string().starts_with(&format!("robot.{}: ", e.field)), "{e}");
}
