//! Genotype kinds, as a registry: what `[genotype] kind` in an experiment file can name.
//!
//! A kind is one module: its `[genotype]` table (serde, `deny_unknown_fields`, a `kind` tag)
//! implementing [`GenotypeKind`] (checks, size, how its runs run, how analyses read its stored
//! genotypes) and a [`GenotypeEntry`] in [`GENOTYPES`]. Most kinds run through
//! [`run_with_operators`]: the kind gives its variation operators (an `evolution`
//! [`Representation`](vsrlab_evolution::Representation)) and a mapper to robots, and any
//! optimizer whose algorithm needs nothing else (GA, NSGA-II, MAP-Elites: an
//! [`OperatorPlan`](crate::optimizers::OperatorPlan)) evolves it. Without a `[genotype]` table
//! an experiment's genotypes are flat vectors ([`vector`]), which every optimizer takes.
//!
//! Adding a kind: a module here (or anywhere, for a kind used from code: set
//! `Experiment::genotype` to a [`GenotypeConfig`]) and one line in [`GENOTYPES`].

pub mod cppn;
pub mod graph;
pub mod material_grid;
mod operators;
pub mod vector;

pub use operators::{check_operators, run_with_operators, time_with_operators};

use crate::config::{Experiment, TaskConfig};
use crate::optimizers::FieldError;
use crate::runner::{Observer, RunError, RunOptions, RunSummary};
use serde::{Serialize, Serializer};
use std::any::Any;
use std::fmt::Debug;
use std::path::Path;
use std::sync::Arc;
use vsrlab_tasks::{erased_serde, Representation, StoredGenotypes};

/// How big a kind's genotypes are: genes for the memory and time estimates, and a phrase for
/// the console ("45 genes per genotype", "graph genotypes from 24 neurons and 60 edges").
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct GenotypeSize {
    /// Genes (numbers) per genotype, or of the starting genotype when they grow.
    pub genes: usize,
    /// What the genotypes are, in words.
    pub text: String,
}

/// A figure the analyses draw of a column the runner logs for each generation's best genotype
/// (`best_<column>` of `generations.csv`, from the evaluator's `genotype_columns`): the kind says
/// what its column means, so that a figure is drawn only for kinds that log it, and labelled
/// for them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ColumnFigure {
    /// The logged column (`size`).
    pub column: &'static str,
    /// The figure's file name, without extension (`graph-size`).
    pub file: &'static str,
    /// Its title.
    pub title: &'static str,
    /// Its y axis.
    pub axis: &'static str,
    /// A line for the analysis summary.
    pub description: &'static str,
}

/// A genotype kind with its `[genotype]` settings. The type-erased plumbing ([`GenotypeCopy`])
/// comes with any `Clone + PartialEq + Serialize` table type.
pub trait GenotypeKind: Debug + Send + Sync + GenotypeCopy {
    /// The `kind` tag of its table.
    fn name(&self) -> &'static str;
    /// Reads what the table names in other files into the experiment (a seed robot's graph), so
    /// that the resolved `experiment.toml` stands on its own; errors name the field.
    fn load_files(&mut self, _representation: &mut Representation) -> Result<(), FieldError> {
        Ok(())
    }
    /// The representation an experiment of this kind has when its file gives no
    /// `[representation]` table (the co-design kinds make their bodies and learn their brains, so
    /// they need none); `None`: the file must give one.
    fn implied_representation(&self, _task: &TaskConfig) -> Option<Representation> {
        None
    }
    /// Checks the table against the rest of the experiment; errors name the field.
    fn validate(&self, experiment: &Experiment) -> Result<(), FieldError>;
    /// The size of its genotypes in this experiment.
    fn size(&self, experiment: &Experiment) -> Result<GenotypeSize, FieldError>;
    /// Runs every run of the experiment into `out`.
    fn run(
        &self,
        experiment: &Experiment,
        out: &Path,
        options: &RunOptions,
        observer: &mut dyn Observer,
    ) -> Result<Vec<RunSummary>, RunError>;
    /// Evaluates `count` initial genotypes (the time estimate of `vsrlab validate`); an error
    /// when every one of them failed, as every run would.
    fn time_evaluations(&self, experiment: &Experiment, count: usize) -> Result<(), FieldError>;
    /// How many times longer a real evaluation takes than one [`GenotypeKind::time_evaluations`]
    /// runs, for kinds that time a shortened evaluation (the co-design kinds time a few PPO
    /// iterations of the many each evaluation runs). Default 1.
    fn timing_scale(&self, _experiment: &Experiment) -> f64 {
        1.0
    }
    /// Its genotypes as snapshots and checkpoints store them → robots: how analyses replay the
    /// individuals of a run.
    fn stored(&self, experiment: &Experiment) -> Result<Arc<dyn StoredGenotypes>, FieldError>;
    /// Whether snapshots hold each generation whole (the GA's parents and children before
    /// truncation, [`vsrlab_evolution::Optimizer::generation_pool`]) instead of the survivors:
    /// the population as EvoGym's GA and thesis ch. 5.2 count it, whose learning curves and
    /// radius are medians over it.
    fn snapshots_whole_generation(&self) -> bool {
        false
    }
    /// Whether its genotypes are rows of numbers, which batch evaluation (`vsrlab evaluate`,
    /// Python's `evaluate_batch`) takes.
    fn rows(&self) -> bool {
        false
    }
    /// The figures `vsrlab analyze` draws of the columns it logs for the best genotype (none by
    /// default).
    fn column_figures(&self) -> Vec<ColumnFigure> {
        Vec::new()
    }
    /// What its evaluations' fitness is, when it is not the task's first objective (a co-design
    /// body's learned mean reward per step); `None`, the default: the task's.
    fn fitness_name(&self) -> Option<&'static str> {
        None
    }
}

