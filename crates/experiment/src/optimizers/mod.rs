//! The optimizers an experiment file can name, as a registry.
//!
//! Each kind is one file here: its `[optimizer]` parameters and an [`OptimizerKind`]
//! implementation. The parameters are the optimizer's own settings struct from
//! `vsrlab-evolution` (`GaSettings`, `CmaSettings`, …, with the thesis defaults: declared once,
//! read from experiment files and kept in checkpoints), flattened beside what only experiment
//! files have (the operators' parameters, initial ranges, MAP-Elites descriptors). The
//! [`OptimizerKind`] implementation validates them, fills defaults that depend on the
//! representation, and builds the optimizer. [`OptimizerConfig`] is the registration list, matched
//! only in [`OptimizerConfig::kind`] and [`OPTIMIZERS`].
//!
//! Adding an optimizer for flat vectors: a file with its parameters and `OptimizerKind` impl, a
//! variant in [`OptimizerConfig`] and [`AnyOptimizer`], and an entry in [`OPTIMIZERS`]. An
//! optimizer that needs nothing of a genotype but its variation operators also returns an
//! [`OperatorPlan`] ([`OptimizerKind::over_operators`]) and then runs over every genotype kind.

mod any;
mod cma_es;
mod es;
mod ga;
mod map_elites;
mod neat;
mod nsga2;
mod over_operators;
mod se;

pub use any::{AnyOptimizer, SearchOptimizer, Searcher, SpeciationFeatures, WrapsOptimizer};
pub use cma_es::CmaParams;
pub use es::EsParams;
pub use ga::GaParams;
pub use map_elites::{Axis, Descriptor, MapElitesParams};
pub use neat::NeatParams;
pub use nsga2::Nsga2Params;
pub use over_operators::{OperatorOptimizer, OperatorPlan};
pub use se::{SeFeatures, SeParams};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, RealVector, Sense};

/// Which extra data an evaluation must extract from its episode for the optimizer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Extract {
    /// Nothing beyond the fitness.
    #[default]
    Nothing,
    /// The 16×16 dynamic pose (SE-s).
    Pose,
    /// The centre-of-mass spectrum (SE-b).
    Spectrum,
}

/// What every optimizer kind provides to the experiment.
pub trait OptimizerKind {
    /// The `kind` tag.
    fn name(&self) -> &'static str;
    /// Checks the parameters: the field (inside `optimizer`) and the message on error.
    fn validate(&self) -> Result<(), FieldError>;
    /// The same config with the defaults that depend on the representation filled in (`cells`:
    /// W·H of the body grid; `genes`: the genotype length, when the representation is valid), or
    /// `None` when there are none to fill.
    fn resolved(&self, _cells: usize, _genes: Option<usize>) -> Option<OptimizerConfig> {
        None
    }
    /// Whether it evolves flat vectors of real genes (every optimizer but NEAT, which evolves
    /// networks); a flat-vector experiment needs one that does.
    fn flat_vectors(&self) -> bool {
        true
    }
    /// Whether it optimizes several objectives at once.
    fn multi_objective(&self) -> bool {
        false
    }
    /// Whether it ranks several objectives lexicographically (the first decides, the next ones
    /// break its ties).
    fn lexicographic(&self) -> bool {
        false
    }
    /// Builds the optimizer for genotypes of `dimension` genes, objectives of these senses, and
    /// a run seed.
    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError>;
    /// Its algorithm over any genotype kind's variation operators, for objectives of these
    /// senses; `None` when the algorithm needs flat vectors (ES, CMA-ES, the speciated evolver).
    fn over_operators(&self, _senses: &[Sense]) -> Option<OperatorPlan> {
        None
    }
    /// What the evaluation must extract for it (speciation features).
    fn extract(&self) -> Extract {
        Extract::Nothing
    }
    /// The MAP-Elites descriptors it needs (empty for others).
    fn descriptors(&self) -> Vec<Descriptor> {
        Vec::new()
    }
    /// At most how many genotypes of `dimension` genes it holds at once (population, batch being
    /// evaluated, offspring), for the memory estimate; `budget` is the run's evaluation limit
    /// when it has one (archives grow with it).
    fn held_genotypes(&self, dimension: usize, budget: Option<u64>) -> u128;
    /// Evaluations per generation after the first (offspring, λ, a MAP-Elites batch), for time
    /// estimates.
    fn batch_size(&self, dimension: usize) -> usize;
    /// Floats it holds besides genotypes (CMA-ES: its matrices).
    fn held_matrix_floats(&self, _dimension: usize) -> u128 {
        0
    }
}

/// The optimizer of an experiment, by `kind`, with its parameters.
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
    /// NSGA-II, multi-objective (thesis ch. 5.1).
    Nsga2(Nsga2Params),
    /// NEAT over network genomes (thesis ch. 5.2's CPPN bodies).
    Neat(NeatParams),
}

