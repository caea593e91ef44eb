//! The runner end to end on tiny experiments with real robots (short episodes, small
//! populations): thread count does not change results; an interrupted then resumed run ends
//! with the same files as an uninterrupted one; failed evaluations are counted, not fatal.

use crate::common;

use common::Killer;
use std::path::Path;
use vsrlab_evolution::Sense;
use vsrlab_experiment::config::{self, Experiment};
use vsrlab_experiment::evaluator::{Evaluated, Evaluator, EvaluatorError, Record, RobotEvaluator};
use vsrlab_experiment::genotypes::vector::run_vectors;
use vsrlab_experiment::optimizers::AnyOptimizer;
use vsrlab_experiment::runner::{run_dir, run_search, Observer, Plan, RunError, RunOptions, Silent};

/// The brain of the tiny experiments.
const BRAIN: &str = r#"{ kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }"#;

/// A tiny experiment: fixed 3×2 body, homogeneous distributed MLP, 2 s episodes.
fn tiny(optimizer: &str, stop: &str) -> Experiment {
    let text = format!(
        r####"
runs = 2
seed = 11

[representation]
body = "###/#.#"
sensors = "uniform-vxy+a+t-0"
brain = {BRAIN}

[task]
terrain = "flat"
duration = 2.0

[optimizer]
{optimizer}

[stop]
{stop}

[output]
snapshot_every = 20
"####
    );
    config::parse(&text, "tiny.toml").unwrap()
}

use crate::common::run_on_threads as run;

#[test]
fn thread_count_does_not_change_results() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 8\noffspring_size = 8",
        "generations = 4",
    );
    let dir = tempfile::tempdir().unwrap();
    let (one, two) = (dir.path().join("one"), dir.path().join("two"));
    run(&experiment, &one, 1);
    run(&experiment, &two, 2);
    let (a, b) = (files_of(&one), files_of(&two));
    let names: Vec<&str> = a.iter().map(|(n, _)| n.as_str()).collect();
    for expected in [
        "experiment.toml",
        "run-00/generations.csv",
        "run-00/best.robot.json",
        "run-00/snapshots/evaluations-0000024.jsonl",
        "run-01/generations.csv",
    ] {
        assert!(names.contains(&expected), "{expected} missing from {names:?}");
    }
    assert!(
        !names.iter().any(|n| n.ends_with("checkpoint.json")),
        "finished runs drop checkpoints"
    );
    assert_eq!(a, b, "1 thread and 2 threads must give identical files");
    // The two runs differ (different derived seeds).
    let csv = |run: &str| {
        a.iter()
            .find(|(n, _)| n == &format!("{run}/generations.csv"))
            .map(|(_, bytes)| String::from_utf8(bytes.clone()).unwrap())
            .unwrap()
    };
    assert_ne!(csv("run-00"), csv("run-01"));
    // Header + one row per generation; timings and summaries exist.
    assert_eq!(csv("run-00").lines().count(), 5);
    assert!(one.join("run-00/timings.csv").exists() && one.join("summary.json").exists());
    // The best robot is a valid robot file.
    vsrlab_tasks::files::load_robot(&one.join("run-00/best.robot.json")).unwrap();
}

#[test]
fn resumed_runs_end_like_uninterrupted_ones() {
    for optimizer in [
        "kind = \"ga\"\npopulation_size = 6\noffspring_size = 6",
        "kind = \"se\"\nfeatures = \"shape\"\npopulation_size = 8\nspecies = 3",
        "kind = \"map-elites\"\ninitial_population = 6\nbatch_size = 4",
        "kind = \"es\"\npopulation_size = 6",
    ] {
        let experiment = tiny(optimizer, "evaluations = 30");
        let evaluator = RobotEvaluator::new(&experiment).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let (straight, resumed) = (dir.path().join("straight"), dir.path().join("resumed"));
        run(&experiment, &straight, 2);
        // Kill run 1 after its 2nd generation, then run 0 is done and run 1 has a checkpoint.
        let options = common::two_threads(false);
        let done = run_vectors(
            &experiment,
            &evaluator,
            &resumed,
            &options,
            &mut Killer { run: 1, after: 2 },
        )
        .unwrap();
        assert_eq!(done.len(), 1);
        let run1 = run_dir(&resumed, 1, 2);
        assert!(run1.join("checkpoint.json").exists());
        assert!(!run1.join("summary.json").exists());
        // Without --resume the folder is refused.
        let again = run_vectors(&experiment, &evaluator, &resumed, &options, &mut Silent);
        assert!(again.unwrap_err().to_string().contains("--resume"));
        // A stale extra CSV row (killed after writing it, before the checkpoint) is dropped.
        let csv = run1.join("generations.csv");
        let mut text = std::fs::read_to_string(&csv).unwrap();
        text.push_str("999,garbage\n");
        std::fs::write(&csv, text).unwrap();
        let options = RunOptions {
            threads: 1,
            resume: true,
            ..RunOptions::default()
        };
        let summaries = run_vectors(&experiment, &evaluator, &resumed, &options, &mut Silent).unwrap();
        assert_eq!(summaries.len(), 2);
        assert_eq!(
            files_of(&straight),
            files_of(&resumed),
            "resumed run differs ({optimizer})"
        );
    }
}

