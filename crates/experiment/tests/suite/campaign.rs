//! Campaigns: two files (one of them a sweep) × two runs each, side by side on one pool, write
//! every setting's folder as running each setting alone does; interrupted everywhere and
//! resumed, the same again.

use std::path::{Path, PathBuf};
use vsrlab_experiment::campaign::{run_campaign, settings, CampaignError, CampaignObserver, Standing};
use vsrlab_experiment::config;
use vsrlab_experiment::run_configured;
use vsrlab_experiment::runner::{deterministic_files, Flow, Progress, RunOptions, RunSummary, Silent};

fn experiment_text(name: &str, seed: u64, sweep: &str) -> String {
    format!(
        r#"
name = "{name}"
runs = 2
seed = {seed}
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = {{ kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }}
[task]
terrain = "flat"
duration = 1.0
fitness = "velocity"
[optimizer]
kind = "ga"
population_size = 6
offspring_size = 6
[stop]
evaluations = 24
{sweep}
"#
    )
}

fn files(dir: &Path) -> Vec<PathBuf> {
    let a = dir.join("a.toml");
    std::fs::write(&a, experiment_text("walk", 3, "")).unwrap();
    let b = dir.join("b.toml");
    let sweep = "[sweep]\n\"task.terrain\" = { flat = \"flat\", hilly = \"hilly-1-10\" }";
    std::fs::write(&b, experiment_text("terrains", 4, sweep)).unwrap();
    vec![a, b]
}

/// Counts progress as the CLI does; stops every run after its first generation when asked.
struct Watch {
    standing: Standing,
    stop_after_first: bool,
    finished: usize,
}

impl CampaignObserver for Watch {
    fn generation(&mut self, setting: usize, p: &Progress) -> Flow {
        self.standing.set(setting, p.run, p.fraction);
        if self.stop_after_first {
            Flow::Interrupt
        } else {
            Flow::Continue
        }
    }
    fn run_finished(&mut self, setting: usize, s: &RunSummary) {
        self.standing.set(setting, s.run, 1.0);
        self.finished += 1;
    }
}

fn same_files(a: &Path, b: &Path) {
    let (x, y) = (deterministic_files(a).unwrap(), deterministic_files(b).unwrap());
    assert!(x.len() >= 6, "{x:?}");
    assert_eq!(x.len(), y.len(), "{} and {}", a.display(), b.display());
    for ((name, p), (_, q)) in x.iter().zip(&y) {
        assert!(p == q, "{name} differs between {} and {}", a.display(), b.display());
    }
}

#[test]
fn a_campaign_runs_every_setting_side_by_side_as_each_alone_and_resumes_to_the_same_files() {
    let dir = tempfile::tempdir().unwrap();
    let files = files(dir.path());
    let out = dir.path().join("campaign");
    let all = settings(&files, &out).unwrap();
    let names: Vec<&str> = all.iter().map(|s| s.name.as_str()).collect();
    let swept: Vec<String> = config::load_all(&files[1])
        .unwrap()
        .into_iter()
        .filter_map(|e| e.name)
        .collect();
    assert_eq!(names.len(), 3, "{names:?}");
    assert_eq!(names[0], "walk");
    assert_eq!(names[1..], swept.iter().map(String::as_str).collect::<Vec<_>>()[..]);

    let options = RunOptions {
        threads: 2,
        ..RunOptions::default()
    };
    let mut watch = Watch {
        standing: Standing::new(&[2, 2, 2]),
        stop_after_first: false,
        finished: 0,
    };
    let results = run_campaign(&all, &options, &mut watch).unwrap();
    assert_eq!(watch.finished, 6);
    assert_eq!(watch.standing.fraction(), 1.0);
    assert!(results.iter().all(|r| r.summaries.len() == 2 && r.runs == 2));
    let table = vsrlab_experiment::campaign::table(&all, &results);
    assert_eq!(table.lines().count(), 4, "{table}");
    assert!(table.lines().nth(1).unwrap().starts_with("walk "), "{table}");

    // each setting alone, one run after the other
    for setting in &all {
        let alone = dir.path().join("alone").join(&setting.name);
        run_configured(&setting.experiment, &alone, &options, &mut Silent).unwrap();
        same_files(&setting.out, &alone);
    }

    // interrupted after every run's first generation, then resumed
    let stopped = dir.path().join("stopped");
    let again = settings(&files, &stopped).unwrap();
    let mut first = Watch {
        standing: Standing::new(&[2, 2, 2]),
        stop_after_first: true,
        finished: 0,
    };
    let partial = run_campaign(&again, &options, &mut first).unwrap();
    assert!(partial.iter().all(|r| r.summaries.is_empty()), "no run finished");
    let resume = RunOptions {
        resume: true,
        ..options.clone()
    };
    run_campaign(&again, &resume, &mut Quiet).unwrap();
    for (setting, original) in again.iter().zip(&all) {
        same_files(&setting.out, &original.out);
    }
}

/// An observer that does nothing.
struct Quiet;
impl CampaignObserver for Quiet {}

#[test]
fn two_settings_of_one_name_are_refused_with_both_files() {
    let dir = tempfile::tempdir().unwrap();
    let a = dir.path().join("a.toml");
    let b = dir.path().join("b.toml");
    std::fs::write(&a, experiment_text("same", 1, "")).unwrap();
    std::fs::write(&b, experiment_text("same", 2, "")).unwrap();
    let err = settings(&[a, b], dir.path()).unwrap_err();
    assert!(matches!(err, CampaignError::SameName { .. }), "{err}");
    let text = err.to_string();
    assert!(
        text.contains("a.toml") && text.contains("b.toml") && text.starts_with("same: "),
        "{text}"
    );
    assert!(matches!(settings(&[], dir.path()), Err(CampaignError::Empty)));
}

/// Loses every batch, as a cluster that went away.
struct Lost;

impl vsrlab_experiment::remote::Transport for Lost {
    fn evaluate(
        &self,
        _genotypes: &[String],
        _seeds: &[u64],
    ) -> Result<Vec<vsrlab_experiment::Evaluated>, vsrlab_experiment::evaluator::EvaluatorError> {
        Err(vsrlab_experiment::evaluator::EvaluatorError::Remote(
            "the cluster went away".into(),
        ))
    }
}

#[test]
fn a_setting_that_cannot_finish_a_batch_stops_the_campaign_at_its_checkpoints() {
    let dir = tempfile::tempdir().unwrap();
    let files = files(dir.path());
    let out = dir.path().join("campaign");
    let mut all = settings(&files, &out).unwrap();
    // the first setting's batches are lost; the others would run 200 generations
    all[0].evaluations = vsrlab_experiment::remote::Evaluations::Remote(std::sync::Arc::new(Lost));
    for setting in &mut all[1..] {
        setting.experiment.stop.evaluations = Some(1200);
    }
    let options = RunOptions {
        threads: 2,
        ..RunOptions::default()
    };
    let err = run_campaign(&all, &options, &mut Quiet).unwrap_err().to_string();
    assert!(
        err.starts_with("walk: ") && err.contains("the cluster went away"),
        "{err}"
    );
    assert!(err.contains("--resume"), "{err}");
    // the others stopped at a checkpoint, unfinished
    for setting in &all[1..] {
        assert!(setting.out.join("run-00/checkpoint.json").is_file(), "{}", setting.name);
        assert!(!setting.out.join("summary.json").exists(), "{} finished", setting.name);
    }
}
