//! Checkpoints and the content hashes that let a resumed run trust its own files.
//!
//! A checkpoint is one JSON object: a format tag, a content hash and the content (run, seed,
//! run state, optimizer). The hash is FNV-1a 64 over the content's exact bytes in the file, so
//! any edit or damage to the content is caught on resume. It detects accidents and hand edits,
//! not an adversary (who could recompute it).
//!
//! The run state also records the hash of every file the run wrote before the checkpoint (the
//! covered part of `generations.csv`, every snapshot), and a finished run's `summary.json` records
//! the hash of its deterministic files, so `--resume` can tell a missing or damaged file apart from
//! a good one.

use crate::evaluator::Record;
use crate::genotype::fnv1a;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::value::RawValue;
use std::collections::BTreeMap;
use std::path::Path;

/// Format tag of checkpoint files written today (content hash included).
pub const CHECKPOINT_FORMAT: &str = "vsrlab-checkpoint/2";
/// Format tag of checkpoints written before content hashes (read without verification).
pub const CHECKPOINT_FORMAT_V1: &str = "vsrlab-checkpoint/1";

/// The content hash of some bytes, as written in checkpoints and summaries (`fnv1a64:…`).
pub fn content_hash(bytes: &[u8]) -> String {
    format!("fnv1a64:{:016x}", fnv1a(bytes.iter().copied()))
}

/// A snapshot file a run wrote: after how many evaluations, and the hash of its content.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct SnapshotEntry {
    pub evaluations: u64,
    pub hash: String,
}

/// Run state that is not the optimizer's: saved in checkpoints.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct RunState {
    /// Records of the current population's genotypes, by genotype hash.
    pub records: BTreeMap<u64, Record>,
    /// Evaluation count at which the next snapshot is due.
    pub next_snapshot: u64,
    /// Evaluation count of the last snapshot written.
    pub last_snapshot: Option<u64>,
    pub failures: u64,
    /// Genotype hash and record of the best individual so far.
    pub best: Option<(u64, Record)>,
    pub wall_seconds: f64,
    pub evaluation_seconds: f64,
    pub episode_cpu_seconds: f64,
    /// Bytes of `generations.csv` and `timings.csv` covered by this checkpoint.
    pub csv_bytes: u64,
    pub timings_bytes: u64,
    /// Hash of the covered part of `generations.csv` (empty in version-1 checkpoints).
    #[serde(default)]
    pub csv_hash: String,
    /// Every snapshot written so far (empty in version-1 checkpoints).
    #[serde(default)]
    pub snapshots: Vec<SnapshotEntry>,
}

/// What a checkpoint holds.
#[derive(Serialize, Deserialize)]
#[serde(bound(deserialize = "O: DeserializeOwned"))]
pub(crate) struct Checkpoint<O> {
    pub run: usize,
    pub seed: u64,
    pub state: RunState,
    pub optimizer: O,
}

#[derive(Serialize)]
struct CheckpointRef<'a, O> {
    run: usize,
    seed: u64,
    state: &'a RunState,
    optimizer: &'a O,
}

#[derive(Serialize, Deserialize)]
struct Envelope<'a> {
    format: String,
    #[serde(default)]
    content_hash: Option<String>,
    #[serde(borrow)]
    content: Option<&'a RawValue>,
}

/// A checkpoint of version 1: the content at the top level, next to the format tag.
#[derive(Deserialize)]
#[serde(bound(deserialize = "O: DeserializeOwned"))]
struct CheckpointV1<O> {
    run: usize,
    seed: u64,
    state: RunState,
    optimizer: O,
}

/// The bytes of a checkpoint file.
pub(crate) fn encode<O: Serialize>(
    run: usize,
    seed: u64,
    state: &RunState,
    optimizer: &O,
) -> Result<Vec<u8>, serde_json::Error> {
    let content = serde_json::to_string(&CheckpointRef {
        run,
        seed,
        state,
        optimizer,
    })?;
    let raw = RawValue::from_string(content)?;
    serde_json::to_vec(&Envelope {
        format: CHECKPOINT_FORMAT.to_string(),
        content_hash: Some(content_hash(raw.get().as_bytes())),
        content: Some(&raw),
    })
}

/// A checkpoint read back: the content, and whether its hash was verified (version-1 files have
/// none).
pub(crate) struct Loaded<O> {
    pub checkpoint: Checkpoint<O>,
    pub verified: bool,
}

/// What is wrong with a checkpoint file's bytes; the caller names the file.
#[derive(Debug, thiserror::Error)]
pub(crate) enum CheckpointProblem {
    /// Not JSON of a checkpoint's envelope.
    #[error("not a checkpoint: {0}")]
    NotACheckpoint(serde_json::Error),
    /// A current-format file without its hash or content.
    #[error("content_hash or content missing")]
    Incomplete,
    /// The content's hash is not the recorded one.
    #[error("content hash mismatch (recorded {recorded}, content has {actual}): the file was edited or damaged")]
    HashMismatch {
        /// The hash in the file.
        recorded: String,
        /// The hash of the content.
        actual: String,
    },
    /// The content does not read as this run's checkpoint.
    #[error("content: {0}")]
    Content(serde_json::Error),
    /// A version-1 file that does not read as this run's checkpoint.
    #[error("{0}")]
    Version1(serde_json::Error),
    /// A format this vsrlab does not know.
    #[error("unknown format {0:?} (this vsrlab reads {CHECKPOINT_FORMAT} and {CHECKPOINT_FORMAT_V1})")]
    UnknownFormat(String),
}

