//! Pressure-based soft agents in experiment files (thesis ch. 6): a CMA-ES run on the escape task
//! writes a PSA robot file that replays to its recorded fitness, whatever the thread count; bad
//! PSA tables are refused naming the field.

use std::path::Path;
use vsrlab_experiment::config::{self, Experiment};
use vsrlab_tasks::files::load_any_robot;
use vsrlab_tasks::{episode, PsaRobot, TraceLevel};

fn experiment(body: &str, brain: &str, extra: &str) -> Result<Experiment, String> {
    let text = format!(
        r#"
runs = 1
seed = 3
[representation]
body = {body}
brain = {brain}
{extra}
[task]
kind = "escape"
side = 15.0
duration = 3.0
[optimizer]
kind = "cma-es"
population_size = 6
[stop]
evaluations = 18
"#
    );
    config::parse(&text, "psa.toml").map_err(|e| e.to_string())
}

use crate::common::run_on_threads as run;

#[test]
fn a_psa_run_writes_a_robot_that_replays_to_its_fitness_on_any_thread_count() {
    let e = experiment(r#"{ kind = "psa", size = "small" }"#, r#"{ kind = "heads" }"#, "").unwrap();
    let (one, two) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    run(&e, one.path(), 1);
    run(&e, two.path(), 2);
    let read = |dir: &Path, file: &str| std::fs::read_to_string(dir.join("run-00").join(file)).unwrap();
    assert_eq!(read(one.path(), "generations.csv"), read(two.path(), "generations.csv"));
    let robot = load_any_robot(&one.path().join("run-00/best.robot.json")).unwrap();
    let psa = robot.downcast_ref::<PsaRobot>().expect("expected a PSA robot file");
    assert_eq!(psa.brain.parameters().len(), 374);
    let outcome = episode::run(robot.as_robot(), e.task.spec.task(), 0, TraceLevel::None).unwrap();
    let best: f64 = read(one.path(), "generations.csv")
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(str::trim)
        .filter_map(|x| x.parse::<f64>().ok())
        .find(|v| (v - outcome.fitness[0]).abs() < 1e-12)
        .expect("the replayed fitness is the run's best");
    assert!(best.is_finite());
}

#[test]
fn bad_psa_tables_name_their_field() {
    let cases = [
        (
            r#"{ kind = "psa", masses = 2 }"#,
            r#"{ kind = "heads" }"#,
            "",
            "masses must be at least 3",
        ),
        (
            r#"{ kind = "psa", radius = -1.0 }"#,
            r#"{ kind = "heads" }"#,
            "",
            "radius must be finite and > 0",
        ),
        (
            r#"{ kind = "psa", gas_mass = -1.0 }"#,
            r#"{ kind = "heads" }"#,
            "",
            "gas_mass",
        ),
        (
            r#"{ kind = "psa", min_pressure_fraction = 2.0 }"#,
            r#"{ kind = "heads" }"#,
            "",
            "p_min ≤ p_max",
        ),
        (
            r#"{ kind = "psa", radios = 3 }"#,
            r#"{ kind = "heads" }"#,
            "",
            "representation.body.radios",
        ),
        (
            r#"{ kind = "psa" }"#,
            r#"{ kind = "heads" }"#,
            r#"sensors = "uniform-t-0""#,
            "representation.sensors",
        ),
        (
            r#"{ kind = "psa", pressure_control = false }"#,
            r#"{ kind = "heads" }"#,
            "",
            "representation.brain.linear_outputs",
        ),
        (
            r#"{ kind = "psa" }"#,
            r#"{ kind = "mlp", hidden = [0] }"#,
            "",
            "representation.brain.hidden",
        ),
    ];
    for (body, brain, extra, expected) in cases {
        let err = match experiment(body, brain, extra) {
            Ok(e) => {
                let vsrlab_experiment::optimizers::FieldError {
                    path: field, message, ..
                } = e.validate().unwrap_err();
                format!("{field}: {message}")
            }
            Err(e) => e,
        };
        assert!(err.contains(expected), "{body} {brain} {extra}: {err}");
    }
}
