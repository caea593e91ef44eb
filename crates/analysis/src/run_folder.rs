//! The layout of an experiment's output folder, as `vsrlab run` writes it and analysis reads it:
//!
//! ```text
//! OUT/experiment.toml            the resolved experiment (every default written out)
//! OUT/summary.json               per-run results and timings (written when all runs end)
//! OUT/run-00/generations.csv     one row per generation: deterministic columns only
//! OUT/run-00/timings.csv         one row per generation: wall-clock columns
//! OUT/run-00/snapshots/evaluations-0001000.jsonl   the population, every N evaluations
//! OUT/run-00/best.robot.json     the best robot (a robot file)
//! OUT/run-00/summary.json        the run's result, timings and overhead (written at its end)
//! OUT/run-00/checkpoint.json     optimizer + run state (while the run is unfinished)
//! OUT/run-00/unfinished-generation.jsonl   evaluations done in a long generation (while it runs)
//! ```
//!
//! Run folders are numbered from 0 with as many digits as the last run's number needs, at least
//! two: `run-00` … `run-99` for up to 100 runs, `run-000` … `run-149` for 150. Writer and
//! readers share these names through [`RunFolder`] and [`RunFiles`], so the layout is defined
//! once.

use std::path::{Path, PathBuf};

/// The resolved experiment configuration, at the top of the folder.
pub const EXPERIMENT_FILE: &str = "experiment.toml";
/// Per-run results of the whole experiment (top) or of one run (in its folder).
pub const SUMMARY_FILE: &str = "summary.json";
/// One row per generation, deterministic columns only.
pub const GENERATIONS_FILE: &str = "generations.csv";
/// One row per generation, wall-clock columns.
pub const TIMINGS_FILE: &str = "timings.csv";
/// Folder of a run's population snapshots.
pub const SNAPSHOTS_DIR: &str = "snapshots";
/// The best robot of a run (a robot file).
pub const BEST_ROBOT_FILE: &str = "best.robot.json";
/// The best robot's episode as a replay file for the browser viewer (`vsrlab view`).
pub const BEST_REPLAY_FILE: &str = "best.replay.json";
/// Optimizer and run state of an unfinished run.
pub const CHECKPOINT_FILE: &str = "checkpoint.json";
/// The evaluations of a long generation still under way, saved while it runs so that a kill
/// loses at most one checkpoint interval of work inside a generation too.
pub const UNFINISHED_GENERATION_FILE: &str = "unfinished-generation.jsonl";
/// Name prefix of run folders (`run-00`).
pub const RUN_PREFIX: &str = "run-";
/// Name prefix of snapshot files (`evaluations-0001000.jsonl`).
pub const SNAPSHOT_PREFIX: &str = "evaluations-";
/// Name suffix of snapshot files (JSON lines).
pub const SNAPSHOT_SUFFIX: &str = ".jsonl";

/// An experiment's output folder (`vsrlab run --out OUT`).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RunFolder {
    root: PathBuf,
}

impl RunFolder {
    /// The output folder at `out` (nothing is read or created).
    pub fn new(out: impl Into<PathBuf>) -> RunFolder {
        RunFolder { root: out.into() }
    }

    /// The folder itself.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// `OUT/experiment.toml`.
    pub fn experiment_toml(&self) -> PathBuf {
        self.root.join(EXPERIMENT_FILE)
    }

    /// `OUT/summary.json`.
    pub fn summary_json(&self) -> PathBuf {
        self.root.join(SUMMARY_FILE)
    }

    /// Whether the folder holds an experiment (its `experiment.toml` exists).
    pub fn is_experiment(&self) -> bool {
        self.experiment_toml().is_file()
    }

    /// The folder of run `run` out of `runs` (`run-07`; `run-007` when there are more than 100
    /// runs).
    pub fn run_dir(&self, run: usize, runs: usize) -> PathBuf {
        self.root.join(run_dir_name(run, runs))
    }

    /// The files of run `run` out of `runs`.
    pub fn run(&self, run: usize, runs: usize) -> RunFiles {
        RunFiles::new(self.run_dir(run, runs), run)
    }

    /// The run folders present on disk, by index (folders named `run-N`, whatever the width).
    pub fn runs_on_disk(&self) -> std::io::Result<Vec<RunFiles>> {
        let mut entries: Vec<_> = std::fs::read_dir(&self.root)?.flatten().collect();
        entries.sort_by_key(|e| e.file_name());
        Ok(entries
            .into_iter()
            .filter_map(|e| {
                let index = parse_run_dir_name(&e.file_name().to_string_lossy())?;
                e.path().is_dir().then(|| RunFiles::new(e.path(), index))
            })
            .collect())
    }
}

/// The files of one run (`OUT/run-NN/`).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RunFiles {
    dir: PathBuf,
    index: usize,
}

impl RunFiles {
    /// Run number `index` in folder `dir`.
    pub fn new(dir: impl Into<PathBuf>, index: usize) -> RunFiles {
        RunFiles { dir: dir.into(), index }
    }

    /// The run's folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The run's number (0-based).
    pub fn index(&self) -> usize {
        self.index
    }

    /// `run-NN/generations.csv`.
    pub fn generations_csv(&self) -> PathBuf {
        self.dir.join(GENERATIONS_FILE)
    }

    /// `run-NN/timings.csv`.
    pub fn timings_csv(&self) -> PathBuf {
        self.dir.join(TIMINGS_FILE)
    }

