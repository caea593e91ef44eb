//! # vsrlab-pipelines
//!
//! The analysis pipelines behind `vsrlab analyze`, `label`, `reassess`, `plasticity`, `codesign`,
//! `modules`, `reassemble`, `transferability` and `inflate`: each takes an options struct, reads
//! the output folders of `vsrlab run`, replays robots where features are needed, writes its files
//! and returns a typed report. They come after `vsrlab-experiment`, so they read experiment files
//! as the runner does ([`setup::read_setup`]: the task, seeds and genotype kind) and write them
//! through its typed configuration (`reassemble`'s re-optimisation experiment).
//!
//! The caller supplies how a video is drawn (for `label`, [`VideoWriter`]) and where progress
//! goes ([`Progress`]); tests may hand their own [`SetupReader`].
#![warn(missing_docs)]

pub mod analyze;
mod best_robots;
mod candidates;
mod classes;
mod classifiers;
pub mod codesign;
pub mod error;
pub mod fidelity;
mod figures;
pub mod inflation;
pub mod label;
mod label_page;
pub mod modules;
mod output;
mod pareto;
pub mod plasticity;
pub mod reassemble;
pub mod reassess;
pub mod replay;
mod settings;
pub mod setup;
mod species;
mod summary_page;
pub mod votes;

pub use analyze::{analyze, AnalysisReport, AnalyzeOptions, FigureNote};
pub use classes::{parse_classes, THESIS_BEHAVIOURS, THESIS_SHAPES};
pub use codesign::{codesign, CodesignOptions, CodesignReport};
pub use error::AnalysisError;
pub use inflation::{inflation, InflationOptions, InflationReport, InflationSummary};
pub use label::{label, LabelOptions, LabelReport, VideoSpec, VideoWriter, LABELLING_FILE};
pub use modules::{modules, ModulesOptions, ModulesReport};
pub use plasticity::{plasticity, PlasticityOptions, PlasticityReport};
pub use reassemble::{
    reassemble, transferability, ReassembleOptions, ReassembleReport, TransferabilityOptions, TransferabilityReport,
};
pub use reassess::{reassess, ReassessOptions, ReassessReport};

use crate::replay::{ReplaySetup, SetupReader};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::results::ExperimentData;

/// A thread pool of `threads` workers (None or 0: every core).
fn thread_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, AnalysisError> {
    Ok(rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()?)
}

/// The replay setup of every experiment (None, with a warning, where it cannot be read).
fn read_setups(
    experiments: &[ExperimentData],
    reader: &dyn SetupReader,
    progress: &dyn Progress,
) -> Vec<Option<ReplaySetup>> {
    experiments
        .iter()
        .map(|e| match reader.read_setup(&e.folder()) {
            Ok(setup) => Some(setup),
            Err(msg) => {
                progress.note(&format!("warning: {}: cannot replay robots: {msg}", e.dir.display()));
                None
            }
        })
        .collect()
}
