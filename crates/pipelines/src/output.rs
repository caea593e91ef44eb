//! Output files of the pipelines: every file is written atomically, through
//! [`vsrlab_tasks::files::write_atomic`], so a failure leaves no half-written file.

use crate::error::AnalysisError;
use std::path::Path;

/// Writes an output file atomically (through [`vsrlab_tasks::files::write_atomic`]): a failure
/// leaves neither a half-written file nor a temporary one.
pub(crate) fn write_output(path: &Path, bytes: &[u8]) -> Result<(), AnalysisError> {
    vsrlab_tasks::files::write_atomic(path, bytes).map_err(|source| AnalysisError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Creates an output folder and its parents.
pub(crate) fn create_folder(path: &Path) -> Result<(), AnalysisError> {
    std::fs::create_dir_all(path).map_err(|source| AnalysisError::Io {
        path: path.to_path_buf(),
        source,
    })
}
