//! One process per output folder: `vsrlab run` holds an OS file lock on `OUT/.vsrlab.lock` while
//! it writes there, so a second run or resume on the same folder is refused instead of mixing its
//! files with the first one's.
//!
//! The lock is advisory and released by the operating system when the process ends, even by
//! kill -9, so a stale lock file never blocks a resume. On file systems without locks (some
//! network file systems) the lock cannot be taken; the run then goes on unprotected and says so.

use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

/// Name of the lock file inside an output folder.
pub const LOCK_FILE: &str = ".vsrlab.lock";

/// A held lock on an output folder; released when dropped.
#[derive(Debug)]
pub struct OutputLock {
    /// `None` when the file system does not support locks.
    file: Option<File>,
}

/// Why the lock could not be taken.
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another process holds it.
    #[error(
        "{folder} is in use by another vsrlab process{holder}: wait for it to end, or choose another output folder"
    )]
    Busy {
        /// The output folder.
        folder: String,
        /// " (pid N)" when the holder wrote its pid.
        holder: String,
    },
    /// The lock file could not be opened.
    #[error("{path}: {source}")]
    Io {
        /// The lock file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
}

impl OutputLock {
    /// Locks `folder` (which must exist). `Ok` with [`OutputLock::unsupported`] true when the file
    /// system has no locks.
    pub fn acquire(folder: &Path) -> Result<OutputLock, LockError> {
        let path = folder.join(LOCK_FILE);
        let io = |source| LockError::Io {
            path: path.clone(),
            source,
        };
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(io)?;
        match file.try_lock() {
            Ok(()) => {
                // the pid is only a hint for the message a second process prints
                let _ = file.set_len(0);
                let _ = file.rewind();
                let _ = write!(file, "{}", std::process::id());
                Ok(OutputLock { file: Some(file) })
            }
            Err(TryLockError::WouldBlock) => {
                let mut pid = String::new();
                let _ = file.read_to_string(&mut pid);
                let pid = pid.trim();
                Err(LockError::Busy {
                    folder: folder.display().to_string(),
                    holder: if pid.is_empty() {
                        String::new()
                    } else {
                        format!(" (pid {pid})")
                    },
                })
            }
            Err(TryLockError::Error(e)) if e.kind() == std::io::ErrorKind::Unsupported => Ok(OutputLock { file: None }),
            Err(TryLockError::Error(e)) => Err(io(e)),
        }
    }

    /// Whether the file system refused to lock (the run is then unprotected).
    pub fn unsupported(&self) -> bool {
        self.file.is_none()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_on_one_folder_is_refused_until_the_first_is_dropped() {
        let tmp = tempfile::tempdir().unwrap();
        let first = OutputLock::acquire(tmp.path()).unwrap();
        assert!(!first.unsupported());
        let error = OutputLock::acquire(tmp.path()).unwrap_err().to_string();
        assert!(error.contains("in use by another vsrlab process"), "{error}");
        assert!(error.contains(&format!("pid {}", std::process::id())), "{error}");
        drop(first);
        OutputLock::acquire(tmp.path()).unwrap();
    }
}
