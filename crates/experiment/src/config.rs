//! The experiment file: one TOML document describing representation, task, optimizer, stop
//! criterion, runs and outputs (documented field by field in `docs/experiments.md`).
//!
//! Every table denies unknown fields. Errors name the file, the line and the dotted field path,
//! e.g. `quickstart.toml, line 14: field 'optimizer.population_size': invalid type: string
//! "many", expected usize`.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::ops::Range;
use vsrlab_tasks::{BodyPart, Locomotion, Representation, Terrain};

/// A whole experiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Experiment {
    /// A short name (defaults to the file name without extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Free text.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
    /// Number of independent runs.
    #[serde(default = "one")]
    pub runs: usize,
    /// Base seed; run r uses [`run_seed`]`(seed, r)`.
    #[serde(default)]
    pub seed: u64,
    /// Genotype → robot mapping.
    pub representation: Representation,
    /// The locomotion task and its fitness.
    pub task: TaskConfig,
    /// The optimizer and its parameters.
    pub optimizer: OptimizerConfig,
    /// When each run stops.
    pub stop: StopConfig,
    /// What is written.
    #[serde(default)]
    pub output: OutputConfig,
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

/// What is maximised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Fitness {
    /// Average x velocity over the episode (after the transient).
    #[default]
    Velocity,
    /// x distance travelled over the episode (after the transient).
    Distance,
}

/// The locomotion task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskConfig {
    /// `flat`, `hilly-H-W[-S]`, `steppy-H-W[-S]`, `uphill-A`, `downhill-A`.
    #[serde(default = "flat")]
    pub terrain: Terrain,
    /// Episode length, simulated seconds.
    #[serde(default = "thirty")]
    pub duration: f64,
    /// Initial seconds excluded from distance and velocity.
    #[serde(default)]
    pub transient: f64,
    /// What is maximised.
    #[serde(default)]
    pub fitness: Fitness,
    /// `true`: every evaluation uses its candidate's own seed (a new random terrain and sensor
    /// noise each time, a noisy fitness); `false`: every evaluation uses `episode_seed`.
    #[serde(default)]
    pub random_terrain_per_evaluation: bool,
    /// The episode seed when `random_terrain_per_evaluation` is false.
    #[serde(default)]
    pub episode_seed: u64,
}

fn flat() -> Terrain {
    Terrain::Flat
}

fn thirty() -> f64 {
    30.0
}

impl TaskConfig {
    /// The task as the episode runner takes it.
    pub fn locomotion(&self) -> Locomotion {
        Locomotion {
            terrain: self.terrain.clone(),
            duration: self.duration,
            transient: self.transient,
            ..Locomotion::default()
        }
    }
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

/// The optimizer, by `kind`, with its parameters (defaults: the thesis' values).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum OptimizerConfig {
    /// μ + λ genetic algorithm (thesis GA).
    Ga(GaParams),
    /// Canonical evolution strategy (thesis ES).
    Es(EsParams),
    /// CMA-ES.
    CmaEs(CmaParams),
    /// Speciated evolver (thesis SE-g / SE-s / SE-b).
    Se(SeParams),
    /// MAP-Elites (thesis ME).
    MapElites(MapElitesParams),
}

/// Parameters of the GA.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GaParams {
    /// μ (thesis 100).
    pub population_size: usize,
    /// λ (thesis 100).
    pub offspring_size: usize,
    /// Tournament size (thesis 5).
    pub tournament_size: usize,
    /// p_mut: mutation instead of crossover (thesis 0.2).
    pub mutation_probability: f64,
    /// Re-evaluate survivors every generation (noisy tasks).
    pub reevaluate_survivors: bool,
    /// Initial genes uniform in [min, max) (thesis [−1, 1]).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation (thesis 0.35).
    pub mutation_sigma: f64,
    /// Per-gene α range of the extended geometric crossover (thesis [−1, 2]).
    pub crossover_range: [f64; 2],
    /// σ′ of the Gaussian perturbation after crossover (thesis 0.1).
    pub crossover_sigma: f64,
}

impl Default for GaParams {
    fn default() -> Self {
        Self {
            population_size: 100,
            offspring_size: 100,
            tournament_size: 5,
            mutation_probability: 0.2,
            reevaluate_survivors: false,
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
            crossover_range: [-1.0, 2.0],
            crossover_sigma: 0.1,
        }
    }
}

