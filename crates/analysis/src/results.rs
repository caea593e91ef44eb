//! Reading the output of `vsrlab run` (docs/experiments.md): an experiment folder holds the
//! resolved `experiment.toml` and one `run-NN/` folder per run with `generations.csv`,
//! `snapshots/evaluations-NNNNNNN.jsonl`, `best.robot.json` and `summary.json` (the layout is
//! [`RunFolder`]'s).
//!
//! The rows are the types the runner writes ([`crate::rows`]); CSV columns are looked up by
//! name, so files that lack a column still read (NaN, or 0 for counts); the configuration stays
//! a TOML table (group-by keys are its dotted paths).

pub use crate::rows::{GenerationRow, SnapshotRow};
use crate::run_folder::{RunFiles, RunFolder};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// Why results could not be read; every variant names the file or folder.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// A file or folder could not be read.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// A CSV file is malformed.
    #[error("{}: {source}", path.display())]
    Csv {
        /// The file.
        path: PathBuf,
        /// The parser's report.
        source: csv::Error,
    },
    /// A CSV row lacks an integer column analysis needs.
    #[error("{}: row {row}: no integer column '{column}'", path.display())]
    MissingColumn {
        /// The file.
        path: PathBuf,
        /// The row (1 = the header).
        row: usize,
        /// The column.
        column: &'static str,
    },
    /// A snapshot line is not valid JSON of a population member.
    #[error("{}: line {line}: {source}", path.display())]
    Snapshot {
        /// The snapshot file.
        path: PathBuf,
        /// The line (1-based).
        line: usize,
        /// The parser's report.
        source: serde_json::Error,
    },
    /// `experiment.toml` is not valid TOML.
    #[error("{}: {source}", path.display())]
    Config {
        /// The file.
        path: PathBuf,
        /// The parser's report.
        source: toml::de::Error,
    },
    /// A results root is not a folder.
    #[error("{}: not a folder", path.display())]
    NotAFolder {
        /// The path given.
        path: PathBuf,
    },
    /// No experiment folder below the roots.
    #[error("{roots}: no experiment.toml found (is this the output of `vsrlab run`?)")]
    NoExperiment {
        /// The roots searched, comma-separated.
        roots: String,
    },
    /// A `--group-by` key is not in an experiment's resolved configuration.
    #[error("group-by: '{key}' is not a setting of {} (keys are dotted paths of experiment.toml, e.g. task.terrain)", path.display())]
    NoSuchKey {
        /// The key.
        key: String,
        /// The experiment's `experiment.toml`.
        path: PathBuf,
    },
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> ResultsError + '_ {
    move |source| ResultsError::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn csv_error(path: &Path) -> impl Fn(csv::Error) -> ResultsError + '_ {
    move |source| ResultsError::Csv {
        path: path.to_path_buf(),
        source,
    }
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

    /// The run's files.
    pub fn files(&self) -> RunFiles {
        RunFiles::new(&self.dir, self.index)
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

    /// The experiment's output folder.
    pub fn folder(&self) -> RunFolder {
        RunFolder::new(&self.dir)
    }

    /// How tables name one of its runs: the experiment folder and the run folder's name
    /// (`out/ga/run-03`).
    pub fn run_label(&self, run: &RunData) -> String {
        let name = run
            .dir
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        format!("{}/{name}", self.dir.display())
    }

    /// What the fitness is: the task's metric (`velocity`, `distance`), the first objective's
    /// metric of a multi-objective task; when the file sets none, the task kind's own default
    /// (an EvoGym task's `reward`, locomotion's `velocity`), or `velocity` for a task this
    /// version cannot read.
    pub fn fitness_kind(&self) -> String {
        let first = match self.config_value("task.fitness") {
            Some(toml::Value::Array(items)) => items.first(),
            other => other,
        };
        let metric = match first {
            Some(toml::Value::String(s)) => Some(s.clone()),
            Some(toml::Value::Table(t)) => t.get("metric").and_then(|m| m.as_str()).map(str::to_string),
            _ => None,
        };
        metric
            .or_else(|| self.default_objective())
            .unwrap_or_else(|| "velocity".to_string())
    }

    /// The first objective the experiment's task has by default (its `[task]` table read as the
    /// runner reads it).
    fn default_objective(&self) -> Option<String> {
        let table = self
            .config_value("task")
            .cloned()
            .unwrap_or(toml::Value::Table(Default::default()));
        let json = serde_json::to_value(table).ok()?;
        let spec = vsrlab_tasks::registry::TaskSpec::from_json(json).ok()?;
        spec.task().objectives().first().map(|o| o.metric.clone())
    }
}

