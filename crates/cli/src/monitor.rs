//! The live monitor of `vsrlab view OUT` (docs/viewer.md): for each run of the experiments in
//! an output folder, its fitness curves (best so far and population median), its progress and
//! ETA, and a replay of its best robot so far, read from the files the runner writes every
//! generation (`generations.csv`, `timings.csv`, the snapshots), so that it works the same on a
//! run in progress, an interrupted one and a finished one.

use serde_json::{json, Value};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};
use vsrlab_analysis::results::{read_generations, read_snapshot};
use vsrlab_analysis::run_folder::{RunFiles, RunFolder, EXPERIMENT_FILE};
use vsrlab_experiment::Experiment;
use vsrlab_render::replay::{Replay, ReplayOptions};
use vsrlab_render::viewer::{LiveSource, MakeError};
use vsrlab_tasks::{episode, Robot, Sense, TraceLevel};

/// One experiment folder being watched.
struct Watched {
    name: String,
    folder: RunFolder,
    experiment: Experiment,
}

/// What a run's best replay was made from: the final best, or the snapshot after this many
/// evaluations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Stamp {
    Final,
    Snapshot(u64),
}

/// Best replays made so far, by (experiment, run), with what each was made from.
type MadeReplays = HashMap<(usize, usize), (Stamp, Arc<Vec<u8>>)>;

/// The live monitor of some experiment folders.
pub struct Monitor {
    watched: Vec<Watched>,
    replays: Mutex<MadeReplays>,
}

/// The experiment folders of a `vsrlab run` output: `dir` itself when it holds an
/// `experiment.toml`, else its sub-folders that do (the settings of a sweep), sorted.
pub fn experiment_folders(dir: &Path) -> Vec<PathBuf> {
    if dir.join(EXPERIMENT_FILE).is_file() {
        return vec![dir.to_path_buf()];
    }
    let mut found: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|entries| {
            entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.join(EXPERIMENT_FILE).is_file())
                .collect()
        })
        .unwrap_or_default();
    found.sort();
    found
}