/// Parameters of the canonical ES.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EsParams {
    /// λ, samples per generation (thesis text and code 40; Table 3.2 says 30).
    pub population_size: usize,
    /// μ, best samples moving the mean (default ⌊λ/4⌋).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub parents: Option<usize>,
    /// Fixed σ (thesis 0.35).
    pub sigma: f64,
    /// Initial mean uniform in [min, max) (thesis [−1, 1]).
    pub init_range: [f64; 2],
}

impl Default for EsParams {
    fn default() -> Self {
        Self {
            population_size: 40,
            parents: None,
            sigma: 0.35,
            init_range: [-1.0, 1.0],
        }
    }
}

/// Parameters of CMA-ES.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CmaParams {
    /// λ (default 4 + ⌊3 ln n⌋).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub population_size: Option<usize>,
    /// σ0 (thesis ch. 6: 0.5).
    pub sigma0: f64,
    /// Initial mean uniform in [min, max).
    pub init_range: [f64; 2],
    /// Active covariance update (negative weights).
    pub active: bool,
}

impl Default for CmaParams {
    fn default() -> Self {
        Self {
            population_size: None,
            sigma0: 0.5,
            init_range: [-1.0, 1.0],
            active: true,
        }
    }
}

/// What the speciated evolver clusters on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SeFeatures {
    /// SE-g: the genotype.
    #[default]
    Genotype,
    /// SE-s: the 16×16 dynamic pose (256 values).
    Shape,
    /// SE-b: the centre-of-mass |Δy| spectrum (100 values).
    Behaviour,
}

/// Parameters of the speciated evolver.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SeParams {
    /// Speciation features: `genotype` (SE-g), `shape` (SE-s), `behaviour` (SE-b).
    pub features: SeFeatures,
    /// n_pop (thesis 100).
    pub population_size: usize,
    /// k of k-means (thesis 10).
    pub species: usize,
    /// α, species preference (thesis 0.75).
    pub alpha: f64,
    /// n_elite, minimum species size whose best survives (thesis 5).
    pub elite_min_species_size: usize,
    /// p_mut (thesis 0.2).
    pub mutation_probability: f64,
    /// Maximum Lloyd iterations of k-means.
    pub kmeans_iterations: usize,
    /// Initial genes uniform in [min, max).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation.
    pub mutation_sigma: f64,
    /// Per-gene α range of the extended geometric crossover.
    pub crossover_range: [f64; 2],
    /// σ′ of the Gaussian perturbation after crossover.
    pub crossover_sigma: f64,
}

impl Default for SeParams {
    fn default() -> Self {
        Self {
            features: SeFeatures::Genotype,
            population_size: 100,
            species: 10,
            alpha: 0.75,
            elite_min_species_size: 5,
            mutation_probability: 0.2,
            kmeans_iterations: 200,
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
            crossover_range: [-1.0, 2.0],
            crossover_sigma: 0.1,
        }
    }
}

/// A morphology descriptor usable as a MAP-Elites axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Descriptor {
    /// d_num: number of voxels.
    Voxels,
    /// d_elong: eccentricity of the moment-equivalent ellipse.
    Elongation,
    /// d_compact: voxels ÷ cells in the convex hull.
    Compactness,
}

/// One MAP-Elites axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// The descriptor.
    pub descriptor: Descriptor,
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
    /// Bins (thesis 10).
    #[serde(default = "ten")]
    pub bins: usize,
}

fn ten() -> usize {
    10
}

/// Parameters of MAP-Elites.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MapElitesParams {
    /// The grid (default: the thesis' d_num over [0, W·H], d_elong and d_compact over [0, 1],
    /// 10 bins each).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axes: Vec<Axis>,
    /// Random genotypes of the first generation (thesis n_parents = 20).
    pub initial_population: usize,
    /// Children per generation (thesis n_parents = 20).
    pub batch_size: usize,
    /// Initial genes uniform in [min, max).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation (thesis 0.35).
    pub mutation_sigma: f64,
}

impl Default for MapElitesParams {
    fn default() -> Self {
        Self {
            axes: Vec::new(),
            initial_population: 20,
            batch_size: 20,
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
        }
    }
}

