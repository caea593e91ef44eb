//! The experiment file: one TOML document describing representation, task, optimizer, stop
//! criterion, runs and outputs (documented field by field in `docs/experiments.md`).
//!
//! Every table denies unknown fields. Errors name the file, the line and the dotted field path,
//! e.g. `quickstart.toml, line 14: field 'optimizer.population_size': invalid type: string
//! "many", expected usize`. The `[task]` and `[optimizer]` tables are decoded through their
//! registries ([`vsrlab_tasks::registry`], [`crate::optimizers`]) by `kind`.

mod error;
mod sweep;
mod task;

pub use error::ConfigError;
pub use sweep::{expand, MAX_SETTINGS};
pub use task::TaskConfig;

use crate::genotypes::{self, GenotypeConfig, GenotypeKind};
use crate::optimizers::{self, FieldError, OptimizerConfig};
use error::{dotted, line_column, locate, Step};
use serde::{Deserialize, Serialize};
use vsrlab_tasks::Representation;

/// A whole experiment.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Experiment {
    /// A short name (defaults to the file name without extension).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// The setting analyses pool this experiment's runs into (default: its name): experiments
    /// of a sweep that share it count as runs of one setting (e.g. fine-tuning from several
    /// source robots, one experiment each).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub setting: Option<String>,
    /// Number of independent runs.
    pub runs: usize,
    /// Base seed; run r uses [`run_seed`]`(seed, r)`.
    pub seed: u64,
    /// Genotype → robot mapping.
    pub representation: Representation,
    /// The `[genotype]` table, by kind ([`genotypes::GENOTYPES`]); `None`: flat vectors.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub genotype: Option<GenotypeConfig>,
    /// The task, its fitness and how episodes are seeded.
    pub task: TaskConfig,
    /// The optimizer and its parameters.
    pub optimizer: OptimizerConfig,
    /// When each run stops.
    pub stop: StopConfig,
    /// What is written.
    pub output: OutputConfig,
}

/// The experiment file as written: `[task]` and `[optimizer]` kept as tables until their kind
/// is known.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExperimentFile {
    #[serde(default)]
    name: Option<String>,
    #[serde(default)]
    description: Option<String>,
    #[serde(default)]
    setting: Option<String>,
    #[serde(default = "one")]
    runs: usize,
    #[serde(default)]
    seed: u64,
    #[serde(default)]
    representation: Option<Representation>,
    #[serde(default)]
    genotype: Option<toml::Table>,
    task: toml::Table,
    optimizer: toml::Table,
    stop: StopConfig,
    #[serde(default)]
    output: OutputConfig,
    #[serde(default)]
    transfer: Option<TransferConfig>,
}

/// `[transfer]`: fix a module of an evolved robot's brain in this experiment's brain (thesis
/// §4.2.4.1: an attention module moved to another body). Applied when the file is read: the
/// resolved `experiment.toml` holds the module's genes in the brain, not this table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct TransferConfig {
    /// The robot file (JSON) whose brain gives the module, e.g. a run's `best.robot.json`.
    from: std::path::PathBuf,
}

fn one() -> usize {
    1
}

fn yes() -> bool {
    true
}

/// The seed of run `run` derived from the base seed (SplitMix64 of both), so runs of one
/// experiment are independent and adding runs never changes earlier ones.
pub fn run_seed(base: u64, run: usize) -> u64 {
    let mut z = base
        .wrapping_add(0x9E37_79B9_7F4A_7C15u64.wrapping_mul(run as u64 + 1))
        .wrapping_add(0x5851_F42D_4C95_7F2D);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Stop criteria, checked after every generation; the run stops when any holds. At least one of
/// `evaluations`, `births`, `generations` and `wall_seconds` must be set.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StopConfig {
    /// Fitness evaluations (births plus re-evaluations).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub evaluations: Option<u64>,
    /// New genotypes evaluated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub births: Option<u64>,
    /// Generations (ask/tell cycles).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub generations: Option<u64>,
    /// Wall-clock seconds of this run (summed over resumed sessions). Makes results depend on
    /// the machine.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_seconds: Option<f64>,
    /// Stop once the best fitness reaches this value.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target_fitness: Option<f64>,
}