/// Reads `generations.csv`.
pub fn read_generations(path: &Path) -> Result<Vec<GenerationRow>, ResultsError> {
    let mut reader = csv::Reader::from_path(path).map_err(csv_error(path))?;
    let headers = reader.headers().map_err(csv_error(path))?.clone();
    let col: HashMap<&str, usize> = headers.iter().enumerate().map(|(i, h)| (h, i)).collect();
    let mut rows = Vec::new();
    for (line, rec) in reader.records().enumerate() {
        let rec = rec.map_err(csv_error(path))?;
        let num = |name: &str| -> f64 {
            col.get(name)
                .and_then(|&i| rec.get(i))
                .and_then(|v| v.trim().parse::<f64>().ok())
                .unwrap_or(f64::NAN)
        };
        let int = |column: &'static str| -> Result<u64, ResultsError> {
            col.get(column)
                .and_then(|&i| rec.get(i))
                .and_then(|v| v.trim().parse::<u64>().ok())
                .ok_or_else(|| ResultsError::MissingColumn {
                    path: path.to_path_buf(),
                    row: line + 2,
                    column,
                })
        };
        let count = |name: &str| {
            col.get(name)
                .and_then(|&i| rec.get(i))
                .and_then(|v| v.trim().parse::<u64>().ok())
        };
        let best_stats = headers
            .iter()
            .enumerate()
            .filter_map(|(i, h)| h.strip_prefix("best_").filter(|_| h != "best_fitness").map(|n| (i, n)))
            .map(|(i, name)| {
                let value = rec.get(i).and_then(|v| v.trim().parse::<f64>().ok());
                (name.to_string(), value.unwrap_or(f64::NAN))
            })
            .collect();
        rows.push(GenerationRow {
            generation: int("generation")?,
            evaluations: int("evaluations")?,
            births: count("births").unwrap_or(0),
            failures: count("failures").unwrap_or(0),
            best_fitness: num("best_fitness"),
            batch_best: num("batch_best"),
            batch_median: num("batch_median"),
            population_best: num("population_best"),
            population_median: num("population_median"),
            population_size: count("population_size").unwrap_or(0),
            distinct_bodies: count("distinct_bodies").unwrap_or(0),
            mean_voxels: num("mean_voxels"),
            species: count("species"),
            archive_cells: count("archive_cells"),
            best_stats,
        });
    }
    Ok(rows)
}

/// Reads a snapshot (JSON lines).
pub fn read_snapshot(path: &Path) -> Result<Vec<SnapshotRow>, ResultsError> {
    let text = std::fs::read_to_string(path).map_err(io_error(path))?;
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l).map_err(|source| ResultsError::Snapshot {
                path: path.to_path_buf(),
                line: i + 1,
                source,
            })
        })
        .collect()
}

fn read_run(files: &RunFiles) -> Result<RunData, ResultsError> {
    let gens = files.generations_csv();
    let generations = if gens.exists() {
        read_generations(&gens)?
    } else {
        Vec::new()
    };
    let best = files.best_robot();
    let summary = std::fs::read_to_string(files.summary_json())
        .ok()
        .and_then(|t| serde_json::from_str(&t).ok());
    Ok(RunData {
        dir: files.dir().to_path_buf(),
        index: files.index(),
        generations,
        snapshots: files.snapshots_on_disk(),
        best_robot: best.exists().then_some(best),
        summary,
    })
}

