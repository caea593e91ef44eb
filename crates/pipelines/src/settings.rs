//! Settings: experiments with the same name pool their runs into one setting, which keeps one
//! colour in every figure.

use vsrlab_analysis::results::{self, ExperimentData, RunData};

/// One setting of an analysis.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Setting {
    /// The experiments' name.
    pub name: String,
    /// Its colour index (its position among the settings, sorted by name).
    pub color: usize,
    /// Its experiments (indices into the experiments).
    pub experiments: Vec<usize>,
}

impl Setting {
    /// Every run of the setting, with its experiment, in experiment then run order.
    pub fn runs<'a>(
        &'a self,
        experiments: &'a [ExperimentData],
    ) -> impl Iterator<Item = (&'a ExperimentData, &'a RunData)> + 'a {
        self.experiments
            .iter()
            .flat_map(move |&e| experiments[e].runs.iter().map(move |r| (&experiments[e], r)))
    }
}

/// The settings of `experiments`, sorted by name.
pub(crate) fn settings_of(experiments: &[ExperimentData]) -> Vec<Setting> {
    results::settings(experiments)
        .into_iter()
        .enumerate()
        .map(|(color, (name, experiments))| Setting {
            name,
            color,
            experiments,
        })
        .collect()
}

/// What the fitness is when every experiment agrees (`velocity`, `distance`, a genotype kind's
/// own, as a co-design body's `reward per step`), else "fitness".
pub(crate) fn fitness_label(experiments: &[ExperimentData]) -> String {
    let mut kinds: Vec<String> = experiments.iter().map(fitness_of).collect();
    kinds.sort();
    kinds.dedup();
    if kinds.len() == 1 {
        kinds.remove(0)
    } else {
        "fitness".into()
    }
}

/// What one experiment's fitness is: its genotype kind's name for it, or its task's objective.
fn fitness_of(experiment: &ExperimentData) -> String {
    let kind = match experiment.config.get("genotype") {
        Some(toml::Value::Table(table)) => vsrlab_experiment::genotypes::decode_table(table.clone()).ok(),
        _ => None,
    };
    match kind.and_then(|k| k.fitness_name()) {
        Some(name) => name.to_string(),
        None => experiment.fitness_kind(),
    }
}

/// A fitness name with its unit for axis labels: the model's length unit (a voxel side is 3
/// length units, docs/model.md) and seconds.
pub(crate) fn with_unit(fitness: &str) -> String {
    let unit = match fitness {
        "velocity" => "length units/s",
        "distance" | "height" | "final_height" => "length units",
        "elapsed" => "s",
        _ => return fitness.to_string(),
    };
    format!("{fitness} [{unit}]")
}

/// The values of one metric per setting (one vector per setting, by colour index).
pub(crate) fn per_setting(
    settings: &[Setting],
    experiments: &[ExperimentData],
    value: impl Fn(&RunData) -> f64,
) -> Vec<Vec<f64>> {
    settings
        .iter()
        .map(|s| s.runs(experiments).map(|(_, r)| value(r)).collect())
        .collect()
}