/// A folder that holds an experiment is refused without `--resume`, and one written by another
/// configuration even with it; the error carries the folder as a path, not inside its text.
#[test]
fn resuming_with_another_configuration_is_refused() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 4\noffspring_size = 4",
        "generations = 1",
    );
    let dir = tempfile::tempdir().unwrap();
    run(&experiment, dir.path(), 1);
    let refused = |experiment: &Experiment, resume: bool| {
        let evaluator = RobotEvaluator::new(experiment).unwrap();
        let options = RunOptions {
            threads: 1,
            resume,
            ..RunOptions::default()
        };
        match run_vectors(experiment, &evaluator, dir.path(), &options, &mut Silent) {
            Err(RunError::Folder { file, problem }) => (file, problem),
            other => panic!("expected a refused folder, got {other:?}"),
        }
    };
    let (file, problem) = refused(&experiment, false);
    assert_eq!(file, dir.path());
    assert!(problem.contains("--resume"), "{problem}");
    let other = tiny(
        "kind = \"ga\"\npopulation_size = 5\noffspring_size = 4",
        "generations = 1",
    );
    let (file, problem) = refused(&other, true);
    assert_eq!(file, dir.path());
    assert!(problem.contains("different experiment configuration"), "{problem}");
}

/// Fails every genotype whose first gene is negative, panics when the second is ≥ 0.9;
/// fitness = −Σx² otherwise.
struct Flaky;

impl Evaluator<Vec<f64>> for Flaky {
    fn evaluate(&self, genotype: &Vec<f64>, seed: u64) -> Evaluated {
        assert!(genotype[1] < 0.9, "gene 1 too large");
        let ok = genotype[0] >= 0.0;
        let fitness = if ok {
            -genotype.iter().map(|x| x * x).sum::<f64>()
        } else {
            f64::NAN
        };
        Evaluated {
            objectives: vec![fitness],
            descriptor: vec![],
            features: vec![],
            record: Record {
                seed,
                fitness: ok.then_some(fitness),
                distance: None,
                velocity: None,
                voxels: None,
                body: None,
                error: (!ok).then(|| "negative first gene".to_string()),
                objectives: None,
                series: Default::default(),
            },
            seconds: 0.0,
        }
    }
}

#[test]
fn failed_and_panicking_evaluations_get_the_worst_fitness_and_are_counted() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 20\noffspring_size = 20",
        "generations = 15",
    );
    let dir = tempfile::tempdir().unwrap();
    let options = common::two_threads(false);
    // three genes, whatever the representation says: the optimizer comes from the plan's kind
    let new_optimizer = |seed: u64| -> Result<AnyOptimizer, RunError> {
        Ok(experiment.optimizer.kind().build(3, &[Sense::Maximize], seed)?)
    };
    let summaries = run_search(
        &Plan::of(&experiment),
        &new_optimizer,
        &Flaky,
        dir.path(),
        &options,
        &mut Silent,
    )
    .unwrap();
    let s = &summaries[0];
    assert!(s.failures > 0 && s.generations == 15);
    let best = s.best_fitness.unwrap();
    assert!(best > -1.0, "GA improves despite failures: {best}");
    let csv = std::fs::read_to_string(dir.path().join("run-00/generations.csv")).unwrap();
    let first: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    assert!(first[3].parse::<u64>().unwrap() > 0, "failures column: {csv}");
    let failures: u64 = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).unwrap().parse::<u64>().unwrap())
        .sum();
    assert_eq!(failures, s.failures);
    // Survivors are never failed ones once enough good genotypes exist.
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    assert_ne!(last[8], "NaN", "population median");
}

