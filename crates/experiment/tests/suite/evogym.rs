//! EvoGym robots in experiment files (issue 33): a GA run on Walker-v0 evolves a brain for a
//! fixed material grid and writes an EvoGym robot file that replays to its recorded fitness,
//! whatever the thread count; bad EvoGym tables are refused naming the field.

use std::path::Path;
use vsrlab_experiment::config::{self, Experiment};
use vsrlab_tasks::files::load_any_robot;
use vsrlab_tasks::kinds::evogym::EvoGymRobot;
use vsrlab_tasks::{episode, TraceLevel};

fn experiment(body: &str) -> Result<Experiment, String> {
    let text = format!(
        r#"
runs = 1
seed = 5
[representation]
body = {body}
brain = {{ kind = "mlp", hidden = [] }}
[task]
kind = "evogym"
env = "Walker-v0"
duration = 0.3
[optimizer]
kind = "ga"
population_size = 6
offspring_size = 6
[stop]
evaluations = 18
"#
    );
    config::parse(&text, "evogym.toml").map_err(|e| e.to_string())
}

use crate::common::run_on_threads as run;

#[test]
fn an_evogym_run_writes_a_robot_that_replays_to_its_fitness_on_any_thread_count() {
    let e = experiment(r#"{ kind = "evogym", body = "131" }"#).unwrap();
    let (one, two) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    run(&e, one.path(), 1);
    run(&e, two.path(), 2);
    let read = |dir: &Path, file: &str| std::fs::read_to_string(dir.join("run-00").join(file)).unwrap();
    assert_eq!(read(one.path(), "generations.csv"), read(two.path(), "generations.csv"));
    let robot = load_any_robot(&one.path().join("run-00/best.robot.json")).unwrap();
    let evogym = robot
        .downcast_ref::<EvoGymRobot>()
        .expect("expected an EvoGym robot file");
    // Walker's observation of a 3-voxel robot: 2 + 2·8 values, one actuator: (18 + 1)·1 weights
    assert_eq!(evogym.brain.parameters().len(), 19);
    let outcome = episode::run(robot.as_robot(), e.task.spec.task(), 0, TraceLevel::None).unwrap();
    let best: f64 = read(one.path(), "generations.csv")
        .lines()
        .last()
        .and_then(|l| l.split(',').nth(4))
        .and_then(|v| v.parse().ok())
        .unwrap();
    assert_eq!(
        outcome.fitness[0], best,
        "the robot file replays to the logged best fitness"
    );
    assert_eq!(outcome.metrics["steps"], 100.0);
}

#[test]
fn bad_evogym_tables_are_refused_naming_the_field() {
    for (body, field) in [
        (r#"{ kind = "evogym", body = "1.3" }"#, "representation.body"),
        (r#"{ kind = "evogym", body = "12" }"#, "representation.body"),
        (
            r#"{ kind = "evogym", body = "131", env = "Runner-v0" }"#,
            "representation.body",
        ),
        (r#"{ kind = "evogym", body = "131", size = 3 }"#, "representation.body"),
    ] {
        let err = experiment(body).unwrap_err();
        assert!(err.contains(field), "{body}: {err}");
    }
}
