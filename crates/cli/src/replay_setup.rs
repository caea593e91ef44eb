//! How `analyze` and `label` replay an experiment's robots: its `experiment.toml`, read by the
//! experiment crate (the analysis crate comes before it and cannot).

use vsrlab_analysis::replay::{BoxError, ReplaySetup};
use vsrlab_analysis::RunFolder;

/// The replay setup of the experiment in `folder`.
pub fn read_setup(folder: &RunFolder) -> Result<ReplaySetup, BoxError> {
    let e = vsrlab_experiment::config::load(&folder.experiment_toml())?;
    Ok(ReplaySetup {
        genotypes: e.genotype_kind().stored(&e)?,
        task: e.task.spec,
        episode_seed: e.task.episode_seed,
        random_terrain: e.task.random_terrain_per_evaluation,
    })
}