/// A configuration error: where (file, line, column, dotted field path) and what.
#[derive(Debug, Clone, PartialEq)]
pub struct ConfigError {
    /// The file (or other origin) of the text.
    pub origin: String,
    /// 1-based line, when known.
    pub line: Option<usize>,
    /// 1-based column, when known.
    pub column: Option<usize>,
    /// Dotted path of the offending field (empty for syntax errors).
    pub field: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.origin)?;
        if let Some(line) = self.line {
            write!(f, ", line {line}")?;
            if let Some(column) = self.column {
                write!(f, ", column {column}")?;
            }
        }
        if !self.field.is_empty() {
            write!(f, ": field '{}'", self.field)?;
        }
        write!(f, ": {}", self.message)
    }
}

impl std::error::Error for ConfigError {}

/// One step of a field path.
#[derive(Debug, Clone, PartialEq)]
enum Step {
    Key(String),
    Index(usize),
}

fn dotted(path: &[Step]) -> String {
    let mut s = String::new();
    for step in path {
        match step {
            Step::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Step::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

fn parse_dotted(field: &str) -> Vec<Step> {
    let mut steps = Vec::new();
    for part in field.split('.').filter(|p| !p.is_empty()) {
        let mut rest = part;
        if let Some(open) = rest.find('[') {
            steps.push(Step::Key(rest[..open].to_string()));
            rest = &rest[open..];
            while let Some(stripped) = rest.strip_prefix('[') {
                let close = stripped.find(']').unwrap_or(stripped.len());
                if let Ok(i) = stripped[..close].parse() {
                    steps.push(Step::Index(i));
                }
                rest = stripped.get(close + 1..).unwrap_or("");
            }
        } else {
            steps.push(Step::Key(rest.to_string()));
        }
    }
    steps
}

/// Byte offset → (line, column), both 1-based.
fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let offset = offset.min(text.len());
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

/// The span of the deepest element of `path` present in the document (the key's span for table
/// entries), or `None` when the text does not parse or nothing of the path is there.
fn locate(text: &str, path: &[Step]) -> Option<Range<usize>> {
    use toml::de::{DeTable, DeValue};
    let root = DeTable::parse(text).ok()?;
    let mut span = None;
    let mut table: Option<&DeTable> = Some(root.get_ref());
    let mut array: Option<&toml::de::DeArray> = None;
    for step in path {
        let value = match (step, table, array) {
            (Step::Key(k), Some(t), _) => {
                let (key, value) = t.iter().find(|(key, _)| key.get_ref().as_ref() == k.as_str())?;
                span = Some(key.span());
                value
            }
            (Step::Index(i), _, Some(a)) => {
                let value = a.get(*i)?;
                span = Some(value.span());
                value
            }
            _ => break,
        };
        (table, array) = match value.get_ref() {
            DeValue::Table(t) => (Some(t), None),
            DeValue::Array(a) => (None, Some(a)),
            _ => (None, None),
        };
    }
    span
}

impl ConfigError {
    /// An error about `field` (dotted path), located in `text` when possible.
    pub fn at_field(origin: &str, text: &str, field: &str, message: impl Into<String>) -> Self {
        let steps = parse_dotted(field);
        let position = locate(text, &steps).map(|span| line_column(text, span.start));
        Self {
            origin: origin.to_string(),
            line: position.map(|p| p.0),
            column: position.map(|p| p.1),
            field: field.to_string(),
            message: message.into(),
        }
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
    let experiment: Experiment = serde_path_to_error::deserialize(deserializer).map_err(|e| {
        let mut path: Vec<Step> = e
            .path()
            .iter()
            .filter_map(|segment| match segment {
                serde_path_to_error::Segment::Map { key } => Some(Step::Key(key.clone())),
                serde_path_to_error::Segment::Seq { index } => Some(Step::Index(*index)),
                _ => None,
            })
            .collect();
        let inner = e.into_inner();
        let mut message = inner.message().to_string();
        // Serde buffers internally tagged tables (`optimizer`), losing the inner path: find it
        // again by deserializing that table on its own.
        if path == [Step::Key("optimizer".into())] {
            if let Some((inner_path, inner_message)) = diagnose_optimizer(text) {
                path.extend(inner_path);
                message = inner_message;
            }
        }
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
    let experiment = experiment.resolve();
    experiment
        .validate()
        .map_err(|(field, message)| ConfigError::at_field(origin, text, &field, message))?;
    Ok(experiment)
}

/// Re-deserializes the `optimizer` table alone with its kind's parameter struct, to recover the
/// path of an error inside it.
fn diagnose_optimizer(text: &str) -> Option<(Vec<Step>, String)> {
    fn check<T: serde::de::DeserializeOwned>(value: toml::Value) -> Option<(Vec<Step>, String)> {
        let e = serde_path_to_error::deserialize::<_, T>(value).err()?;
        let mut path: Vec<Step> = e
            .path()
            .iter()
            .filter_map(|segment| match segment {
                serde_path_to_error::Segment::Map { key } => Some(Step::Key(key.clone())),
                serde_path_to_error::Segment::Seq { index } => Some(Step::Index(*index)),
                _ => None,
            })
            .collect();
        let message = e.into_inner().message().to_string();
        if let Some(name) = message
            .strip_prefix("unknown field `")
            .and_then(|rest| rest.split('`').next())
        {
            if path.last() != Some(&Step::Key(name.to_string())) {
                path.push(Step::Key(name.to_string()));
            }
        }
        Some((path, message))
    }
    let doc: toml::Table = toml::from_str(text).ok()?;
    let mut table = doc.get("optimizer")?.as_table()?.clone();
    let kind = table.remove("kind")?;
    let value = toml::Value::Table(table);
    match kind.as_str()? {
        "ga" => check::<GaParams>(value),
        "es" => check::<EsParams>(value),
        "cma-es" => check::<CmaParams>(value),
        "se" => check::<SeParams>(value),
        "map-elites" => check::<MapElitesParams>(value),
        _ => None,
    }
}

/// Reads and parses an experiment file.
pub fn load(path: &std::path::Path) -> Result<Experiment, ConfigError> {
    let origin = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| ConfigError {
        origin: origin.clone(),
        line: None,
        column: None,
        field: String::new(),
        message: e.to_string(),
    })?;
    let mut experiment = parse(&text, &origin)?;
    if experiment.name.is_none() {
        experiment.name = path.file_stem().map(|s| s.to_string_lossy().into_owned());
    }
    Ok(experiment)
}

impl Experiment {
    /// Fills in defaults that depend on other fields: MAP-Elites axes (the thesis' three
    /// descriptors, d_num over [0, W·H]) and the ES parent count (⌊λ/4⌋).
    pub fn resolve(mut self) -> Self {
        match &mut self.optimizer {
            OptimizerConfig::MapElites(me) if me.axes.is_empty() => {
                let cells = match &self.representation.body {
                    BodyPart::Encoded(e) => e.width() * e.height(),
                    BodyPart::Fixed(m) => m.width() * m.height(),
                };
                me.axes = vec![
                    Axis {
                        descriptor: Descriptor::Voxels,
                        min: 0.0,
                        max: cells as f64,
                        bins: 10,
                    },
                    Axis {
                        descriptor: Descriptor::Elongation,
                        min: 0.0,
                        max: 1.0,
                        bins: 10,
                    },
                    Axis {
                        descriptor: Descriptor::Compactness,
                        min: 0.0,
                        max: 1.0,
                        bins: 10,
                    },
                ];
            }
            OptimizerConfig::Es(es) if es.parents.is_none() => es.parents = Some((es.population_size / 4).max(1)),
            _ => {}
        }
        self
    }

    /// Checks values that the types cannot: returns the dotted field path and the message.
    pub fn validate(&self) -> Result<(), (String, String)> {
        let err = |field: &str, msg: String| Err((field.to_string(), msg));
        if self.runs == 0 {
            return err("runs", "must be at least 1".into());
        }
        if let Err(e) = self.representation.validate() {
            // Messages read "representation.<field>: …".
            let text = e.to_string();
            let (field, msg) = match text.split_once(": ") {
                Some((f, m)) if f.starts_with("representation.") => (f.to_string(), m.to_string()),
                _ => ("representation".to_string(), text.clone()),
            };
            return err(&field, msg);
        }
        let t = &self.task;
        if !(t.duration.is_finite() && t.duration > 0.0 && t.duration <= 1e5) {
            return err(
                "task.duration",
                format!("must be in (0, 100000] seconds, got {}", t.duration),
            );
        }
        if !(t.transient.is_finite() && t.transient >= 0.0 && t.transient < t.duration) {
            return err(
                "task.transient",
                format!("must be ≥ 0 and shorter than task.duration, got {}", t.transient),
            );
        }
        let s = &self.stop;
        if s.evaluations.is_none() && s.births.is_none() && s.generations.is_none() && s.wall_seconds.is_none() {
            return err(
                "stop",
                "set at least one of evaluations, births, generations, wall_seconds".into(),
            );
        }
        if let Some(w) = s.wall_seconds {
            if !(w.is_finite() && w > 0.0) {
                return err("stop.wall_seconds", format!("must be a positive number, got {w}"));
            }
        }
        let o = &self.output;
        if !(o.checkpoint_interval.is_finite() && o.checkpoint_interval >= 0.0) {
            return err("output.checkpoint_interval", "must be ≥ 0 seconds".into());
        }
        self.validate_optimizer()
    }

    fn validate_optimizer(&self) -> Result<(), (String, String)> {
        let err = |field: &str, msg: String| Err((format!("optimizer.{field}"), msg));
        let range = |field: &str, r: [f64; 2]| {
            if r[0].is_finite() && r[1].is_finite() && r[0] <= r[1] {
                Ok(())
            } else {
                err(field, format!("must be [min, max] with min ≤ max, got {r:?}"))
            }
        };
        let positive = |field: &str, v: usize| {
            if v > 0 {
                Ok(())
            } else {
                err(field, "must be at least 1".into())
            }
        };
        let probability = |field: &str, p: f64| {
            if (0.0..=1.0).contains(&p) {
                Ok(())
            } else {
                err(field, format!("must be in [0, 1], got {p}"))
            }
        };
        let sigma = |field: &str, s: f64| {
            if s.is_finite() && s >= 0.0 {
                Ok(())
            } else {
                err(field, format!("must be ≥ 0, got {s}"))
            }
        };
        match &self.optimizer {
            OptimizerConfig::Ga(p) => {
                positive("population_size", p.population_size)?;
                positive("offspring_size", p.offspring_size)?;
                positive("tournament_size", p.tournament_size)?;
                probability("mutation_probability", p.mutation_probability)?;
                range("init_range", p.init_range)?;
                range("crossover_range", p.crossover_range)?;
                sigma("mutation_sigma", p.mutation_sigma)?;
                sigma("crossover_sigma", p.crossover_sigma)
            }
            OptimizerConfig::Es(p) => {
                positive("population_size", p.population_size)?;
                let parents = p.parents.unwrap_or(1);
                if parents == 0 || parents > p.population_size {
                    return err("parents", format!("must be in 1..=population_size, got {parents}"));
                }
                if !(p.sigma.is_finite() && p.sigma > 0.0) {
                    return err("sigma", format!("must be > 0, got {}", p.sigma));
                }
                range("init_range", p.init_range)
            }
            OptimizerConfig::CmaEs(p) => {
                if p.population_size == Some(0) || p.population_size == Some(1) {
                    return err("population_size", "must be at least 2".into());
                }
                if !(p.sigma0.is_finite() && p.sigma0 > 0.0) {
                    return err("sigma0", format!("must be > 0, got {}", p.sigma0));
                }
                range("init_range", p.init_range)
            }
            OptimizerConfig::Se(p) => {
                positive("population_size", p.population_size)?;
                positive("species", p.species)?;
                if !(p.alpha > 0.0 && p.alpha <= 1.0) {
                    return err("alpha", format!("must be in (0, 1], got {}", p.alpha));
                }
                probability("mutation_probability", p.mutation_probability)?;
                range("init_range", p.init_range)?;
                range("crossover_range", p.crossover_range)?;
                sigma("mutation_sigma", p.mutation_sigma)?;
                sigma("crossover_sigma", p.crossover_sigma)
            }
            OptimizerConfig::MapElites(p) => {
                positive("initial_population", p.initial_population)?;
                positive("batch_size", p.batch_size)?;
                range("init_range", p.init_range)?;
                sigma("mutation_sigma", p.mutation_sigma)?;
                for (i, axis) in p.axes.iter().enumerate() {
                    if !(axis.min.is_finite() && axis.max.is_finite() && axis.min < axis.max) {
                        return err(&format!("axes[{i}]"), "needs finite min < max".into());
                    }
                    if axis.bins == 0 {
                        return err(&format!("axes[{i}].bins"), "must be at least 1".into());
                    }
                }
                Ok(())
            }
        }
    }

    /// The experiment as TOML, every default written out (the "resolved config").
    pub fn to_toml(&self) -> String {
        toml::to_string(self).expect("experiments always serialise to TOML")
    }

    /// The run seeds, in order.
    pub fn run_seeds(&self) -> Vec<u64> {
        (0..self.runs).map(|r| run_seed(self.seed, r)).collect()
    }
}