impl Monitor {
    /// A monitor of these experiment folders (each with its `experiment.toml`).
    pub fn new(folders: &[PathBuf]) -> Result<Monitor, String> {
        let watched = folders
            .iter()
            .map(|dir| {
                let experiment =
                    vsrlab_experiment::config::load(&dir.join(EXPERIMENT_FILE)).map_err(|e| e.to_string())?;
                Ok(Watched {
                    name: experiment.name.clone().unwrap_or_else(|| dir.display().to_string()),
                    folder: RunFolder::new(dir),
                    experiment,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(Monitor {
            watched,
            replays: Mutex::new(HashMap::new()),
        })
    }

    /// The run files of run `run` of a watched experiment.
    fn run_files(w: &Watched, run: usize) -> RunFiles {
        w.folder.run(run, w.experiment.runs)
    }

    /// One experiment's state: its runs, and the ETA of what is left of it.
    fn experiment_status(w: &Watched) -> Value {
        let runs: Vec<RunStatus> = (0..w.experiment.runs).map(|run| run_status(w, run)).collect();
        json!({
            "name": w.name,
            "folder": w.folder.root().display().to_string(),
            "eta": experiment_eta(&runs),
            "runs": runs.iter().map(RunStatus::to_json).collect::<Vec<_>>(),
        })
    }

    /// What a run's best replay would be made from now, if it has a best.
    fn stamp(files: &RunFiles) -> Option<Stamp> {
        if files.summary_json().is_file() {
            let final_best = files.best_replay().is_file() || files.best_robot().is_file();
            return final_best.then_some(Stamp::Final);
        }
        files
            .snapshots_on_disk()
            .last()
            .map(|&(evaluations, _)| Stamp::Snapshot(evaluations))
    }

    /// The replay of a run's best as of `stamp`.
    fn make_replay(&self, w: &Watched, run: usize, stamp: Stamp) -> Result<Vec<u8>, MakeError> {
        let files = Self::run_files(w, run);
        let task = &w.experiment.task.spec;
        let (robot, seed, title): (Box<dyn Robot>, u64, String) = match stamp {
            Stamp::Final if files.best_replay().is_file() => {
                return Ok(vsrlab_tasks::files::read_bytes(&files.best_replay())?);
            }
            Stamp::Final => {
                let robot = vsrlab_tasks::files::load_any_robot(&files.best_robot())?;
                let title = format!("{} run {run}: best", w.name);
                (robot.into_robot(), 0, title)
            }
            Stamp::Snapshot(evaluations) => {
                let rows = read_snapshot(&files.snapshot(evaluations))?;
                let sense = task.task().objectives().first().map(|o| o.sense).unwrap_or_default();
                let key = |f: f64| if sense == Sense::Minimize { -f } else { f };
                let best = rows
                    .iter()
                    .filter_map(|r| r.fitness().filter(|f| f.is_finite()).map(|f| (key(f), r)))
                    .max_by(|a, b| a.0.total_cmp(&b.0))
                    .map(|(_, r)| r)
                    .ok_or("no robot of the latest snapshot was evaluated successfully")?;
                let stored = w.experiment.genotype_kind().stored(&w.experiment)?;
                let title = format!(
                    "{} run {run}: best so far (after {evaluations} evaluations, fitness {})",
                    w.name,
                    best.fitness().unwrap_or(f64::NAN)
                );
                (stored.robot(&best.genotype)?, best.seed(), title)
            }
        };
        let outcome = episode::run(robot.as_ref(), task.task(), seed, TraceLevel::Full)?;
        let trace = outcome.trace.ok_or("the episode recorded no trace")?;
        let options = ReplayOptions {
            title,
            ..ReplayOptions::default()
        };
        Ok(Replay::from_trace(&trace, &options)?.to_json().into_bytes())
    }
}

impl LiveSource for Monitor {
    fn status(&self) -> Result<Vec<u8>, MakeError> {
        let experiments: Vec<Value> = self.watched.iter().map(Monitor::experiment_status).collect();
        Ok(serde_json::to_vec(&json!({ "experiments": experiments }))?)
    }

    fn best_replay(&self, experiment: usize, run: usize) -> Option<Result<Vec<u8>, MakeError>> {
        let w = self.watched.get(experiment)?;
        if run >= w.experiment.runs {
            return None;
        }
        let stamp = Self::stamp(&Self::run_files(w, run))?;
        if let Some((made, bytes)) = self.replays.lock().ok()?.get(&(experiment, run)) {
            if *made == stamp {
                return Some(Ok(bytes.to_vec()));
            }
        }
        let made = self.make_replay(w, run, stamp);
        if let (Ok(bytes), Ok(mut cache)) = (&made, self.replays.lock()) {
            cache.insert((experiment, run), (stamp, Arc::new(bytes.clone())));
        }
        Some(made)
    }
}

/// A run's state, read from its files.
struct RunStatus {
    run: usize,
    name: String,
    /// `waiting` (no generation yet), `running` (generations, no summary) or `finished`.
    state: &'static str,
    /// (evaluations, best so far, population median) per generation.
    curve: Vec<(u64, f64, f64)>,
    generation: u64,
    evaluations: u64,
    best: f64,
    fraction: f64,
    elapsed: f64,
    stamp: Option<Stamp>,
}

impl RunStatus {
    /// Seconds left, when it is running and has made progress.
    fn eta(&self) -> Option<f64> {
        (self.state == "running" && self.fraction > 0.0).then(|| self.elapsed * (1.0 - self.fraction) / self.fraction)
    }

    /// Its whole length, projected from its progress (finished: its length).
    fn projected_seconds(&self) -> Option<f64> {
        (self.fraction > 0.0).then(|| self.elapsed / self.fraction)
    }

    fn to_json(&self) -> Value {
        json!({
            "run": self.run,
            "name": self.name,
            "state": self.state,
            "generation": self.generation,
            "evaluations": self.evaluations,
            "best": self.best,
            "fraction": self.fraction,
            "elapsed": self.elapsed,
            "eta": self.eta(),
            "curve": self.curve.iter().map(|&(e, b, m)| json!([e, b, m])).collect::<Vec<_>>(),
            "best_stamp": match self.stamp {
                Some(Stamp::Final) => json!("final"),
                Some(Stamp::Snapshot(evaluations)) => json!(evaluations),
                None => Value::Null,
            },
        })
    }
}

/// The state of one run of a watched experiment.
fn run_status(w: &Watched, run: usize) -> RunStatus {
    let files = Monitor::run_files(w, run);
    let rows = read_generations(&files.generations_csv()).unwrap_or_default();
    let state = if files.summary_json().is_file() {
        "finished"
    } else if rows.is_empty() {
        "waiting"
    } else {
        "running"
    };
    let elapsed = last_elapsed_seconds(&files.timings_csv());
    let last = rows.last();
    let (generation, evaluations, births) = last.map_or((0, 0, 0), |r| (r.generation, r.evaluations, r.births));
    let fraction = match state {
        "finished" => 1.0,
        _ => w.experiment.stop.fraction(evaluations, births, generation, elapsed),
    };
    RunStatus {
        run,
        name: files
            .dir()
            .file_name()
            .map_or(String::new(), |n| n.to_string_lossy().into_owned()),
        state,
        curve: rows
            .iter()
            .map(|r| (r.evaluations, r.best_fitness, r.population_median))
            .collect(),
        generation,
        evaluations,
        best: last.map_or(f64::NAN, |r| r.best_fitness),
        fraction,
        elapsed,
        stamp: Monitor::stamp(&files),
    }
}

/// The wall seconds of a run so far: the `elapsed_seconds` of the last row of its
/// `timings.csv` (0 without one).
fn last_elapsed_seconds(path: &Path) -> f64 {
    let Ok(text) = std::fs::read_to_string(path) else {
        return 0.0;
    };
    let column = text
        .lines()
        .next()
        .and_then(|header| header.split(',').position(|c| c == "elapsed_seconds"));
    match (column, text.lines().rev().find(|l| !l.trim().is_empty())) {
        (Some(i), Some(row)) => row.split(',').nth(i).and_then(|v| v.parse().ok()).unwrap_or(0.0),
        _ => 0.0,
    }
}

/// Seconds left of an experiment whose runs go one after another: what the running one has
/// left, plus, for each run not started, the mean projected length of the runs seen so far.
fn experiment_eta(runs: &[RunStatus]) -> Option<f64> {
    let lengths: Vec<f64> = runs.iter().filter_map(RunStatus::projected_seconds).collect();
    if lengths.is_empty() || runs.iter().all(|r| r.state == "finished") {
        return None;
    }
    let mean = lengths.iter().sum::<f64>() / lengths.len() as f64;
    let waiting = runs.iter().filter(|r| r.state == "waiting").count() as f64;
    let running: f64 = runs.iter().filter_map(RunStatus::eta).sum();
    Some(running + waiting * mean)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn status(state: &'static str, fraction: f64, elapsed: f64) -> RunStatus {
        RunStatus {
            run: 0,
            name: "run-00".into(),
            state,
            curve: Vec::new(),
            generation: 0,
            evaluations: 0,
            best: f64::NAN,
            fraction,
            elapsed,
            stamp: None,
        }
    }

    #[test]
    fn the_eta_adds_what_the_running_run_has_left_and_the_runs_not_started() {
        // a finished run of 100 s, one a quarter through after 30 s (90 s left, 120 s in all),
        // two not started: 90 + 2 × mean(100, 120)
        let runs = [
            status("finished", 1.0, 100.0),
            status("running", 0.25, 30.0),
            status("waiting", 0.0, 0.0),
            status("waiting", 0.0, 0.0),
        ];
        assert_eq!(runs[1].eta(), Some(90.0));
        assert_eq!(experiment_eta(&runs), Some(90.0 + 2.0 * 110.0));
        assert_eq!(experiment_eta(&[status("waiting", 0.0, 0.0)]), None);
        assert_eq!(experiment_eta(&runs[..1]), None, "nothing left");
    }

    #[test]
    fn the_elapsed_time_is_the_last_row_of_the_timings() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("timings.csv");
        std::fs::write(&path, "generation,elapsed_seconds,x\n1,0.5,9\n2,1.25,9\n").unwrap();
        assert_eq!(last_elapsed_seconds(&path), 1.25);
        assert_eq!(last_elapsed_seconds(&dir.path().join("missing.csv")), 0.0);
    }
}
