//! Analysis of evolved voxel-based soft robots (thesis ch. 3; docs/analysis.md): morphology
//! descriptors, dynamic pose, centre-of-mass spectra, footprints and gaits, a random-forest
//! species classifier, the Inverse Simpson Index, Mann–Whitney tests, PCA and figures; and the
//! pipelines behind `vsrlab analyze` and `vsrlab label` ([`pipelines`]), which read the output
//! folders of `vsrlab run` ([`run_folder`], [`results`]) and replay robots ([`mod@replay`]).
#![warn(missing_docs)]

pub mod curves;
pub mod diversity;
pub mod error;
pub mod features;
pub mod footprint;
pub mod forest;
pub mod labels;
pub mod morphology;
mod output;
pub mod pca;
pub mod pipelines;
pub mod plot;
pub mod pose;
pub mod progress;
pub mod replay;
pub mod report;
pub mod results;
pub mod run_folder;
pub mod sampling;
pub mod spectrum;
pub mod stats;
#[cfg(test)]
mod testutil;

pub use diversity::{inverse_simpson, species_index, Classifier};
pub use error::AnalysisError;
pub use features::{FeatureParams, RobotFeatures};
pub use footprint::{FootprintParams, Gait};
pub use forest::{cross_validate, CvReport, Folds, ForestParams, MaxFeatures, RandomForest};
pub use morphology::MorphologyDescriptors;
pub use pca::Pca;
pub use pipelines::{analyze, label, AnalysisReport, AnalyzeOptions, LabelOptions, LabelReport};
pub use pose::Pose;
pub use replay::{replay, ReplayError, ReplaySetup, SetupReader};
pub use run_folder::{RunFiles, RunFolder};
pub use spectrum::{Axis, SpectrumParams};
pub use stats::{mann_whitney_u, median, std_dev, MannWhitney};
