//! How the pipelines replay an experiment's robots: its `experiment.toml`, read as the runner
//! reads it, so that its genotype kind turns stored genotypes into robots.

use crate::replay::{BoxError, ReplaySetup};
use vsrlab_analysis::RunFolder;

/// The replay setup of the experiment in `folder` (the [`crate::replay::SetupReader`] every
/// command uses; tests hand the pipelines their own).
pub fn read_setup(folder: &RunFolder) -> Result<ReplaySetup, BoxError> {
    let e = vsrlab_experiment::config::load(&folder.experiment_toml())?;
    Ok(ReplaySetup {
        genotypes: e.genotype_kind().stored(&e)?,
        task: e.task.spec,
        episode_seed: e.task.episode_seed,
        random_terrain: e.task.random_terrain_per_evaluation,
    })
}