    /// `run-NN/snapshots/`.
    pub fn snapshots_dir(&self) -> PathBuf {
        self.dir.join(SNAPSHOTS_DIR)
    }

    /// `run-NN/snapshots/evaluations-NNNNNNN.jsonl`, the snapshot after `evaluations`.
    pub fn snapshot(&self, evaluations: u64) -> PathBuf {
        self.snapshots_dir().join(snapshot_file_name(evaluations))
    }

    /// `run-NN/best.robot.json`.
    pub fn best_robot(&self) -> PathBuf {
        self.dir.join(BEST_ROBOT_FILE)
    }

    /// `run-NN/best.replay.json`.
    pub fn best_replay(&self) -> PathBuf {
        self.dir.join(BEST_REPLAY_FILE)
    }

    /// `run-NN/summary.json`.
    pub fn summary_json(&self) -> PathBuf {
        self.dir.join(SUMMARY_FILE)
    }

    /// `run-NN/checkpoint.json`.
    pub fn checkpoint_json(&self) -> PathBuf {
        self.dir.join(CHECKPOINT_FILE)
    }

    /// `run-NN/unfinished-generation.jsonl`.
    pub fn unfinished_generation(&self) -> PathBuf {
        self.dir.join(UNFINISHED_GENERATION_FILE)
    }

    /// The snapshots present on disk, by evaluation count (empty without a snapshot folder).
    pub fn snapshots_on_disk(&self) -> Vec<(u64, PathBuf)> {
        let mut snapshots: Vec<(u64, PathBuf)> = std::fs::read_dir(self.snapshots_dir())
            .into_iter()
            .flat_map(|entries| entries.flatten())
            .filter_map(|e| Some((parse_snapshot_file_name(&e.file_name().to_string_lossy())?, e.path())))
            .collect();
        snapshots.sort();
        snapshots
    }
}

/// `run-07` for run 7 of up to 100 runs; `run-007` for run 7 of 101 to 1000.
pub fn run_dir_name(run: usize, runs: usize) -> String {
    let width = (runs.max(1) - 1).to_string().len().max(2);
    format!("{RUN_PREFIX}{run:0width$}")
}

/// The run number of a run folder's name (`run-07` → 7), whatever the width.
pub fn parse_run_dir_name(name: &str) -> Option<usize> {
    name.strip_prefix(RUN_PREFIX)?.parse().ok()
}

/// `evaluations-0001000.jsonl` for the snapshot after 1000 evaluations.
pub fn snapshot_file_name(evaluations: u64) -> String {
    format!("{SNAPSHOT_PREFIX}{evaluations:07}{SNAPSHOT_SUFFIX}")
}

/// The evaluation count of a snapshot file's name (`evaluations-0001000.jsonl` → 1000).
pub fn parse_snapshot_file_name(name: &str) -> Option<u64> {
    name.strip_prefix(SNAPSHOT_PREFIX)?
        .strip_suffix(SNAPSHOT_SUFFIX)?
        .parse()
        .ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn run_folders_widen_beyond_100_runs() {
        let out = RunFolder::new("out");
        assert_eq!(out.run_dir(3, 10), Path::new("out/run-03"));
        assert_eq!(out.run_dir(99, 100), Path::new("out/run-99"));
        assert_eq!(out.run_dir(7, 101), Path::new("out/run-007"));
        assert_eq!(out.run_dir(0, 0), Path::new("out/run-00"));
        assert_eq!(parse_run_dir_name("run-007"), Some(7));
        assert_eq!(parse_run_dir_name("runs"), None);
    }

    #[test]
    fn file_names_round_trip() {
        let run = RunFolder::new("out").run(2, 5);
        assert_eq!(run.index(), 2);
        assert_eq!(run.generations_csv(), Path::new("out/run-02/generations.csv"));
        assert_eq!(run.timings_csv(), Path::new("out/run-02/timings.csv"));
        assert_eq!(run.best_robot(), Path::new("out/run-02/best.robot.json"));
        assert_eq!(run.summary_json(), Path::new("out/run-02/summary.json"));
        assert_eq!(run.checkpoint_json(), Path::new("out/run-02/checkpoint.json"));
        assert_eq!(
            run.snapshot(1000),
            Path::new("out/run-02/snapshots/evaluations-0001000.jsonl")
        );
        assert_eq!(parse_snapshot_file_name("evaluations-0001000.jsonl"), Some(1000));
        assert_eq!(parse_snapshot_file_name(".evaluations-0001000.jsonl.tmp-1"), None);
        assert_eq!(
            RunFolder::new("out").experiment_toml(),
            Path::new("out/experiment.toml")
        );
        assert_eq!(RunFolder::new("out").summary_json(), Path::new("out/summary.json"));
    }

    #[test]
    fn reads_runs_and_snapshots_on_disk() {
        let tmp = tempfile::tempdir().unwrap();
        let folder = RunFolder::new(tmp.path());
        for run in [folder.run(1, 2), folder.run(0, 2)] {
            std::fs::create_dir_all(run.snapshots_dir()).unwrap();
            for evals in [200, 100] {
                std::fs::write(run.snapshot(evals), "").unwrap();
            }
        }
        std::fs::write(tmp.path().join("run-notes.txt"), "").unwrap();
        let runs = folder.runs_on_disk().unwrap();
        assert_eq!(runs.iter().map(RunFiles::index).collect::<Vec<_>>(), vec![0, 1]);
        let snaps: Vec<u64> = runs[0].snapshots_on_disk().iter().map(|s| s.0).collect();
        assert_eq!(snaps, vec![100, 200]);
    }
}