/// Reads one experiment folder (it must hold `experiment.toml`).
pub fn read_experiment(dir: &Path) -> Result<ExperimentData, ResultsError> {
    let folder = RunFolder::new(dir);
    let cfg_path = folder.experiment_toml();
    let text = std::fs::read_to_string(&cfg_path).map_err(io_error(&cfg_path))?;
    let config: toml::Table = text.parse().map_err(|source| ResultsError::Config {
        path: cfg_path.clone(),
        source,
    })?;
    let folder_name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "experiment".into());
    // the setting the runs pool into: `setting` when the experiment names one, else its name
    let name = ["setting", "name"]
        .iter()
        .find_map(|key| config.get(*key).and_then(|v| v.as_str()))
        .map(str::to_string)
        .unwrap_or(folder_name);
    let runs = folder
        .runs_on_disk()
        .map_err(io_error(dir))?
        .iter()
        .map(read_run)
        .collect::<Result<_, _>>()?;
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
        if RunFolder::new(dir).is_experiment() {
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
            return Err(ResultsError::NotAFolder { path: r.clone() });
        }
        walk(r, 4, &mut found);
    }
    found.sort();
    found.dedup();
    if found.is_empty() {
        let names: Vec<String> = roots.iter().map(|r| r.display().to_string()).collect();
        return Err(ResultsError::NoExperiment {
            roots: names.join(", "),
        });
    }
    found.iter().map(|d| read_experiment(d)).collect()
}

/// Renames every experiment after its values of `keys` (dotted paths of its resolved
/// `experiment.toml`, e.g. `task.terrain` or `representation.body.pressure_control`), as
/// `key=value` joined by `, `: the settings then pool the runs of experiments that agree on those
/// keys, whatever their other settings (a sweep's other axes). No keys: names unchanged.
pub fn group_by(experiments: &mut [ExperimentData], keys: &[String]) -> Result<(), ResultsError> {
    if keys.is_empty() {
        return Ok(());
    }
    for e in experiments.iter_mut() {
        let mut parts = Vec::with_capacity(keys.len());
        for key in keys {
            let value = value_at(&e.config, key).ok_or_else(|| ResultsError::NoSuchKey {
                key: key.clone(),
                path: RunFolder::new(&e.dir).experiment_toml(),
            })?;
            parts.push(format!("{key}={}", short_value(value)));
        }
        e.name = parts.join(", ");
    }
    Ok(())
}

/// The value at a dotted path of a TOML table.
fn value_at<'a>(table: &'a toml::Table, key: &str) -> Option<&'a toml::Value> {
    let mut parts = key.split('.');
    let mut value = table.get(parts.next()?)?;
    for part in parts {
        value = value.as_table()?.get(part)?;
    }
    Some(value)
}