impl StopConfig {
    /// How much of a run is done, in [0, 1]: the largest share of any budget it has used after
    /// these counts and wall seconds (progress bars, ETAs, the live monitor).
    pub fn fraction(&self, evaluations: u64, births: u64, generations: u64, wall_seconds: f64) -> f64 {
        let share = |done: u64, budget: Option<u64>| budget.map_or(0.0, |n| done as f64 / n.max(1) as f64);
        let wall = self.wall_seconds.map_or(0.0, |s| wall_seconds / s);
        share(evaluations, self.evaluations)
            .max(share(births, self.births))
            .max(share(generations, self.generations))
            .max(wall)
            .clamp(0.0, 1.0)
    }
}

/// What a run writes besides its per-generation CSV and its checkpoint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutputConfig {
    /// Write the population every this many evaluations (0: never; the final population is
    /// always written).
    #[serde(default = "thousand")]
    pub snapshot_every: u64,
    /// Save the best robot of each run as a robot file.
    #[serde(default = "yes")]
    pub save_best: bool,
    /// Minimum seconds between checkpoints (0: after every generation). Large populations of
    /// long genotypes make big checkpoints; a few tens of seconds bounds the cost.
    #[serde(default)]
    pub checkpoint_interval: f64,
}

fn thousand() -> u64 {
    1000
}

impl Default for OutputConfig {
    fn default() -> Self {
        Self {
            snapshot_every: 1000,
            save_best: true,
            checkpoint_interval: 0.0,
        }
    }
}

/// Turns a serde_path_to_error path into steps.
fn steps(path: &serde_path_to_error::Path) -> Vec<Step> {
    path.iter()
        .filter_map(|segment| match segment {
            serde_path_to_error::Segment::Map { key } => Some(Step::Key(key.clone())),
            serde_path_to_error::Segment::Seq { index } => Some(Step::Index(*index)),
            _ => None,
        })
        .collect()
}

/// The dotted path and value of the first NaN or infinite number in `value` (an array's
/// elements are reported at the array's path): no field of an experiment takes one, and serde
/// would otherwise read it as `null` ("invalid type: null").
fn first_non_finite(value: &toml::Value, path: &str) -> Option<(String, f64)> {
    match value {
        toml::Value::Float(v) if !v.is_finite() => Some((path.to_string(), *v)),
        toml::Value::Array(items) => items.iter().find_map(|v| first_non_finite(v, path)),
        toml::Value::Table(t) => t.iter().find_map(|(k, v)| {
            let inner = if path.is_empty() {
                k.clone()
            } else {
                format!("{path}.{k}")
            };
            first_non_finite(v, &inner)
        }),
        _ => None,
    }
}

/// Parses an experiment from TOML text; `origin` names the source in errors. Also validates
/// the values (see [`Experiment::validate`]) and fills in defaults that depend on other fields
/// (see [`Experiment::resolve`]).
pub fn parse(text: &str, origin: &str) -> Result<Experiment, ConfigError> {
    let deserializer = toml::de::Deserializer::parse(text).map_err(|e| {
        let position = e.span().map(|s| line_column(text, s.start));
        ConfigError {
            origin: origin.to_string(),
            line: position.map(|p| p.0),
            column: position.map(|p| p.1),
            field: String::new(),
            message: format!("invalid TOML: {}", e.message()),
        }
    })?;
    if let Ok(table) = text.parse::<toml::Table>() {
        if let Some((field, v)) = first_non_finite(&toml::Value::Table(table), "") {
            return Err(ConfigError::at_field(
                origin,
                text,
                &field,
                format!("must be a finite number, got {v}"),
            ));
        }
    }
    let file: ExperimentFile = serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let mut path = steps(e.path());
        let inner = e.into_inner();
        let message = inner.message().to_string();
        // An unknown field: point at the field itself.
        if let Some(name) = message
            .strip_prefix("unknown field `")
            .and_then(|rest| rest.split('`').next())
        {
            if path.last() != Some(&Step::Key(name.to_string())) {
                path.push(Step::Key(name.to_string()));
            }
        }
        let span = locate(text, &path).or_else(|| inner.span());
        let position = span.map(|s| line_column(text, s.start));
        ConfigError {
            origin: origin.to_string(),
            line: position.map(|p| p.0),
            column: position.map(|p| p.1),
            field: dotted(&path),
            message,
        }
    })?;
    let at_field = |e: FieldError| ConfigError::at_field(origin, text, &e.path, e.message);
    let in_table = |table: &str, e: FieldError| at_field(e.at(table));
    let task = TaskConfig::decode(file.task).map_err(|e| in_table("task", e))?;
    let mut genotype = file
        .genotype
        .map(genotypes::decode_table)
        .transpose()
        .map_err(|e| in_table("genotype", e))?;
    let implied = genotype.as_ref().and_then(|kind| kind.implied_representation(&task));
    let mut representation = file.representation.or(implied).ok_or_else(|| ConfigError {
        origin: origin.to_string(),
        line: None,
        column: None,
        field: "representation".into(),
        message: "missing: give a [representation] table (body, sensors, brain)".into(),
    })?;
    if let Some(transfer) = &file.transfer {
        let field = |message: String| ConfigError::at_field(origin, text, "transfer.from", message);
        let source = vsrlab_tasks::files::load_robot(&transfer.from).map_err(|e| field(e.to_string()))?;
        representation
            .brain
            .as_kind_mut()
            .transfer_from(&source.brain)
            .map_err(|e| field(format!("{}: {e}", transfer.from.display())))?;
    }
    if let Some(kind) = &mut genotype {
        kind.kind_mut().load_files(&mut representation).map_err(at_field)?;
    }
    let optimizer = optimizers::decode_table(file.optimizer).map_err(|e| in_table("optimizer", e))?;
    let experiment = Experiment {
        name: file.name,
        description: file.description,
        setting: file.setting,
        runs: file.runs,
        seed: file.seed,
        representation,
        genotype,
        task,
        optimizer,
        stop: file.stop,
        output: file.output,
    }
    .resolve();
    experiment.validate().map_err(at_field)?;
    Ok(experiment)
}