impl OptimizerConfig {
    /// The kind behind the value.
    pub fn kind(&self) -> &dyn OptimizerKind {
        match self {
            OptimizerConfig::Ga(p) => p,
            OptimizerConfig::Es(p) => p,
            OptimizerConfig::CmaEs(p) => p,
            OptimizerConfig::Se(p) => p,
            OptimizerConfig::MapElites(p) => p,
            OptimizerConfig::Nsga2(p) => p,
            OptimizerConfig::Neat(p) => p,
        }
    }

    /// Fills the defaults that depend on the representation (`cells`: W·H of the body grid;
    /// `genes`: the genotype length).
    pub fn resolve(&mut self, cells: usize, genes: Option<usize>) {
        if let Some(resolved) = self.kind().resolved(cells, genes) {
            *self = resolved;
        }
    }
}

/// An error on a field of an experiment file (inside the `[optimizer]` table: the dotted path
/// inside it and what is wrong).
pub use vsrlab_field::FieldError;

/// One registered optimizer kind: its tag and its decoder from a TOML table (without `kind`).
pub struct OptimizerEntry {
    /// The `kind` tag.
    pub name: &'static str,
    /// Builds the config from the table, naming the field on error.
    pub decode: fn(toml::Value) -> Result<OptimizerConfig, FieldError>,
}

/// Every optimizer kind (each module contributes its entry).
pub const OPTIMIZERS: &[OptimizerEntry] = &[
    ga::ENTRY,
    es::ENTRY,
    cma_es::ENTRY,
    se::ENTRY,
    map_elites::ENTRY,
    nsga2::ENTRY,
    neat::ENTRY,
];

/// Builds an optimizer config from its `[optimizer]` table, naming the field on error.
pub fn decode_table(mut table: toml::Table) -> Result<OptimizerConfig, FieldError> {
    let names = || OPTIMIZERS.iter().map(|o| o.name).collect::<Vec<_>>().join(", ");
    let kind = match table.remove("kind") {
        Some(toml::Value::String(s)) => s,
        Some(other) => {
            return Err(FieldError::new(
                "kind",
                format!("expected one of {}, got {other}", names()),
            ))
        }
        None => return Err(FieldError::new("kind", format!("missing: give one of {}", names()))),
    };
    let entry = OPTIMIZERS.iter().find(|o| o.name == kind).ok_or_else(|| {
        FieldError::new(
            "kind",
            format!("unknown optimizer '{kind}': expected one of {}", names()),
        )
    })?;
    (entry.decode)(toml::Value::Table(table))
}

/// Deserializes a parameter struct, keeping the path of a failing field (the tasks' decoder,
/// over the table as JSON).
pub(crate) fn decode<T: DeserializeOwned>(value: toml::Value) -> Result<T, FieldError> {
    let json = serde_json::to_value(&value).map_err(|e| FieldError::message(e.to_string()))?;
    vsrlab_tasks::registry::decode(json)
}

/// The thesis' real-vector operators with an experiment's parameters.
pub(crate) fn real_vector(
    dimension: usize,
    init: [f64; 2],
    sigma: f64,
    crossover: [f64; 2],
    crossover_sigma: f64,
) -> RealVector {
    RealVector {
        dimension,
        init_min: init[0],
        init_max: init[1],
        mutation_sigma: sigma,
        crossover_min: crossover[0],
        crossover_max: crossover[1],
        crossover_sigma,
    }
}

/// The parameters of the thesis' real-vector operators, shared by GA, SE and NSGA-II and written
/// flat in their tables: initial genes uniform in `init_range`, Gaussian mutation of σ
/// `mutation_sigma`, extended geometric crossover with per-gene α in `crossover_range` followed
/// by a Gaussian perturbation of σ′ `crossover_sigma` (thesis: [−1, 1], 0.35, [−1, 2], 0.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Operators {
    /// Initial genes uniform in [min, max).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation.
    pub mutation_sigma: f64,
    /// Per-gene α range of the extended geometric crossover.
    pub crossover_range: [f64; 2],
    /// σ′ of the Gaussian perturbation after crossover.
    pub crossover_sigma: f64,
}

impl Default for Operators {
    fn default() -> Self {
        Self {
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
            crossover_range: [-1.0, 2.0],
            crossover_sigma: 0.1,
        }
    }
}

impl Operators {
    /// Checks the values; the field and the message on error.
    pub fn validate(&self) -> Result<(), FieldError> {
        check::range("init_range", self.init_range)?;
        check::range("crossover_range", self.crossover_range)?;
        check::sigma("mutation_sigma", self.mutation_sigma)?;
        check::sigma("crossover_sigma", self.crossover_sigma)
    }

    /// The operators for genotypes of `dimension` genes.
    pub fn real_vector(&self, dimension: usize) -> RealVector {
        real_vector(
            dimension,
            self.init_range,
            self.mutation_sigma,
            self.crossover_range,
            self.crossover_sigma,
        )
    }
}