/// A value as a setting's name shows it: strings without quotes, tables by their `kind` when they
/// have one, anything else as TOML.
fn short_value(value: &toml::Value) -> String {
    match value {
        toml::Value::String(s) => s.clone(),
        toml::Value::Table(t) => match t.get("kind").and_then(toml::Value::as_str) {
            Some(kind) => kind.to_string(),
            None => value.to_string(),
        },
        other => other.to_string(),
    }
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
    fn group_by_pools_experiments_that_agree_on_the_keys() {
        let dir = tempfile::tempdir().unwrap();
        let configs = [
            (
                "a",
                "name = \"s-flat-ho\"\n[task]\nterrain = \"flat\"\n[representation.brain]\nkind = \"mlp\"\n",
            ),
            (
                "b",
                "name = \"s-flat-he\"\n[task]\nterrain = \"flat\"\n[representation.brain]\nkind = \"graph\"\n",
            ),
            (
                "c",
                "name = \"s-hilly-ho\"\n[task]\nterrain = \"hilly-1-10\"\n[representation.brain]\nkind = \"mlp\"\n",
            ),
        ];
        for (folder, text) in configs {
            write(&dir.path().join(folder).join("experiment.toml"), text);
        }
        let mut exps = discover(&[dir.path().to_path_buf()]).unwrap();
        group_by(&mut exps, &["task.terrain".to_string()]).unwrap();
        let s = settings(&exps);
        let names: Vec<(&str, usize)> = s.iter().map(|(n, e)| (n.as_str(), e.len())).collect();
        assert_eq!(names, [("task.terrain=flat", 2), ("task.terrain=hilly-1-10", 1)]);
        group_by(
            &mut exps,
            &["task.terrain".to_string(), "representation.brain".to_string()],
        )
        .unwrap();
        assert_eq!(exps[1].name, "task.terrain=flat, representation.brain=graph");
        let err = group_by(&mut exps, &["task.terain".to_string()])
            .unwrap_err()
            .to_string();
        assert!(err.starts_with("group-by: 'task.terain' is not a setting of"), "{err}");
    }

    #[test]
    fn a_setting_label_pools_differently_named_experiments() {
        let tmp = tempfile::tempdir().unwrap();
        for (folder, head) in [
            ("x", "name = \"moved-a\"\nsetting = \"moved\""),
            ("y", "name = \"moved-b\"\nsetting = \"moved\""),
            ("z", "name = \"scratch\""),
        ] {
            let d = tmp.path().join(folder);
            write(&d.join("experiment.toml"), &format!("{head}\nruns = 1\n"));
            write(
                &d.join("run-00/generations.csv"),
                "generation,evaluations,births,best_fitness\n1,4,4,0.5\n",
            );
        }
        let exps = discover(&[tmp.path().to_path_buf()]).unwrap();
        let s = settings(&exps);
        assert_eq!(
            s,
            vec![("moved".to_string(), vec![0, 1]), ("scratch".to_string(), vec![2])]
        );
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
                "{\"generation\":2,\"evaluations\":80,\"index\":0,\"birth_generation\":1,\"seed\":3,\"fitness\":0.7,\"distance\":7.0,\"velocity\":0.7,\"voxels\":4,\"body\":\"##/##\",\"error\":null,\"descriptor\":[],\"genotype\":[0.1,-0.2]}\n",
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
        assert_eq!(rows[0].genotype, serde_json::json!([0.1, -0.2]));
        assert_eq!(rows[0].body(), Some("##/##"));
        let graph = root.join("graph.jsonl");
        let line = r#"{"generation": 3, "evaluations": 9, "index": 0, "birth_generation": 2, "seed": 1, "fitness": 0.5, "distance": null, "velocity": null, "voxels": null, "body": null, "error": null, "descriptor": [], "genotype": {"neurons": [], "edges": [], "parameters": []}}"#;
        write(&graph, line);
        let rows = read_snapshot(&graph).unwrap();
        assert_eq!(
            rows[0].genotype["neurons"],
            serde_json::json!([]),
            "a graph genotype is read whole"
        );
        assert_eq!(rows[0].fitness(), Some(0.5));
        assert_eq!(exps[0].fitness_kind(), "velocity");
        let mut two = exps[0].clone();
        two.config =
            toml::from_str("[task]\nfitness = [{ metric = \"locomotion\", sense = \"minimize\" }, \"sensing\"]")
                .unwrap();
        assert_eq!(two.fitness_kind(), "locomotion", "the first objective of several");
        two.config = toml::from_str("[task]\nfitness = \"distance\"").unwrap();
        assert_eq!(two.fitness_kind(), "distance");
        // without `fitness`, the task kind's own objective (issue 56: an EvoGym run's reward was
        // called velocity)
        two.config = toml::from_str("[task]\nkind = \"evogym\"\nenv = \"BridgeWalker-v0\"").unwrap();
        assert_eq!(two.fitness_kind(), "reward");
        assert_eq!(exps[0].run_label(run), format!("{}/run-00", root.join("a").display()));
        assert_eq!(run.files().best_robot(), root.join("a/run-00/best.robot.json"));
        assert!(matches!(
            discover(&[root.join("a/run-00")]),
            Err(ResultsError::NoExperiment { .. })
        ));
        assert!(matches!(
            discover(&[root.join("missing")]),
            Err(ResultsError::NotAFolder { .. })
        ));
    }
}