/// Reads a checkpoint file's bytes, verifying its content hash.
pub(crate) fn decode<O: DeserializeOwned>(bytes: &[u8]) -> Result<Loaded<O>, CheckpointProblem> {
    let envelope: Envelope<'_> = serde_json::from_slice(bytes).map_err(CheckpointProblem::NotACheckpoint)?;
    match envelope.format.as_str() {
        CHECKPOINT_FORMAT => {
            let (Some(hash), Some(content)) = (envelope.content_hash, envelope.content) else {
                return Err(CheckpointProblem::Incomplete);
            };
            let actual = content_hash(content.get().as_bytes());
            if actual != hash {
                return Err(CheckpointProblem::HashMismatch { recorded: hash, actual });
            }
            let checkpoint = serde_json::from_str(content.get()).map_err(CheckpointProblem::Content)?;
            Ok(Loaded {
                checkpoint,
                verified: true,
            })
        }
        CHECKPOINT_FORMAT_V1 => {
            let old: CheckpointV1<O> = serde_json::from_slice(bytes).map_err(CheckpointProblem::Version1)?;
            Ok(Loaded {
                checkpoint: Checkpoint {
                    run: old.run,
                    seed: old.seed,
                    state: old.state,
                    optimizer: old.optimizer,
                },
                verified: false,
            })
        }
        other => Err(CheckpointProblem::UnknownFormat(other.to_string())),
    }
}

/// What is wrong with a file whose hash was recorded: `None` when it is intact.
pub(crate) fn damage(path: &Path, expected: &str) -> Option<String> {
    match std::fs::read(path) {
        Ok(bytes) if content_hash(&bytes) == expected => None,
        Ok(_) => Some(format!("{} (content differs from the recorded hash)", path.display())),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Some(format!("{} (missing)", path.display())),
        Err(e) => Some(format!("{} ({e})", path.display())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state() -> RunState {
        RunState {
            next_snapshot: 100,
            failures: 2,
            csv_bytes: 10,
            csv_hash: content_hash(b"0123456789"),
            ..RunState::default()
        }
    }

    #[test]
    fn round_trips_and_verifies() {
        let bytes = encode(3, 42, &state(), &vec![1.5, -2.0]).unwrap();
        let loaded: Loaded<Vec<f64>> = decode(&bytes).unwrap();
        assert!(loaded.verified);
        assert_eq!(loaded.checkpoint.run, 3);
        assert_eq!(loaded.checkpoint.seed, 42);
        assert_eq!(loaded.checkpoint.state, state());
        assert_eq!(loaded.checkpoint.optimizer, vec![1.5, -2.0]);
    }

    #[test]
    fn an_edited_value_is_refused() {
        let bytes = encode(0, 1, &state(), &vec![1.5, -2.0]).unwrap();
        let text = String::from_utf8(bytes).unwrap().replace("-2.0", "1e300");
        let error = decode::<Vec<f64>>(text.as_bytes()).err().unwrap();
        assert!(matches!(error, CheckpointProblem::HashMismatch { .. }), "{error}");
        assert!(error.to_string().contains("content hash mismatch"), "{error}");
        let cut = &text.as_bytes()[..text.len() / 2];
        assert!(decode::<Vec<f64>>(cut).is_err());
    }

    #[test]
    fn version_1_checkpoints_are_read_unverified() {
        let v1 = serde_json::json!({
            "format": CHECKPOINT_FORMAT_V1, "run": 1, "seed": 9,
            "state": serde_json::to_value(state()).unwrap(), "optimizer": [0.25]
        });
        let loaded: Loaded<Vec<f64>> = decode(v1.to_string().as_bytes()).unwrap();
        assert!(!loaded.verified);
        assert_eq!(loaded.checkpoint.optimizer, vec![0.25]);
        let other = serde_json::json!({"format": "vsrlab-checkpoint/9"});
        let error = decode::<Vec<f64>>(other.to_string().as_bytes()).err().unwrap();
        assert!(matches!(&error, CheckpointProblem::UnknownFormat(f) if f == "vsrlab-checkpoint/9"));
        assert!(error.to_string().contains("unknown format"), "{error}");
    }

    #[test]
    fn damage_tells_missing_from_changed() {
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("a.txt");
        std::fs::write(&path, "abc").unwrap();
        assert_eq!(damage(&path, &content_hash(b"abc")), None);
        assert!(damage(&path, &content_hash(b"abd")).unwrap().contains("differs"));
        assert!(damage(&tmp.path().join("b.txt"), "x").unwrap().contains("missing"));
    }
}