/// [`decode`] for parameter structs with flattened parts (an optimizer's settings, the
/// [`Operators`]), which serde cannot check for unknown fields: serde ignores a key no part
/// reads. A key the decoded struct writes back is known; any other key is probed: the table is
/// decoded again with that key set to a value no parameter accepts (a table with an unlikely key),
/// and a key whose probe still decodes was ignored, so it is unknown. The probe also recognises
/// known fields that are not written back at their default (`eliminate_duplicates = false`).
pub(crate) fn decode_flat<T: DeserializeOwned + Serialize>(value: toml::Value) -> Result<T, FieldError> {
    let decoded: T = decode(value.clone()).map_err(|e| name_flattened_field::<T>(&value, e))?;
    let known = serde_json::to_value(&decoded).map_err(|e| FieldError::message(e.to_string()))?;
    let known: Vec<String> = known
        .as_object()
        .map(|o| o.keys().cloned().collect())
        .unwrap_or_default();
    let Some(table) = value.as_table() else {
        return Ok(decoded);
    };
    let ignored = |key: &str| {
        let mut probe = table.clone();
        let mut odd = toml::Table::new();
        odd.insert("__vsrlab_probe__".to_string(), toml::Value::Boolean(true));
        probe.insert(key.to_string(), toml::Value::Table(odd));
        decode::<T>(toml::Value::Table(probe)).is_ok()
    };
    match table.keys().find(|k| !known.contains(k) && ignored(k)) {
        None => Ok(decoded),
        Some(unknown) => {
            let expected: Vec<String> = known.iter().map(|k| format!("`{k}`")).collect();
            let message = format!("unknown field `{unknown}`, expected one of {}", expected.join(", "));
            Err(FieldError::new(unknown.clone(), message))
        }
    }
}

/// A wrong value inside a flattened part reaches serde without its field's name: the error
/// names the table as a whole, or (an unknown field of a nested table) only the unknown key.
/// The field is the one key whose removal lets the table decode; a path that is not one of the
/// table's own keys is put under it (`mutation.bogus`, not `bogus`).
fn name_flattened_field<T: DeserializeOwned>(value: &toml::Value, error: FieldError) -> FieldError {
    let first = error.path.split(['.', '[']).next().unwrap_or_default();
    let Some(table) = value
        .as_table()
        .filter(|t| error.path.is_empty() || !t.contains_key(first))
    else {
        return error;
    };
    let culprit = table.keys().find(|key| {
        let mut rest = table.clone();
        rest.remove(key.as_str());
        decode::<T>(toml::Value::Table(rest)).is_ok()
    });
    match culprit {
        Some(key) if error.path.is_empty() => FieldError::new(key.clone(), error.message),
        Some(key) => FieldError::new(format!("{key}.{}", error.path), error.message),
        None => error,
    }
}

/// The one objective of a single-objective optimizer.
pub(crate) fn single(senses: &[Sense]) -> Sense {
    senses.first().copied().unwrap_or_default()
}

/// Shared checks of parameter values; each returns the field and message on error.
pub(crate) mod check {
    use super::FieldError;

    /// Largest population, batch, tournament or species count.
    pub const MAX_SIZE: usize = 1_000_000;

    /// `1 ≤ v ≤` [`MAX_SIZE`].
    pub fn positive(field: &str, v: usize) -> Result<(), FieldError> {
        if v == 0 {
            Err(FieldError::new(field, "must be at least 1"))
        } else if v > MAX_SIZE {
            Err(FieldError::new(field, format!("must be at most {MAX_SIZE}, got {v}")))
        } else {
            Ok(())
        }
    }
    /// `p ∈ [0, 1]`.
    pub fn probability(field: &str, p: f64) -> Result<(), FieldError> {
        if (0.0..=1.0).contains(&p) {
            Ok(())
        } else {
            Err(FieldError::new(field, format!("must be in [0, 1], got {p}")))
        }
    }
    /// A finite `[min, max]` with min ≤ max, within ±[`MAX_GENE`].
    pub fn range(field: &str, r: [f64; 2]) -> Result<(), FieldError> {
        if !(r[0].is_finite() && r[1].is_finite() && r[0] <= r[1]) {
            Err(FieldError::new(
                field,
                format!("must be [min, max] with min ≤ max, got {r:?}"),
            ))
        } else if r[0].abs().max(r[1].abs()) > MAX_GENE {
            Err(FieldError::new(
                field,
                format!("must lie within ±{MAX_GENE:e} (genes beyond it overflow the networks they weigh), got {r:?}"),
            ))
        } else {
            Ok(())
        }
    }
    /// Largest magnitude of a gene an operator may start from or produce in one step: a network
    /// weighted by genes of 1e308 gives infinities in every evaluation.
    pub const MAX_GENE: f64 = 1e6;
    /// A finite `s` in [0, [`MAX_GENE`]].
    pub fn sigma(field: &str, s: f64) -> Result<(), FieldError> {
        if s.is_finite() && (0.0..=MAX_GENE).contains(&s) {
            Ok(())
        } else {
            Err(FieldError::new(field, format!("must be in [0, {MAX_GENE:e}], got {s}")))
        }
    }
}