/// An experiment file's text (a regular file of bounded size, as every file vsrlab reads).
fn read_experiment_text(path: &std::path::Path) -> Result<String, ConfigError> {
    vsrlab_tasks::files::read_text(path).map_err(|e| {
        let message = match e {
            vsrlab_tasks::files::FileError::Io { source, .. } => source.to_string(),
            vsrlab_tasks::files::FileError::Invalid { msg, .. } => msg,
        };
        ConfigError {
            origin: path.display().to_string(),
            line: None,
            column: None,
            field: String::new(),
            message,
        }
    })
}

/// Reads and parses an experiment file.
pub fn load(path: &std::path::Path) -> Result<Experiment, ConfigError> {
    let origin = path.display().to_string();
    let text = read_experiment_text(path)?;
    let mut experiment = parse(&text, &origin)?;
    if experiment.name.is_none() {
        let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
        if let Some(Err(FieldError { message, .. })) = stem.as_deref().map(check_name) {
            return Err(ConfigError {
                origin,
                line: None,
                column: None,
                field: "name".into(),
                message: format!("the file name gives no usable name ({message}): set `name = \"…\"` in the file"),
            });
        }
        experiment.name = stem;
    }
    Ok(experiment)
}

/// The task of an experiment file, or of the `experiment.toml` in a `vsrlab run` output folder:
/// what replays on "that experiment's task" read (the CLI's `--task-of`, Python's `task=`).
pub fn load_task(path: &std::path::Path) -> Result<vsrlab_tasks::TaskSpec, ConfigError> {
    let file = if path.is_dir() {
        path.join("experiment.toml")
    } else {
        path.to_path_buf()
    };
    load(&file).map(|e| e.task.spec)
}

/// Reads an experiment file that may hold a `[sweep]`: its experiments, one per setting (one
/// when there is no sweep, exactly as [`load`] gives it).
pub fn load_all(path: &std::path::Path) -> Result<Vec<Experiment>, ConfigError> {
    let text = read_experiment_text(path)?;
    if !text.contains("sweep") {
        return load(path).map(|e| vec![e]);
    }
    let stem = path
        .file_stem()
        .map_or("experiment".into(), |s| s.to_string_lossy().into_owned());
    let mut experiments = expand(&text, &path.display().to_string(), &stem)?;
    if let [single] = experiments.as_mut_slice() {
        if single.name.is_none() {
            return load(path).map(|e| vec![e]);
        }
    }
    Ok(experiments)
}

/// Most runs of one experiment.
pub const MAX_RUNS: usize = 100_000;

/// Longest experiment name.
pub const MAX_NAME_LENGTH: usize = 100;

