//! Reading the output of `vsrlab run` (docs/experiments.md): an experiment folder holds the
//! resolved `experiment.toml` and one `run-NN/` folder per run with `generations.csv`,
//! `snapshots/evaluations-NNNNNNN.jsonl`, `best.robot.json` and `summary.json`.
//!
//! Only file formats are read here (no dependency on the experiment crate): the configuration
//! stays a TOML table, CSV columns are looked up by name, snapshot lines keep what analysis uses.

use serde::Deserialize;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Why results could not be read.
#[derive(Debug, thiserror::Error)]
#[error("{path}: {msg}")]
pub struct ResultsError {
    /// The file or folder.
    pub path: String,
    /// What is wrong.
    pub msg: String,
}

fn fail(path: &Path, msg: impl std::fmt::Display) -> ResultsError {
    ResultsError {
        path: path.display().to_string(),
        msg: msg.to_string(),
    }
}

/// One row of `generations.csv` (the columns analysis uses; NaN when absent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GenerationRow {
    /// Generation number.
    pub generation: u64,
    /// Fitness evaluations so far.
    pub evaluations: u64,
    /// Best fitness so far.
    pub best_fitness: f64,
    /// Median fitness of the population after the generation.
    pub population_median: f64,
    /// Best fitness of the population after the generation.
    pub population_best: f64,
}

/// One population member of a snapshot.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct SnapshotRow {
    /// Generation of the snapshot.
    #[serde(default)]
    pub generation: u64,
    /// Evaluations at the snapshot.
    #[serde(default)]
    pub evaluations: u64,
    /// Index in the population.
    #[serde(default)]
    pub index: usize,
    /// Episode seed used to evaluate it.
    #[serde(default)]
    pub seed: u64,
    /// Fitness (None when the evaluation failed).
    #[serde(default)]
    pub fitness: Option<f64>,
    /// Average velocity.
    #[serde(default)]
    pub velocity: Option<f64>,
    /// Number of voxels.
    #[serde(default)]
    pub voxels: Option<usize>,
    /// Body as rows joined by `/`, top row first.
    #[serde(default)]
    pub body: Option<String>,
    /// Why the evaluation failed.
    #[serde(default)]
    pub error: Option<String>,
    /// The genotype.
    #[serde(default)]
    pub genotype: Vec<f64>,
}

/// One run of an experiment.
#[derive(Debug, Clone, PartialEq)]
pub struct RunData {
    /// The run's folder.
    pub dir: PathBuf,
    /// Run index (from the folder name `run-NN`).
    pub index: usize,
    /// Rows of `generations.csv`.
    pub generations: Vec<GenerationRow>,
    /// Snapshot files, by evaluation count.
    pub snapshots: Vec<(u64, PathBuf)>,
    /// `best.robot.json`, when present.
    pub best_robot: Option<PathBuf>,
    /// `summary.json`, when present.
    pub summary: Option<serde_json::Value>,
}

impl RunData {
    /// Best fitness at the end of the run (NaN without generations).
    pub fn final_best(&self) -> f64 {
        self.summary
            .as_ref()
            .and_then(|s| s.get("best_fitness"))
            .and_then(|v| v.as_f64())
            .unwrap_or_else(|| self.generations.last().map_or(f64::NAN, |g| g.best_fitness))
    }

    /// The last snapshot (the final population).
    pub fn final_snapshot(&self) -> Option<&(u64, PathBuf)> {
        self.snapshots.last()
    }
}

/// One experiment folder.
#[derive(Debug, Clone, PartialEq)]
pub struct ExperimentData {
    /// The folder.
    pub dir: PathBuf,
    /// Setting name: the configuration's `name`, else the folder name.
    pub name: String,
    /// The resolved configuration.
    pub config: toml::Table,
    /// Its runs, by index.
    pub runs: Vec<RunData>,
}

impl ExperimentData {
    /// A configuration value by dotted path (`task.fitness`).
    pub fn config_value(&self, dotted: &str) -> Option<&toml::Value> {
        let mut parts = dotted.split('.');
        let mut v = self.config.get(parts.next()?)?;
        for p in parts {
            v = v.get(p)?;
        }
        Some(v)
    }