/// Fails every evaluation, and its replay as a robot evaluator's would (it re-simulates).
struct AlwaysFails;

impl Evaluator<Vec<f64>> for AlwaysFails {
    fn evaluate(&self, _genotype: &Vec<f64>, seed: u64) -> Evaluated {
        self.failure(seed, "the simulation exploded".into())
    }
    fn save_replay(&self, _genotype: &Vec<f64>, _path: &Path, _title: &str) -> Result<(), EvaluatorError> {
        Err(EvaluatorError::NoTrace)
    }
}

#[test]
fn a_run_whose_every_evaluation_fails_ends_with_a_summary_saying_so_and_resumes() {
    let experiment = tiny("kind = \"cma-es\"\npopulation_size = 4", "evaluations = 8");
    let dir = tempfile::tempdir().unwrap();
    let new_optimizer = |seed: u64| -> Result<AnyOptimizer, RunError> {
        Ok(experiment.optimizer.kind().build(3, &[Sense::Maximize], seed)?)
    };
    let plan = Plan::of(&experiment);
    let run = |resume: bool| {
        run_search(
            &plan,
            &new_optimizer,
            &AlwaysFails,
            dir.path(),
            &RunOptions {
                resume,
                ..common::two_threads(false)
            },
            &mut Silent,
        )
    };
    let summaries = run(false).unwrap();
    for s in &summaries {
        assert_eq!((s.failures, s.evaluations, s.best_fitness), (8, 8, None), "{s:?}");
    }
    let run0 = dir.path().join("run-00");
    assert!(run0.join("summary.json").is_file() && !run0.join("checkpoint.json").exists());
    assert!(
        !run0.join("best.robot.json").exists(),
        "no best robot when nothing succeeded"
    );
    assert_eq!(run(true).unwrap(), summaries, "the finished runs resume as they ended");
}

#[test]
fn nsga2_runs_a_two_objective_task_from_a_config() {
    let experiment = two_objectives(tiny(
        "kind = \"nsga2\"\npopulation_size = 8\noffspring_size = 8",
        "generations = 3",
    ));
    let lines = final_snapshot(&experiment);
    assert_eq!(lines.len(), 8);
    for line in &lines {
        let objectives = line["objectives"].as_array().unwrap();
        assert_eq!(objectives.len(), 2, "{line}");
        assert_eq!(objectives[0], line["velocity"]);
        assert_eq!(objectives[1].as_f64().unwrap(), line["voxels"].as_f64().unwrap());
    }
}

#[test]
fn a_single_objective_optimizer_refuses_two_objectives_and_the_ga_ranks_them_lexicographically() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../experiments/two-objectives.toml"
    ))
    .unwrap();
    assert!(config::parse(&text, "two-objectives.toml").is_ok());
    let es = text.replace(
        "kind = \"nsga2\"\npopulation_size = 40\noffspring_size = 40",
        "kind = \"cma-es\"",
    );
    let err = config::parse(&es, "x.toml").unwrap_err();
    assert_eq!(err.field, "optimizer.kind");
    assert!(err.to_string().contains("use nsga2, ga (lexicographic)"), "{err}");
    assert!(config::parse(&text.replace("kind = \"nsga2\"", "kind = \"ga\""), "x.toml").is_ok());
    // the GA keeps both objectives and sorts its population by the first, then the second
    let experiment = two_objectives(tiny(
        "kind = \"ga\"\npopulation_size = 8\noffspring_size = 8",
        "generations = 3",
    ));
    let objectives: Vec<(f64, f64)> = final_snapshot(&experiment)
        .iter()
        .map(|line| {
            let o = line["objectives"].as_array().unwrap();
            (o[0].as_f64().unwrap(), o[1].as_f64().unwrap())
        })
        .collect();
    assert_eq!(objectives.len(), 8);
    // velocity maximised, then voxels minimised on equal velocity
    assert!(
        objectives
            .windows(2)
            .all(|w| w[0].0 > w[1].0 || (w[0].0 == w[1].0 && w[0].1 <= w[1].1)),
        "{objectives:?}"
    );
}

