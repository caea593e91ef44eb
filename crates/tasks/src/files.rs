//! Files: atomic writes, and robot files (a robot as small, human-readable JSON).

use crate::kinds::{self, AnyRobot};
use std::io::Write;
use std::path::Path;

/// Format tag written at the top of every robot file.
pub const ROBOT_FORMAT: &str = "vsrlab-robot/1";

/// Why a file could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// The operating system refused.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The OS error.
        source: std::io::Error,
    },
    /// The content is not a valid robot file; the message names the field.
    #[error("{path}: {msg}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong, naming the field (and line, for syntax errors).
        msg: String,
    },
}

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename, so that a
/// reader never sees a half-written file and a failure leaves nothing behind.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = TempPath::beside(path);
    std::fs::File::create(tmp.path())?.write_all(bytes)?;
    tmp.commit()
}

/// Parses JSON text into `T`, naming the field, line and column of an error.
pub fn parse_json<T: serde::de::DeserializeOwned>(text: &str, origin: &str) -> Result<T, FileError> {
    let de = &mut serde_json::Deserializer::from_str(text);
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        FileError::Invalid {
            path: origin.to_string(),
            msg: format!(
                "field '{path}' (line {}, column {}): {inner}",
                inner.line(),
                inner.column()
            ),
        }
    })
}

/// Checks a robot file's `format` field, naming it.
pub fn check_format(format: &str, origin: &str) -> Result<(), FileError> {
    if format == ROBOT_FORMAT {
        Ok(())
    } else {
        Err(FileError::Invalid {
            path: origin.to_string(),
            msg: format!("field 'format': expected \"{ROBOT_FORMAT}\", got \"{format}\""),
        })
    }
}

/// Saves a robot file of any kind atomically.
pub fn save_any_robot(path: &Path, robot: &AnyRobot, note: Option<&str>) -> Result<(), FileError> {
    write_text(path, &robot.to_json(note))
}