/// Checks an experiment name, which becomes a folder (`out/<name>`): one path component of
/// letters, digits, `-`, `_`, `.` and `+`, not starting with `.`, at most [`MAX_NAME_LENGTH`]
/// characters. So a name can never point outside the output folder (`..`, `/`, `\\`).
pub fn check_name(name: &str) -> Result<(), FieldError> {
    let allowed = |c: char| c.is_alphanumeric() || matches!(c, '-' | '_' | '.' | '+');
    if name.is_empty() || name.chars().count() > MAX_NAME_LENGTH {
        return Err(FieldError::message(format!(
            "must have 1 to {MAX_NAME_LENGTH} characters"
        )));
    }
    if name.starts_with('.') {
        return Err(FieldError::message(format!(
            "'{name}' must not start with '.' (it becomes a folder name)"
        )));
    }
    match name.chars().find(|&c| !allowed(c)) {
        Some(c) => Err(FieldError::message(format!(
            "'{name}' holds {c:?}: use letters, digits, '-', '_', '.' and '+' only (it becomes a folder name)"
        ))),
        None => Ok(()),
    }
}

impl Experiment {
    /// Fills in defaults that depend on other fields (e.g. MAP-Elites axes over the body grid,
    /// the ES parent count).
    pub fn resolve(mut self) -> Self {
        let cells = self.representation.body.size();
        let genes = self.representation.genotype_length().ok();
        self.optimizer.resolve(cells, genes);
        self
    }

    /// Checks values that the types cannot: returns the dotted field path and the message.
    pub fn validate(&self) -> Result<(), FieldError> {
        let err = |field: &str, msg: String| Err(FieldError::new(field.to_string(), msg));
        if self.runs == 0 || self.runs > MAX_RUNS {
            return err("runs", format!("must be in 1..={MAX_RUNS}, got {}", self.runs));
        }
        if let Some(Err(e)) = self.name.as_deref().map(check_name) {
            return Err(e.at("name"));
        }
        if let Err(e) = self.representation.validate() {
            return Err(e
                .field_error()
                .unwrap_or_else(|| FieldError::new("representation", e.to_string())));
        }
        self.genotype_kind().validate(self)?;
        self.task.validate()?;
        let s = &self.stop;
        if s.evaluations.is_none() && s.births.is_none() && s.generations.is_none() && s.wall_seconds.is_none() {
            return err(
                "stop",
                "set at least one of evaluations, births, generations, wall_seconds".into(),
            );
        }
        for (field, value) in [
            ("stop.evaluations", s.evaluations),
            ("stop.births", s.births),
            ("stop.generations", s.generations),
        ] {
            if value == Some(0) {
                return err(
                    field,
                    "must be at least 1 (0 would stop before anything is evaluated)".into(),
                );
            }
        }
        if let Some(w) = s.wall_seconds {
            if !(w.is_finite() && w > 0.0) {
                return err("stop.wall_seconds", format!("must be a positive number, got {w}"));
            }
        }
        if let Some(t) = s.target_fitness {
            if !t.is_finite() {
                return err(
                    "stop.target_fitness",
                    format!("must be a finite number, got {t} (no fitness can reach it, or every one does)"),
                );
            }
        }
        let o = &self.output;
        if !(o.checkpoint_interval.is_finite() && o.checkpoint_interval >= 0.0) {
            return err("output.checkpoint_interval", "must be ≥ 0 seconds".into());
        }
        let kind = self.optimizer.kind();
        kind.validate().map_err(|e| e.at("optimizer"))?;
        let objectives = self.task.spec.task().objectives().len();
        if objectives > 1 && !kind.multi_objective() && !kind.lexicographic() {
            return err(
                "optimizer.kind",
                format!(
                    "{} optimizes one objective but task.fitness has {objectives}: use nsga2, ga (lexicographic), or one objective",
                    kind.name()
                ),
            );
        }
        Ok(())
    }

    /// The experiment as TOML, every default written out (the "resolved config").
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("experiments always serialise to TOML")
    }

    /// The genotype kind: the `[genotype]` table's, or flat vectors without one.
    pub fn genotype_kind(&self) -> &dyn GenotypeKind {
        match &self.genotype {
            Some(kind) => &**kind,
            None => &genotypes::vector::VECTOR,
        }
    }

    /// Whether each of the task's objectives is maximised or minimised, as optimizers take them.
    pub fn senses(&self) -> Vec<vsrlab_evolution::Sense> {
        self.task
            .spec
            .task()
            .objectives()
            .iter()
            .map(|o| match o.sense {
                vsrlab_tasks::Sense::Maximize => vsrlab_evolution::Sense::Maximize,
                vsrlab_tasks::Sense::Minimize => vsrlab_evolution::Sense::Minimize,
            })
            .collect()
    }

    /// The run seeds, in order.
    pub fn run_seeds(&self) -> Vec<u64> {
        (0..self.runs).map(|r| run_seed(self.seed, r)).collect()
    }
}
