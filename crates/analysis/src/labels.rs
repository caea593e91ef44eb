//! The labels CSV that trains the species classifiers (written by `vsrlab label`'s page).
//!
//! Columns: `robot` (a robot file, relative to the CSV's folder), `terrain`, `duration`,
//! `transient`, `seed` (the episode to replay), `shape`, `behaviour` (class names; a row with an
//! empty class is skipped for that classifier). Extra columns are ignored.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use vsrlab_tasks::files::write_atomic;

/// One labelled robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LabelRow {
    /// Robot file, relative to the labels file's folder (or absolute).
    pub robot: String,
    /// Terrain of the episode.
    pub terrain: String,
    /// Episode length (s).
    pub duration: f64,
    /// Transient (s).
    #[serde(default)]
    pub transient: f64,
    /// Episode seed.
    #[serde(default)]
    pub seed: u64,
    /// Morphology class.
    #[serde(default)]
    pub shape: String,
    /// Behaviour class.
    #[serde(default)]
    pub behaviour: String,
}

impl LabelRow {
    /// The robot file's path, resolved against the labels file's folder.
    pub fn robot_path(&self, labels_file: &Path) -> PathBuf {
        let p = PathBuf::from(&self.robot);
        if p.is_absolute() {
            p
        } else {
            labels_file.parent().unwrap_or(Path::new(".")).join(p)
        }
    }
}

/// Why a labels CSV could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum LabelsError {
    /// The file could not be opened, or a row is malformed.
    #[error("{}{}: {source}", path.display(), row.map(|r| format!(", row {r}")).unwrap_or_default())]
    Csv {
        /// The labels file.
        path: PathBuf,
        /// The row (1 = the header), when a row is at fault.
        row: Option<usize>,
        /// The parser's report.
        source: csv::Error,
    },
    /// The file could not be written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The labels file.
        path: PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
}

/// Reads a labels CSV.
pub fn read_labels(path: &Path) -> Result<Vec<LabelRow>, LabelsError> {
    let csv_error = |row: Option<usize>| {
        move |source| LabelsError::Csv {
            path: path.to_path_buf(),
            row,
            source,
        }
    };
    let mut r = csv::Reader::from_path(path).map_err(csv_error(None))?;
    let mut out = Vec::new();
    for (i, row) in r.deserialize::<LabelRow>().enumerate() {
        out.push(row.map_err(csv_error(Some(i + 2)))?);
    }
    Ok(out)
}

/// Writes a labels CSV (atomically: a failure leaves no half-written file).
pub fn write_labels(path: &Path, rows: &[LabelRow]) -> Result<(), LabelsError> {
    let csv_error = |source| LabelsError::Csv {
        path: path.to_path_buf(),
        row: None,
        source,
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in rows {
        w.serialize(r).map_err(csv_error)?;
    }
    let bytes = w.into_inner().map_err(|e| csv_error(e.into_error().into()))?;
    write_atomic(path, &bytes).map_err(|source| LabelsError::Io {
        path: path.to_path_buf(),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip_and_extra_columns() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("labels.csv");
        let rows = vec![LabelRow {
            robot: "robots/r-0001.robot.json".into(),
            terrain: "flat".into(),
            duration: 10.0,
            transient: 0.0,
            seed: 3,
            shape: "blob".into(),
            behaviour: "".into(),
        }];
        write_labels(&p, &rows).unwrap();
        assert_eq!(read_labels(&p).unwrap(), rows);
        assert_eq!(rows[0].robot_path(&p), dir.path().join("robots/r-0001.robot.json"));
        std::fs::write(
            &p,
            "id,robot,terrain,duration,transient,seed,shape,behaviour,note\n1,a.json,flat,5,0,0,limbed,walking,x\n",
        )
        .unwrap();
        let r = read_labels(&p).unwrap();
        assert_eq!((r[0].shape.as_str(), r[0].behaviour.as_str()), ("limbed", "walking"));
    }
}