    /// What the fitness is (`velocity` or `distance`; `velocity` when unset).
    pub fn fitness_kind(&self) -> String {
        self.config_value("task.fitness")
            .and_then(|v| v.as_str())
            .unwrap_or("velocity")
            .to_string()
    }
}

/// Reads `generations.csv`.
pub fn read_generations(path: &Path) -> Result<Vec<GenerationRow>, ResultsError> {
    let mut reader = csv::Reader::from_path(path).map_err(|e| fail(path, e))?;
    let headers = reader.headers().map_err(|e| fail(path, e))?.clone();
    let col: HashMap<&str, usize> = headers.iter().enumerate().map(|(i, h)| (h, i)).collect();
    let mut rows = Vec::new();
    for (line, rec) in reader.records().enumerate() {
        let rec = rec.map_err(|e| fail(path, e))?;
        let num = |name: &str| -> f64 {
            col.get(name)
                .and_then(|&i| rec.get(i))
                .and_then(|v| v.trim().parse::<f64>().ok())
                .unwrap_or(f64::NAN)
        };
        let int = |name: &str| -> Result<u64, ResultsError> {
            col.get(name)
                .and_then(|&i| rec.get(i))
                .and_then(|v| v.trim().parse::<u64>().ok())
                .ok_or_else(|| fail(path, format!("row {}: no integer column '{name}'", line + 2)))
        };
        rows.push(GenerationRow {
            generation: int("generation")?,
            evaluations: int("evaluations")?,
            best_fitness: num("best_fitness"),
            population_median: num("population_median"),
            population_best: num("population_best"),
        });
    }
    Ok(rows)
}

/// Reads a snapshot (JSON lines).
pub fn read_snapshot(path: &Path) -> Result<Vec<SnapshotRow>, ResultsError> {
    let text = std::fs::read_to_string(path).map_err(|e| fail(path, e))?;
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| serde_json::from_str(l).map_err(|e| fail(path, format!("line {}: {e}", i + 1))))
        .collect()
}

fn read_run(dir: &Path, index: usize) -> Result<RunData, ResultsError> {
    let gens = dir.join("generations.csv");
    let generations = if gens.exists() {
        read_generations(&gens)?
    } else {
        Vec::new()
    };
    let mut snapshots = Vec::new();
    if let Ok(entries) = std::fs::read_dir(dir.join("snapshots")) {
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().into_owned();
            if let Some(n) = name.strip_prefix("evaluations-").and_then(|s| s.strip_suffix(".jsonl")) {
                if let Ok(n) = n.parse::<u64>() {
                    snapshots.push((n, e.path()));
                }
            }
        }
    }
    snapshots.sort();
    let best = dir.join("best.robot.json");
    let summary = std::fs::read_to_string(dir.join("summary.json"))
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok());
    Ok(RunData {
        dir: dir.to_path_buf(),
        index,
        generations,
        snapshots,
        best_robot: best.exists().then_some(best),
        summary,
    })
}

/// Reads one experiment folder (it must hold `experiment.toml`).
pub fn read_experiment(dir: &Path) -> Result<ExperimentData, ResultsError> {
    let cfg_path = dir.join("experiment.toml");
    let text = std::fs::read_to_string(&cfg_path).map_err(|e| fail(&cfg_path, e))?;
    let config: toml::Table = text.parse().map_err(|e| fail(&cfg_path, e))?;
    let folder = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "experiment".into());
    let name = config
        .get("name")
        .and_then(|v| v.as_str())
        .map(str::to_string)
        .unwrap_or(folder);
    let mut runs = Vec::new();
    let mut entries: Vec<_> = std::fs::read_dir(dir).map_err(|e| fail(dir, e))?.flatten().collect();
    entries.sort_by_key(|e| e.file_name());
    for e in entries {
        let fname = e.file_name().to_string_lossy().into_owned();
        if let Some(i) = fname.strip_prefix("run-").and_then(|s| s.parse::<usize>().ok()) {
            if e.path().is_dir() {
                runs.push(read_run(&e.path(), i)?);
            }
        }
    }
    Ok(ExperimentData {
        dir: dir.to_path_buf(),
        name,
        config,
        runs,
    })
}

