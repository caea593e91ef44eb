//! [`AnalysisError`]: why an analysis pipeline (`analyze`, `label`) stopped. Every variant names
//! the file, folder or robot at fault.

use crate::replay::{BoxError, ReplayError};
use std::path::PathBuf;
use vsrlab_analysis::labels::LabelsError;
use vsrlab_analysis::plot::PlotError;
use vsrlab_analysis::results::ResultsError;
use vsrlab_tasks::files::FileError;

/// Why an analysis pipeline stopped.
#[derive(Debug, thiserror::Error)]
pub enum AnalysisError {
    /// An option is out of range; the message names it.
    #[error("{option}: {message}")]
    Option {
        /// The option, as on the command line (`bins`, `count`).
        option: &'static str,
        /// What is wrong.
        message: String,
    },
    /// The results of `vsrlab run` could not be read.
    #[error(transparent)]
    Results(#[from] ResultsError),
    /// The labels CSV could not be read or written.
    #[error(transparent)]
    Labels(#[from] LabelsError),
    /// A figure could not be written.
    #[error(transparent)]
    Plot(#[from] PlotError),
    /// A robot file could not be read or written.
    #[error(transparent)]
    Robot(#[from] FileError),
    /// An output file or folder could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// A robot could not be replayed.
    #[error("{robot}: {source}")]
    Replay {
        /// Which robot (its file, or its experiment).
        robot: String,
        /// Why.
        source: ReplayError,
    },
    /// The replay setup of an experiment could not be read.
    #[error("{}: cannot replay: {source}", folder.display())]
    Setup {
        /// The experiment folder.
        folder: PathBuf,
        /// The setup reader's report.
        source: BoxError,
    },
    /// A labelled robot names an unknown terrain.
    #[error("{robot}: terrain '{terrain}': {message}")]
    Terrain {
        /// The robot file as the labels name it.
        robot: String,
        /// The terrain as written.
        terrain: String,
        /// What is wrong with it.
        message: String,
    },
    /// Too few labelled robots to cross-validate the classifiers.
    #[error(
        "{}: too few labelled robots ({shapes} with a shape, {behaviours} with a behaviour) for {folds}-fold cross-validation",
        labels.display()
    )]
    TooFewLabels {
        /// The labels file.
        labels: PathBuf,
        /// Robots with a morphology class.
        shapes: usize,
        /// Robots with a behaviour class.
        behaviours: usize,
        /// Cross-validation folds asked for.
        folds: usize,
    },
    /// A list of class names has fewer than two classes.
    #[error("need at least two classes, got '{given}'")]
    TooFewClasses {
        /// The list as given.
        given: String,
    },
    /// A class name holds a character the labelling page cannot show safely.
    #[error("class names may not contain quotes or <>&: '{given}'")]
    ClassNameCharacters {
        /// The list as given.
        given: String,
    },
    /// The snapshots hold no evaluated individual to label.
    #[error("no evaluated individual found in the snapshots")]
    NoIndividuals,
    /// A video could not be written.
    #[error("{}: {source}", path.display())]
    Video {
        /// The video file.
        path: PathBuf,
        /// The video writer's report.
        source: BoxError,
    },
    /// The worker threads could not be started.
    #[error("thread pool: {0}")]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
}