/// Writes a file atomically, naming it in the error.
pub fn write_text(path: &Path, text: &str) -> Result<(), FileError> {
    write_atomic(path, text.as_bytes()).map_err(|source| FileError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// Largest file vsrlab reads (bytes): far above any robot, replay or experiment file it writes,
/// far below what exhausts memory.
pub const MAX_FILE_BYTES: u64 = 1 << 30;

/// Reads a file's bytes, naming it in the error. Only regular files are read (a FIFO would block
/// and a device such as `/dev/zero` never end), at most [`MAX_FILE_BYTES`] of them.
pub fn read_bytes(path: &Path) -> Result<Vec<u8>, FileError> {
    read_bytes_within(path, MAX_FILE_BYTES)
}

/// [`read_bytes`] with another size limit.
pub fn read_bytes_within(path: &Path, limit: u64) -> Result<Vec<u8>, FileError> {
    use std::io::Read;
    let origin = || path.display().to_string();
    let io = |source| FileError::Io { path: origin(), source };
    // metadata before open: opening a FIFO for reading blocks until someone writes to it
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a folder"
        } else {
            "not a regular file (a device, pipe or socket)"
        };
        return Err(FileError::Invalid {
            path: origin(),
            msg: format!("{what}: vsrlab reads only regular files"),
        });
    }
    let too_large = |size: u64| FileError::Invalid {
        path: origin(),
        msg: format!("{size} bytes or more: larger than the {limit} bytes vsrlab reads from one file"),
    };
    if meta.len() > limit {
        return Err(too_large(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(bytes.len() as u64));
    }
    Ok(bytes)
}

/// Reads a UTF-8 text file (regular, bounded as [`read_bytes`]), naming it in the error.
pub fn read_text(path: &Path) -> Result<String, FileError> {
    String::from_utf8(read_bytes(path)?).map_err(|e| FileError::Invalid {
        path: path.display().to_string(),
        msg: format!("not UTF-8 text: byte {} is not valid", e.utf8_error().valid_up_to()),
    })
}

/// Parses and validates a robot file of any registered kind (the kind is the one whose key the
/// file holds; a file with none is read as a voxel robot file, whose errors then name what is
/// missing).
pub fn any_robot_from_json(text: &str, origin: &str) -> Result<AnyRobot, FileError> {
    let kind = match serde_json::from_str::<serde_json::Value>(text) {
        Ok(value) => kinds::kind_of_file(&value),
        // not JSON (a number like 1e999, a cut file): the kind whose key the text names, so
        // that its own parser reports the fault where it is rather than a wrong kind's
        Err(_) => kinds::ROBOT_KINDS.iter().find(|k| {
            k.file_keys.iter().any(|key| text.contains(&format!("\"{key}\""))) && k.name != kinds::default_kind().name
        }),
    };
    (kind.unwrap_or_else(kinds::default_kind).from_file)(text, origin)
}

/// Loads and validates a robot file of any registered kind: vsrlab's JSON, or a file of
/// another program that a kind reads ([`kinds::ForeignFormat`], e.g. EvoGym's `.npz`).
pub fn load_any_robot(path: &Path) -> Result<AnyRobot, FileError> {
    let origin = path.display().to_string();
    let bytes = read_bytes(path)?;
    if let Some(format) = kinds::foreign_format_of(&bytes) {
        return (format.read)(&bytes, &origin);
    }
    let text = String::from_utf8(bytes).map_err(|e| FileError::Invalid {
        path: origin.clone(),
        msg: format!(
            "not a robot file: byte {} is not UTF-8 text (JSON), and the file is none of {}",
            e.utf8_error().valid_up_to(),
            kinds::foreign_format_names().join(", ")
        ),
    })?;
    // a byte-order mark (some editors write one) is not part of the JSON, as TOML files allow it
    any_robot_from_json(text.strip_prefix('\u{feff}').unwrap_or(&text), &origin)
}

/// Saves a robot in format `format`: `vsrlab` (the robot file), or a foreign format by name
/// (`evogym-json`, `evogym-npz`); with none, the foreign format whose extension `path` has, other
/// than `json`, else `vsrlab`. Atomic; a format that cannot hold the
/// robot is refused before anything is written.
pub fn save_any_robot_as(
    path: &Path,
    robot: &AnyRobot,
    note: Option<&str>,
    format: Option<&str>,
) -> Result<(), FileError> {
    let invalid = |msg: String| FileError::Invalid {
        path: path.display().to_string(),
        msg,
    };
    // any kind's: a `.npz` name for a robot no `.npz` format can hold is refused, not written
    // as JSON under a misleading name
    let by_extension = || {
        let ext = path.extension()?.to_str()?;
        kinds::ROBOT_KINDS
            .iter()
            .flat_map(|k| k.foreign_formats.iter())
            .find(|f| f.extension != "json" && f.extension.eq_ignore_ascii_case(ext))
    };
    let foreign = match format {
        None => by_extension(),
        Some("vsrlab") => None,
        Some(name) => Some(kinds::foreign_format(name).map(|(_, f)| f).ok_or_else(|| {
            let mut names = vec!["vsrlab"];
            names.extend(kinds::foreign_format_names());
            invalid(format!(
                "unknown robot file format '{name}': expected {}",
                names.join(", ")
            ))
        })?),
    };
    let bytes = match foreign {
        Some(f) => (f.write)(robot).map_err(|m| invalid(format!("{}: {m}", f.name)))?,
        None => robot.to_json(note).into_bytes(),
    };
    write_atomic(path, &bytes).map_err(|source| FileError::Io {
        path: path.display().to_string(),
        source,
    })
}

pub use crate::kinds::voxel::{load_robot, robot_from_json, robot_to_json, save_robot};

/// A temporary path beside a destination file, for writers that must be given a path of their
/// own (an encoder process, a library that saves by file name), where [`write_atomic`] cannot
/// take the bytes: write to [`TempPath::path`], then [`TempPath::commit`] renames it onto the
/// destination. Dropped uncommitted, it removes whatever was written there, so a failure leaves
/// nothing behind. The name keeps the destination's extension (`.NAME.tmp-PID-N.EXT`), for
/// writers that pick the format by extension.
#[derive(Debug)]
pub struct TempPath {
    path: std::path::PathBuf,
    dest: std::path::PathBuf,
    committed: bool,
}

impl TempPath {
    /// A fresh temporary name in `dest`'s folder (nothing is created yet).
    pub fn beside(dest: &Path) -> TempPath {
        static COUNTER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        let n = COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let dir = dest
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let stem = dest
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let ext = dest
            .extension()
            .map(|e| format!(".{}", e.to_string_lossy()))
            .unwrap_or_default();
        let path = dir.join(format!(".{stem}.tmp-{}-{n}{ext}", std::process::id()));
        TempPath {
            path,
            dest: dest.to_path_buf(),
            committed: false,
        }
    }

    /// Where the writer writes.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Flushes the written file to disk and renames it onto the destination, replacing what is
    /// there.
    pub fn commit(mut self) -> std::io::Result<()> {
        std::fs::File::open(&self.path)?.sync_all()?;
        std::fs::rename(&self.path, &self.dest)?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for TempPath {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

#[cfg(test)]
mod temp_path_tests {
    use super::*;

    #[test]
    fn temp_path_commits_or_leaves_nothing() {
        let dir = std::env::temp_dir().join(format!("vsrlab-temp-path-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let dest = dir.join("figure.png");
        let tmp = TempPath::beside(&dest);
        assert_eq!(tmp.path().extension().unwrap(), "png");
        std::fs::write(tmp.path(), b"abc").unwrap();
        tmp.commit().unwrap();
        assert_eq!(std::fs::read(&dest).unwrap(), b"abc");
        let dropped = TempPath::beside(&dest);
        std::fs::write(dropped.path(), b"half").unwrap();
        drop(dropped);
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("figure.png")]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[cfg(test)]
mod write_atomic_tests {
    use super::*;

    #[test]
    fn a_failed_write_leaves_nothing_and_a_good_one_replaces_the_file() {
        let dir = std::env::temp_dir().join(format!("vsrlab-write-atomic-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("taken")).unwrap();
        // renaming a file onto a folder fails: no temporary file may remain
        assert!(write_atomic(&dir.join("taken"), b"x").is_err());
        let file = dir.join("a.txt");
        write_atomic(&file, b"first").unwrap();
        write_atomic(&file, b"second").unwrap();
        assert_eq!(std::fs::read(&file).unwrap(), b"second");
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| e.file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, ["a.txt", "taken"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[cfg(test)]
mod bom_tests {
    use super::*;

    #[test]
    fn a_robot_file_with_a_byte_order_mark_reads_as_without() {
        let dir = std::env::temp_dir().join(format!("vsrlab-bom-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let robot = crate::kinds::from_short_forms(&crate::kinds::RobotArgs {
            body: "biped-4x3",
            brain: None,
            sensors: None,
            preset: None,
        })
        .unwrap();
        let plain = dir.join("plain.json");
        save_any_robot(&plain, &robot, None).unwrap();
        let text = std::fs::read_to_string(&plain).unwrap();
        let marked = dir.join("marked.json");
        std::fs::write(&marked, format!("\u{feff}{text}")).unwrap();
        let (a, b) = (load_any_robot(&plain).unwrap(), load_any_robot(&marked).unwrap());
        assert_eq!(a.to_json(None), b.to_json(None));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[cfg(test)]
mod read_bytes_tests {
    use super::*;

    #[test]
    fn devices_folders_and_oversized_files_are_refused_naming_the_file() {
        let dir = std::env::temp_dir().join(format!("vsrlab-read-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let refused = |path: &Path, limit: u64| match read_bytes_within(path, limit) {
            Err(FileError::Invalid { path: named, msg }) => {
                assert_eq!(named, path.display().to_string());
                msg
            }
            other => panic!("{}: {other:?}", path.display()),
        };
        assert!(refused(Path::new("/dev/zero"), MAX_FILE_BYTES).contains("not a regular file"));
        assert!(refused(&dir, MAX_FILE_BYTES).contains("a folder"));
        let file = dir.join("ten.json");
        std::fs::write(&file, b"0123456789").unwrap();
        assert!(refused(&file, 9).contains("larger than the 9 bytes"));
        assert_eq!(read_bytes_within(&file, 10).unwrap(), b"0123456789");
        assert!(matches!(
            load_any_robot(Path::new("/dev/zero")),
            Err(FileError::Invalid { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_without_blocking() {
        let dir = std::env::temp_dir().join(format!("vsrlab-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("robot.json");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status().unwrap();
        assert!(made.success());
        // a blocking open would hang this test: the refusal comes from the metadata alone
        let error = read_text(&fifo).unwrap_err().to_string();
        assert!(error.contains("not a regular file"), "{error}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

#[cfg(test)]
mod kind_of_broken_files_tests {
    use super::*;

    #[test]
    fn a_robot_file_that_is_not_json_is_reported_by_its_own_kind() {
        let args = crate::kinds::RobotArgs {
            body: "psa:small",
            brain: None,
            sensors: None,
            preset: None,
        };
        let text = crate::kinds::from_short_forms(&args).unwrap().to_json(None);
        let radius = text.lines().find(|l| l.contains("\"radius\"")).unwrap();
        for bad in ["1e999", "NaN"] {
            let broken = text.replace(radius, &format!("\"radius\": {bad},"));
            let e = any_robot_from_json(&broken, "psa.json").unwrap_err().to_string();
            assert!(
                e.contains("psa.body.radius") && !e.contains("unknown field"),
                "{bad}: {e}"
            );
        }
    }

    #[test]
    fn a_psa_brain_short_form_is_named_as_given() {
        let args = crate::kinds::RobotArgs {
            body: "psa:small",
            brain: Some("heads:0"),
            sensors: None,
            preset: None,
        };
        let e = crate::kinds::from_short_forms(&args).unwrap_err();
        assert_eq!(e.part(), crate::kinds::voxel::short_forms::RobotPart::Brain);
        assert!(
            e.message().starts_with("'heads:0' (linear_outputs)") && !e.message().contains("robot."),
            "{}",
            e.message()
        );
    }
}