/// Runs `experiment` (2 threads) and returns the rows of run 0's last snapshot.
fn final_snapshot(experiment: &Experiment) -> Vec<serde_json::Value> {
    let dir = tempfile::tempdir().unwrap();
    run(experiment, dir.path(), 2);
    let snapshots = std::fs::read_dir(dir.path().join("run-00/snapshots")).unwrap();
    let last = snapshots.map(|e| e.unwrap().path()).max().unwrap();
    let text = std::fs::read_to_string(last).unwrap();
    text.lines().map(|l| serde_json::from_str(l).unwrap()).collect()
}

/// The experiment with two objectives: velocity maximised, voxel count minimised.
fn two_objectives(mut experiment: Experiment) -> Experiment {
    experiment.task.spec = experiment
        .task
        .spec
        .with_settings(&[(
            "fitness",
            serde_json::json!(["velocity", {"metric": "voxels", "sense": "minimize"}]),
        )])
        .unwrap();
    experiment
}

/// The deterministic files of an output folder.
fn files_of(out: &std::path::Path) -> Vec<(String, Vec<u8>)> {
    vsrlab_experiment::runner::deterministic_files(out).unwrap()
}

#[test]
fn too_many_threads_are_refused_before_anything_is_written() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 4\noffspring_size = 4",
        "generations = 1",
    );
    let evaluator = RobotEvaluator::new(&experiment).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let options = RunOptions {
        threads: 100_000,
        resume: false,
        ..RunOptions::default()
    };
    let err = run_vectors(&experiment, &evaluator, &out, &options, &mut Silent).unwrap_err();
    assert!(err.to_string().contains("at most 1024"), "{err}");
    assert!(matches!(&err, RunError::Field(f) if f.path == "threads"), "{err:?}");
    assert!(!out.exists());
}

/// An observer that keeps the notices.
#[derive(Default)]
struct Notes(Vec<String>);

impl Observer for Notes {
    fn notice(&mut self, message: &str) {
        self.0.push(message.to_string());
    }
}

/// A two-run GA experiment interrupted in run 1 after 4 generations (one snapshot written) (run 0 finished, run 1 with a
/// checkpoint), and an uninterrupted copy to compare with.
fn interrupted(dir: &Path) -> (Experiment, std::path::PathBuf, std::path::PathBuf) {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 6\noffspring_size = 6",
        "evaluations = 30",
    );
    let evaluator = RobotEvaluator::new(&experiment).unwrap();
    let (straight, resumed) = (dir.join("straight"), dir.join("resumed"));
    run(&experiment, &straight, 2);
    let options = RunOptions {
        threads: 2,
        ..RunOptions::default()
    };
    run_vectors(
        &experiment,
        &evaluator,
        &resumed,
        &options,
        &mut Killer { run: 1, after: 4 },
    )
    .unwrap();
    (experiment, straight, resumed)
}

fn resume(experiment: &Experiment, out: &Path, observer: &mut dyn Observer) -> Result<(), RunError> {
    let evaluator = RobotEvaluator::new(experiment).unwrap();
    let options = RunOptions {
        threads: 2,
        resume: true,
        ..RunOptions::default()
    };
    run_vectors(experiment, &evaluator, out, &options, observer).map(drop)
}

/// Rewrites a checkpoint's content with `edit` and a freshly computed content hash, as someone
/// who knows the format could.
fn rewrite_checkpoint(path: &Path, edit: impl FnOnce(&mut serde_json::Value)) {
    let file: serde_json::Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    let mut content = file["content"].clone();
    edit(&mut content);
    let content = content.to_string();
    let hash = vsrlab_experiment::checkpoint::content_hash(content.as_bytes());
    let text = format!(
        r#"{{"format":"{}","content_hash":"{hash}","content":{content}}}"#,
        file["format"].as_str().unwrap()
    );
    std::fs::write(path, text).unwrap();
}

