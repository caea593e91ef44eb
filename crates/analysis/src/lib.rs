//! Analysis of evolved voxel-based soft robots (thesis ch. 3; docs/analysis.md): morphology
//! descriptors, dynamic pose, centre-of-mass spectra, footprints and gaits, a random-forest
//! species classifier, the Inverse Simpson Index, Mann–Whitney tests, PCA and figures; and the
//! layout and rows of the output folders of `vsrlab run` ([`run_folder`], [`results`]), shared by
//! the runner that writes them and the pipelines (`vsrlab-pipelines`) that read them.
#![warn(missing_docs)]

pub mod curves;
pub mod diversity;
pub mod equivalence;
pub mod features;
pub mod footprint;
pub mod forest;
pub mod labels;
/// The morphology descriptors (d_num, d_elong, d_compact), defined with the body grid in
/// `vsrlab-body` so that robot kinds compute them.
pub use vsrlab_body::descriptors as morphology;
pub mod pareto;
pub mod pca;
pub mod plot;
pub mod pose;
pub mod progress;
pub mod report;
pub mod results;
pub mod rows;
pub mod run_folder;
pub mod sampling;
pub mod spectrum;
pub mod stats;
#[cfg(test)]
mod testutil;

pub use diversity::{inverse_simpson, species_index, Classifier};
pub use features::{FeatureParams, RobotFeatures};
pub use footprint::{FootprintParams, Gait};
pub use forest::{cross_validate, CvReport, Folds, ForestParams, MaxFeatures, RandomForest};
pub use morphology::MorphologyDescriptors;
pub use pca::Pca;
pub use pose::Pose;
pub use run_folder::{RunFiles, RunFolder};
pub use spectrum::{Axis, SpectrumParams};
pub use stats::{mann_whitney_u, median, std_dev, MannWhitney};
