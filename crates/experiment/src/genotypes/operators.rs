//! How a genotype kind with variation operators runs: the `[optimizer]` table's algorithm over
//! the kind's operators ([`OperatorPlan`]), the kind's mapper to robots, and the runner.

use crate::config::Experiment;
use crate::evaluator::{Evaluator, RobotEvaluator};
use crate::genotype::Genotype;
use crate::memory::{MemoryEstimate, DEFAULT_MEMORY_LIMIT};
use crate::optimizers::{decode_table, FieldError, OperatorPlan, OPTIMIZERS};
use crate::runner::{run_search, worker_threads, Observer, Plan, RunError, RunOptions, RunSummary};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::Path;
use vsrlab_evolution::rng::{SeededRng, Stream};
use vsrlab_evolution::Representation as Variation;
use vsrlab_tasks::Mapper;

/// Checks that the experiment's optimizer runs over its genotype kind's variation operators:
/// the field and message when its algorithm needs flat vectors, or when it crosses over
/// genotypes that have no `crossover`. Kinds call it from [`GenotypeKind::validate`].
///
/// [`GenotypeKind::validate`]: super::GenotypeKind::validate
pub fn check_operators(experiment: &Experiment, crossover: bool) -> Result<OperatorPlan, FieldError> {
    let kind = experiment.genotype_kind().name();
    let optimizer = experiment.optimizer.kind();
    let plan = optimizer.over_operators(&experiment.senses()).ok_or_else(|| {
        FieldError::new(
            "optimizer.kind",
            format!(
                "a {kind} genotype evolves with an optimizer over variation operators ({}), not {}",
                operator_optimizers().join(", "),
                optimizer.name()
            ),
        )
    })?;
    let p = plan.mutation_probability();
    if !crossover && p != 1.0 {
        return Err(FieldError::new(
            "optimizer.mutation_probability",
            format!("{kind} genotypes have no crossover: set 1.0, got {p}"),
        ));
    }
    Ok(plan)
}

/// The optimizer kinds that run over variation operators (their defaults say so).
fn operator_optimizers() -> Vec<&'static str> {
    let over_operators = |name: &str| {
        let table = toml::Table::from_iter([("kind".to_string(), toml::Value::String(name.into()))]);
        decode_table(table).is_ok_and(|c| c.kind().over_operators(&[]).is_some())
    };
    OPTIMIZERS
        .iter()
        .map(|o| o.name)
        .filter(|n| over_operators(n))
        .collect()
}

/// Runs every run of an experiment whose genotypes come from `variation` and become robots
/// through `mapper`, evolved by the `[optimizer]` the file names (checked by
/// [`check_operators`] when the experiment was validated); `genes` sizes the memory estimate.
pub fn run_with_operators<V, M>(
    experiment: &Experiment,
    variation: V,
    mapper: M,
    genes: usize,
    out: &Path,
    options: &RunOptions,
    observer: &mut dyn Observer,
) -> Result<Vec<RunSummary>, RunError>
where
    V: Variation + Clone + Serialize + DeserializeOwned + Send + Sync,
    V::Genotype: Genotype,
    M: Mapper<V::Genotype>,
{
    MemoryEstimate::of(experiment, genes, worker_threads(options.threads))
        .check(options.memory_limit.unwrap_or(DEFAULT_MEMORY_LIMIT))?;
    let senses = experiment.senses();
    let optimizer = experiment.optimizer.kind();
    let plan = optimizer.over_operators(&senses).ok_or_else(|| {
        RunError::Field(FieldError::new(
            "optimizer.kind",
            format!("{} needs flat-vector genotypes", optimizer.name()),
        ))
    })?;
    let evaluator = RobotEvaluator::with_mapper(mapper, experiment);
    let new_optimizer = |seed: u64| Ok(plan.build(variation.clone(), seed)?);
    run_search(
        &Plan::of(experiment),
        &new_optimizer,
        &evaluator,
        out,
        options,
        observer,
    )
}

/// Evaluates the first `count` initial genotypes of `variation` (for time estimates).
pub fn time_with_operators<V, M>(
    experiment: &Experiment,
    variation: &V,
    mapper: M,
    count: usize,
) -> Result<(), FieldError>
where
    V: Variation,
    M: Mapper<V::Genotype>,
{
    let evaluator = RobotEvaluator::with_mapper(mapper, experiment);
    let errors: Vec<Option<String>> = (0..count)
        .map(|i| {
            let mut rng = SeededRng::derive(0, 0, i as u64, Stream::Initialisation);
            let genotype = variation.initial(i, &mut rng);
            evaluator.evaluate(&genotype, 0).record.error
        })
        .collect();
    super::unless_every_evaluation_failed(&errors)
}