#[test]
fn a_tampered_checkpoint_is_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let (experiment, straight, resumed) = interrupted(dir.path());
    let checkpoint = run_dir(&resumed, 1, 2).join("checkpoint.json");
    let original = std::fs::read_to_string(&checkpoint).unwrap();

    // A fitness edited by hand: the content hash no longer matches.
    let value: serde_json::Value = serde_json::from_str(&original).unwrap();
    let fitness = value["content"]["optimizer"]["Ga"]["population"][0]["objectives"][0].to_string();
    let edited = original.replacen(&fitness, "1e300", 1);
    assert_ne!(edited, original, "the test must change the checkpoint");
    std::fs::write(&checkpoint, &edited).unwrap();
    let err = resume(&experiment, &resumed, &mut Silent).unwrap_err().to_string();
    assert!(
        err.contains("checkpoint.json") && err.contains("content hash mismatch"),
        "{err}"
    );

    // A genotype cut to 10 genes, with the hash recomputed: the representation check catches it.
    std::fs::write(&checkpoint, &original).unwrap();
    rewrite_checkpoint(&checkpoint, |c| {
        let genotype = c["optimizer"]["Ga"]["population"][0]["genotype"]
            .as_array_mut()
            .unwrap();
        genotype.truncate(10);
    });
    let err = resume(&experiment, &resumed, &mut Silent).unwrap_err().to_string();
    assert!(
        err.contains("checkpoint.json") && err.contains("population member 0"),
        "{err}"
    );
    assert!(err.contains("got 10"), "{err}");

    // An infinite fitness with the hash recomputed.
    std::fs::write(&checkpoint, &original).unwrap();
    rewrite_checkpoint(&checkpoint, |c| {
        c["optimizer"]["Ga"]["population"][1]["objectives"][0] = serde_json::json!("inf");
    });
    let err = resume(&experiment, &resumed, &mut Silent).unwrap_err().to_string();
    assert!(err.contains("checkpoint.json"), "{err}");

    // The untouched checkpoint resumes to the uninterrupted result.
    std::fs::write(&checkpoint, &original).unwrap();
    resume(&experiment, &resumed, &mut Silent).unwrap();
    assert_eq!(files_of(&straight), files_of(&resumed));
}

#[test]
fn missing_or_damaged_files_are_reported_on_resume() {
    let dir = tempfile::tempdir().unwrap();
    let (experiment, straight, resumed) = interrupted(dir.path());
    // A snapshot of the unfinished run, written before its checkpoint, deleted.
    let run1 = run_dir(&resumed, 1, 2);
    let snapshot = std::fs::read_dir(run1.join("snapshots"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .min()
        .unwrap();
    let saved = std::fs::read(&snapshot).unwrap();
    std::fs::remove_file(&snapshot).unwrap();
    let err = resume(&experiment, &resumed, &mut Silent).unwrap_err().to_string();
    assert!(
        err.contains(&snapshot.display().to_string()) && err.contains("missing"),
        "{err}"
    );
    std::fs::write(&snapshot, &saved).unwrap();

    // The finished run's best robot, truncated.
    let best = run_dir(&resumed, 0, 2).join("best.robot.json");
    let text = std::fs::read(&best).unwrap();
    std::fs::write(&best, &text[..text.len() / 2]).unwrap();
    let err = resume(&experiment, &resumed, &mut Silent).unwrap_err().to_string();
    assert!(err.contains("best.robot.json") && err.contains("differs"), "{err}");
    assert!(err.contains("delete the folder and resume again"), "{err}");

    std::fs::write(&best, &text).unwrap();

    // The finished run's summary, edited: its best fitness raised.
    let summary = run_dir(&resumed, 0, 2).join("summary.json");
    let original = std::fs::read_to_string(&summary).unwrap();
    let mut edited: serde_json::Value = serde_json::from_str(&original).unwrap();
    edited["best_fitness"] = serde_json::json!(1e6);
    std::fs::write(&summary, serde_json::to_string_pretty(&edited).unwrap()).unwrap();
    let err = resume(&experiment, &resumed, &mut Silent).unwrap_err().to_string();
    assert!(err.contains("summary.json") && err.contains("seal"), "{err}");
    std::fs::write(&summary, &original).unwrap();
    resume(&experiment, &resumed, &mut Silent).unwrap();

    // Doing what the message says gives the uninterrupted result back.
    std::fs::write(&best, &text[..text.len() / 2]).unwrap();
    std::fs::remove_dir_all(run_dir(&resumed, 0, 2)).unwrap();
    resume(&experiment, &resumed, &mut Silent).unwrap();
    assert_eq!(files_of(&straight), files_of(&resumed));
    // A finished experiment resumes again without complaint.
    resume(&experiment, &resumed, &mut Silent).unwrap();
}

#[test]
fn a_second_process_on_one_output_folder_is_refused() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 4\noffspring_size = 4",
        "generations = 1",
    );
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    let held = vsrlab_experiment::output_lock::OutputLock::acquire(&out).unwrap();
    let evaluator = RobotEvaluator::new(&experiment).unwrap();
    let err = run_vectors(&experiment, &evaluator, &out, &RunOptions::default(), &mut Silent)
        .unwrap_err()
        .to_string();
    assert!(err.contains("in use by another vsrlab process"), "{err}");
    assert!(!out.join("experiment.toml").exists());
    drop(held);
    run_vectors(&experiment, &evaluator, &out, &RunOptions::default(), &mut Silent).unwrap();
}

