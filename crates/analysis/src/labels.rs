//! The labels CSV that trains the species classifiers (written by `vsrlab label`'s page).
//!
//! Columns: `robot` (a robot file, relative to the CSV's folder), `terrain`, `duration`,
//! `transient`, `seed` (the episode to replay), `shape`, `behaviour` (class names; a row with an
//! empty class is skipped for that classifier). Extra columns are ignored.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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

/// Reads a labels CSV.
pub fn read_labels(path: &Path) -> Result<Vec<LabelRow>, String> {
    let mut r = csv::Reader::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = Vec::new();
    for (i, row) in r.deserialize::<LabelRow>().enumerate() {
        out.push(row.map_err(|e| format!("{}, row {}: {e}", path.display(), i + 2))?);
    }
    Ok(out)
}

/// Writes a labels CSV.
pub fn write_labels(path: &Path, rows: &[LabelRow]) -> Result<(), String> {
    let mut w = csv::Writer::from_path(path).map_err(|e| format!("{}: {e}", path.display()))?;
    for r in rows {
        w.serialize(r).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    w.flush().map_err(|e| format!("{}: {e}", path.display()))
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