/// What a boxed [`GenotypeKind`] needs to be copied, compared and written; implemented for
/// every `Clone + PartialEq + Serialize` table type.
pub trait GenotypeCopy {
    /// The experiment-file form, for writing resolved experiment files.
    fn as_serialize(&self) -> &dyn erased_serde::Serialize;
    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn GenotypeKind>;
    /// The table itself, for comparisons within its kind and downcasts.
    fn as_any(&self) -> &dyn Any;
    /// The table itself, mutably (to edit an experiment through its kind's own type).
    fn as_any_mut(&mut self) -> &mut dyn Any;
    /// Whether `other` is the same table.
    fn same_as(&self, other: &dyn GenotypeKind) -> bool;
}

impl<T: GenotypeKind + Clone + PartialEq + Serialize + 'static> GenotypeCopy for T {
    fn as_serialize(&self) -> &dyn erased_serde::Serialize {
        self
    }
    fn clone_box(&self) -> Box<dyn GenotypeKind> {
        Box::new(self.clone())
    }
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn same_as(&self, other: &dyn GenotypeKind) -> bool {
        other.as_any().downcast_ref::<T>() == Some(self)
    }
}

/// The `[genotype]` table of an experiment, of any kind.
#[derive(Debug)]
pub struct GenotypeConfig(Box<dyn GenotypeKind>);

impl GenotypeConfig {
    /// Wraps a kind's table.
    pub fn new(kind: impl GenotypeKind + 'static) -> GenotypeConfig {
        GenotypeConfig(Box::new(kind))
    }

    /// The kind's table as its own type, when it is `T`.
    pub fn downcast_ref<T: 'static>(&self) -> Option<&T> {
        self.0.as_any().downcast_ref()
    }

    /// The kind's table as its own type, mutably, when it is `T`.
    pub fn downcast_mut<T: 'static>(&mut self) -> Option<&mut T> {
        self.0.as_any_mut().downcast_mut()
    }

    /// The kind's table, mutably (to read files it names).
    pub fn kind_mut(&mut self) -> &mut dyn GenotypeKind {
        self.0.as_mut()
    }
}

impl std::ops::Deref for GenotypeConfig {
    type Target = dyn GenotypeKind;
    fn deref(&self) -> &Self::Target {
        self.0.as_ref()
    }
}

impl Clone for GenotypeConfig {
    fn clone(&self) -> Self {
        GenotypeConfig(self.0.clone_box())
    }
}

impl PartialEq for GenotypeConfig {
    fn eq(&self, other: &Self) -> bool {
        self.0.same_as(other.0.as_ref())
    }
}

impl Serialize for GenotypeConfig {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        erased_serde::serialize(self.0.as_serialize(), serializer)
    }
}

/// One registered genotype kind: its tag and its decoder from a TOML table (with `kind`).
pub struct GenotypeEntry {
    /// The `kind` tag.
    pub name: &'static str,
    /// Builds the table, naming the field on error.
    pub decode: fn(toml::Value) -> Result<GenotypeConfig, FieldError>,
}

/// Every genotype kind an experiment file can name.
pub const GENOTYPES: &[GenotypeEntry] = &[vector::ENTRY, graph::ENTRY, material_grid::ENTRY, cppn::ENTRY];

/// Builds a genotype table from its `[genotype]` table, naming the field on error.
pub fn decode_table(table: toml::Table) -> Result<GenotypeConfig, FieldError> {
    let names = || GENOTYPES.iter().map(|g| g.name).collect::<Vec<_>>().join(", ");
    let kind = match table.get("kind") {
        Some(toml::Value::String(s)) => s.clone(),
        Some(other) => {
            return Err(FieldError::new(
                "kind",
                format!("expected one of {}, got {other}", names()),
            ))
        }
        None => return Err(FieldError::new("kind", format!("missing: give one of {}", names()))),
    };
    let entry = GENOTYPES.iter().find(|g| g.name == kind).ok_or_else(|| {
        FieldError::new(
            "kind",
            format!("unknown genotype kind '{kind}': expected one of {}", names()),
        )
    })?;
    (entry.decode)(toml::Value::Table(table))
}

/// Runs every run of an experiment file into `out`, whatever its genotype kind.
pub fn run_configured(
    experiment: &Experiment,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    experiment.genotype_kind().run(experiment, out, options, observer)
}

/// An error when every timed evaluation failed (`errors`: each one's failure, if any): a run of
/// such an experiment would fail every evaluation too, so `vsrlab validate` refuses it with the
/// first reason (which names the field, e.g. `task.obstacles[0]: …`).
pub(crate) fn unless_every_evaluation_failed(errors: &[Option<String>]) -> Result<(), FieldError> {
    match errors.iter().map(Option::as_deref).collect::<Option<Vec<&str>>>() {
        Some(all) if !all.is_empty() => Err(FieldError::message(format!(
            "all {} initial genotypes timed failed (so would every evaluation of a run): {}",
            all.len(),
            all[0]
        ))),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::unless_every_evaluation_failed;

    #[test]
    fn validation_refuses_only_when_every_timed_evaluation_failed() {
        let failed = |why: &str| Some(why.to_string());
        assert!(unless_every_evaluation_failed(&[]).is_ok());
        assert!(unless_every_evaluation_failed(&[failed("a"), None, failed("b")]).is_ok());
        let e = unless_every_evaluation_failed(&[failed("task.x: bad"), failed("other")]).unwrap_err();
        assert!(
            e.to_string().contains("all 2 initial genotypes") && e.to_string().ends_with("task.x: bad"),
            "{e}"
        );
    }
}
