//! Flat vectors of real genes, the genotype of an experiment without a `[genotype]` table (or
//! with `kind = "vector"`): the body and brain genes of `[representation]`, evolved by any
//! optimizer (the flat-vector ones build their own operators from the `[optimizer]` table).

use super::{GenotypeConfig, GenotypeEntry, GenotypeKind, GenotypeSize};
use crate::config::Experiment;
use crate::evaluator::{Evaluator, RobotEvaluator};
use crate::memory::{MemoryEstimate, DEFAULT_MEMORY_LIMIT};
use crate::optimizers::{AnyOptimizer, FieldError};
use crate::runner::{check_threads, run_search, worker_threads, Observer, Plan, RunError, RunOptions, RunSummary};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use vsrlab_tasks::{Stored, StoredGenotypes};

/// The `kind` tag of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum VectorTag {
    /// Flat vectors.
    Vector,
}

/// `[genotype] kind = "vector"`: no settings; the representation says how many genes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VectorGenotype {
    /// `vector`.
    pub kind: VectorTag,
}

/// The genotype of experiments without a `[genotype]` table.
pub static VECTOR: VectorGenotype = VectorGenotype {
    kind: VectorTag::Vector,
};

fn genes(experiment: &Experiment) -> Result<usize, FieldError> {
    experiment.representation.genotype_length().map_err(|e| {
        e.field_error()
            .unwrap_or_else(|| FieldError::new("representation", e.to_string()))
    })
}

impl GenotypeKind for VectorGenotype {
    fn name(&self) -> &'static str {
        "vector"
    }

    /// The representation's own checks cover the genes; the optimizer must evolve vectors.
    fn validate(&self, experiment: &Experiment) -> Result<(), FieldError> {
        let optimizer = experiment.optimizer.kind();
        if !optimizer.flat_vectors() {
            return Err(FieldError::new(
                "optimizer.kind",
                format!(
                    "{} does not evolve flat vectors of genes: give a [genotype] kind it evolves (NEAT: kind = \"cppn\")",
                    optimizer.name()
                ),
            ));
        }
        Ok(())
    }

    fn size(&self, experiment: &Experiment) -> Result<GenotypeSize, FieldError> {
        let genes = genes(experiment)?;
        Ok(GenotypeSize {
            genes,
            text: format!("{genes} genes per genotype"),
        })
    }

    fn run(
        &self,
        experiment: &Experiment,
        out: &Path,
        options: &RunOptions,
        observer: &mut dyn Observer,
    ) -> Result<Vec<RunSummary>, RunError> {
        let evaluator = RobotEvaluator::new(experiment).map_err(|e| match e.field_error() {
            Some(field) => RunError::Field(field),
            None => RunError::Other(e.to_string()),
        })?;
        run_vectors(experiment, &evaluator, out, options, observer)
    }

    /// Genotypes with genes uniform in [-1, 1), seeded.
    fn time_evaluations(&self, experiment: &Experiment, count: usize) -> Result<(), FieldError> {
        let evaluator = RobotEvaluator::new(experiment).map_err(|e| {
            e.field_error()
                .unwrap_or_else(|| FieldError::new("representation", e.to_string()))
        })?;
        let genes = evaluator.genotype_length();
        let mut rng = ChaCha8Rng::seed_from_u64(0);
        let errors: Vec<Option<String>> = (0..count)
            .map(|_| {
                let genotype: Vec<f64> = (0..genes).map(|_| rng.random_range(-1.0..1.0)).collect();
                Evaluator::<Vec<f64>>::evaluate(&evaluator, &genotype, 0).record.error
            })
            .collect();
        super::unless_every_evaluation_failed(&errors)
    }

    fn stored(&self, experiment: &Experiment) -> Result<Arc<dyn StoredGenotypes>, FieldError> {
        Ok(Arc::new(Stored::<Vec<f64>, _>::new(experiment.representation.clone())))
    }

    fn rows(&self) -> bool {
        true
    }
}

/// Runs every run of a flat-vector experiment into `out` with the optimizer its `[optimizer]`
/// table names, evaluating batches with `evaluator` (the local robots, or batches sent to
/// workers elsewhere).
pub fn run_vectors(
    experiment: &Experiment,
    evaluator: &dyn Evaluator<Vec<f64>>,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError> {
    let dimension = genes(experiment)?;
    let senses = experiment.senses();
    check_threads(options)?;
    MemoryEstimate::of(experiment, dimension, worker_threads(options.threads))
        .check(options.memory_limit.unwrap_or(DEFAULT_MEMORY_LIMIT))?;
    let new_optimizer = |seed: u64| -> Result<AnyOptimizer, RunError> {
        Ok(experiment.optimizer.kind().build(dimension, &senses, seed)?)
    };
    run_search(&Plan::of(experiment), &new_optimizer, evaluator, out, options, observer)
}

/// The registry entry of `kind = "vector"`.
pub(crate) const ENTRY: GenotypeEntry = GenotypeEntry {
    name: "vector",
    decode: |v| crate::optimizers::decode::<VectorGenotype>(v).map(GenotypeConfig::new),
};