/// Finds every experiment folder at or below each root (up to 4 levels deep), in path order.
pub fn discover(roots: &[PathBuf]) -> Result<Vec<ExperimentData>, ResultsError> {
    fn walk(dir: &Path, depth: usize, out: &mut Vec<PathBuf>) {
        if dir.join("experiment.toml").is_file() {
            out.push(dir.to_path_buf());
            return;
        }
        if depth == 0 {
            return;
        }
        if let Ok(entries) = std::fs::read_dir(dir) {
            let mut dirs: Vec<PathBuf> = entries.flatten().map(|e| e.path()).filter(|p| p.is_dir()).collect();
            dirs.sort();
            for d in dirs {
                walk(&d, depth - 1, out);
            }
        }
    }
    let mut found = Vec::new();
    for r in roots {
        if !r.is_dir() {
            return Err(fail(r, "not a folder"));
        }
        walk(r, 4, &mut found);
    }
    found.sort();
    found.dedup();
    if found.is_empty() {
        let names: Vec<String> = roots.iter().map(|r| r.display().to_string()).collect();
        return Err(ResultsError {
            path: names.join(", "),
            msg: "no experiment.toml found (is this the output of `vsrlab run`?)".into(),
        });
    }
    found.iter().map(|d| read_experiment(d)).collect()
}

/// Groups experiments into settings by name (experiments with the same name, e.g. the same
/// file run into two folders, pool their runs). Settings are sorted by name; each lists its
/// experiments' indices.
pub fn settings(experiments: &[ExperimentData]) -> Vec<(String, Vec<usize>)> {
    let mut out: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, e) in experiments.iter().enumerate() {
        match out.iter_mut().find(|(n, _)| n == &e.name) {
            Some((_, v)) => v.push(i),
            None => out.push((e.name.clone(), vec![i])),
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(path: &Path, text: &str) {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }

    #[test]
    fn discovers_and_reads_a_results_tree() {
        let tmp = tempfile::tempdir().unwrap();
        let root = tmp.path();
        for (folder, name) in [("a", "ga-flat"), ("b", "es-flat"), ("nested/c", "ga-flat")] {
            let d = root.join(folder);
            write(
                &d.join("experiment.toml"),
                &format!("name = \"{name}\"\nruns = 1\n[task]\nfitness = \"velocity\"\n"),
            );
            write(
                &d.join("run-00/generations.csv"),
                "generation,evaluations,births,best_fitness,population_median,population_best\n1,40,40,0.5,0.1,0.5\n2,80,80,NaN,0.2,0.7\n",
            );
            write(
                &d.join("run-00/snapshots/evaluations-0000080.jsonl"),
                "{\"generation\":2,\"evaluations\":80,\"index\":0,\"birth_generation\":1,\"seed\":3,\"fitness\":0.7,\"distance\":7.0,\"velocity\":0.7,\"voxels\":4,\"body\":\"##/##\",\"error\":null,\"genotype\":[0.1,-0.2]}\n",
            );
            write(&d.join("run-00/snapshots/evaluations-0000040.jsonl"), "");
            write(&d.join("run-00/summary.json"), "{\"best_fitness\": 0.7}");
        }
        let exps = discover(&[root.to_path_buf()]).unwrap();
        assert_eq!(exps.len(), 3);
        let s = settings(&exps);
        assert_eq!(
            s.iter().map(|x| x.0.as_str()).collect::<Vec<_>>(),
            vec!["es-flat", "ga-flat"]
        );
        assert_eq!(s[1].1.len(), 2);
        let run = &exps[0].runs[0];
        assert_eq!(run.generations.len(), 2);
        assert!(run.generations[1].best_fitness.is_nan());
        assert_eq!(run.final_best(), 0.7);
        assert_eq!(run.snapshots.iter().map(|s| s.0).collect::<Vec<_>>(), vec![40, 80]);
        let rows = read_snapshot(&run.final_snapshot().unwrap().1).unwrap();
        assert_eq!(rows[0].genotype, vec![0.1, -0.2]);
        assert_eq!(rows[0].body.as_deref(), Some("##/##"));
        assert_eq!(exps[0].fitness_kind(), "velocity");
        assert!(discover(&[root.join("a/run-00")]).is_err());
    }
}
