//! The pool `label` draws from: every evaluated individual of every snapshot, each genotype once
//! per experiment, optionally without the slow ones.

use crate::error::AnalysisError;
use std::collections::HashSet;
use vsrlab_analysis::morphology::MorphologyDescriptors;
use vsrlab_analysis::results::{self, ExperimentData, SnapshotRow};

/// One individual that may be drawn for labelling.
#[derive(Debug, Clone)]
pub(crate) struct Candidate {
    /// Its experiment (index).
    pub experiment: usize,
    /// Its setting's name.
    pub setting: String,
    /// Its run's number.
    pub run: usize,
    /// Its snapshot line.
    pub row: SnapshotRow,
    /// Its body's descriptors.
    pub descriptors: MorphologyDescriptors,
}

/// Every evaluated individual with a body in the snapshots, in experiment, run and snapshot
/// order; survivors seen in several snapshots are kept once, and with `min_velocity`, slower
/// individuals are left out.
pub(crate) fn candidates(
    experiments: &[ExperimentData],
    min_velocity: Option<f64>,
) -> Result<Vec<Candidate>, AnalysisError> {
    let mut pool = Vec::new();
    let mut seen: HashSet<(String, String)> = HashSet::new();
    for (e, exp) in experiments.iter().enumerate() {
        for r in &exp.runs {
            for (_, path) in &r.snapshots {
                for row in results::read_snapshot(path)? {
                    if !eligible(&row, min_velocity) {
                        continue;
                    }
                    let Some(body) = row.morphology() else { continue };
                    let key = (exp.dir.display().to_string(), row.genotype.to_string());
                    if !seen.insert(key) {
                        continue;
                    }
                    pool.push(Candidate {
                        experiment: e,
                        setting: exp.name.clone(),
                        run: r.index,
                        descriptors: MorphologyDescriptors::of(&body),
                        row,
                    });
                }
            }
        }
    }
    Ok(pool)
}

/// Whether a snapshot line was evaluated, has a genotype, and is fast enough.
fn eligible(row: &SnapshotRow, min_velocity: Option<f64>) -> bool {
    row.error().is_none()
        && row.fitness().is_some()
        && !row.genotype.is_null()
        && !min_velocity.is_some_and(|v| row.velocity().unwrap_or(f64::NEG_INFINITY) < v)
}