#[test]
fn resuming_a_run_without_checkpoint_says_it_restarts() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 6\noffspring_size = 6",
        "evaluations = 30",
    );
    let dir = tempfile::tempdir().unwrap();
    let evaluator = RobotEvaluator::new(&experiment).unwrap();
    let out = dir.path().join("out");
    run_vectors(
        &experiment,
        &evaluator,
        &out,
        &RunOptions::default(),
        &mut Killer { run: 0, after: 1 },
    )
    .unwrap();
    std::fs::remove_file(run_dir(&out, 0, 2).join("checkpoint.json")).unwrap();
    let mut notes = Notes::default();
    resume(&experiment, &out, &mut notes).unwrap();
    assert_eq!(notes.0.len(), 1, "{:?}", notes.0);
    assert!(
        notes.0[0].contains("run 1/2") && notes.0[0].contains("from the beginning"),
        "{:?}",
        notes.0
    );
    // Resuming a folder that holds nothing says so too.
    let mut notes = Notes::default();
    resume(&experiment, &dir.path().join("empty"), &mut notes).unwrap();
    assert!(notes.0[0].contains("nothing to resume"), "{:?}", notes.0);
}

#[test]
fn a_run_estimated_above_the_memory_limit_is_refused_before_anything_is_written() {
    let experiment = tiny(
        "kind = \"ga\"\npopulation_size = 1000\noffspring_size = 1000",
        "generations = 1",
    );
    let evaluator = RobotEvaluator::new(&experiment).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let options = RunOptions {
        threads: 1,
        memory_limit: Some(1 << 20),
        ..RunOptions::default()
    };
    let err = run_vectors(&experiment, &evaluator, &out, &options, &mut Silent).unwrap_err();
    match &err {
        RunError::Memory(limit) => {
            assert_eq!(limit.limit, 1 << 20);
            assert!(limit.estimate.bytes > 1 << 20, "{limit:?}");
        }
        other => panic!("expected a memory refusal, got {other:?}"),
    }
    let err = err.to_string();
    assert!(
        err.contains("memory limit of 0.0 GiB") && err.contains("--max-memory-gib"),
        "{err}"
    );
    assert!(!out.exists());
    // The default limit lets such a run through.
    let estimate = vsrlab_experiment::memory::MemoryEstimate::of(&experiment, evaluator.genotype_length(), 1);
    estimate.check(vsrlab_experiment::memory::DEFAULT_MEMORY_LIMIT).unwrap();
}

/// A CMA-ES run whose termination criterion holds ends by itself before its budget, with the
/// criterion as its stop reason (here `tolfun` set so large that the first generation meets it);
/// with `termination = false` the same run goes on to the budget.
#[test]
fn a_cma_es_run_that_stops_by_itself_names_the_criterion() {
    let summary = |termination: &str| {
        let experiment = tiny(
            &format!("kind = \"cma-es\"\npopulation_size = 4\ntolfun = 1e9\n{termination}"),
            "generations = 3",
        );
        let dir = tempfile::tempdir().unwrap();
        run(&experiment, dir.path(), 2);
        let text = std::fs::read_to_string(dir.path().join("run-00/summary.json")).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()
    };
    let stopped = summary("");
    assert_eq!(stopped["stop_reason"], "cma-es:tolfun", "{stopped}");
    assert_eq!(stopped["generations"], 1, "{stopped}");
    let budget = summary("termination = false");
    assert_eq!(budget["stop_reason"], "generations", "{budget}");
    assert_eq!(budget["generations"], 3, "{budget}");
}
