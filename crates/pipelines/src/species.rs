//! Species over evolution: every snapshot's individuals (or an even sample of them) replayed,
//! classified by shape and behaviour, and summarised by the Inverse Simpson Index.

use crate::classifiers::Classifiers;
use crate::error::AnalysisError;
use crate::replay::ReplaySetup;
use crate::settings::Setting;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::Path;
use vsrlab_analysis::diversity::{inverse_simpson, species_index};
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::progress::Progress;
use vsrlab_analysis::report::csv_field;
use vsrlab_analysis::results::{self, ExperimentData, SnapshotRow};
use vsrlab_analysis::sampling::spread;

/// The species of one replayed individual.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Labelled {
    /// Morphology class index.
    pub shape: usize,
    /// Behaviour class index.
    pub behaviour: usize,
    /// Its velocity as evaluated (NaN when unknown).
    pub velocity: f64,
}

/// Diversity of one snapshot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SnapshotIsi {
    /// Evaluations at the snapshot.
    pub evaluations: u64,
    /// ISI of morphology classes.
    pub shape: f64,
    /// ISI of behaviour classes.
    pub behaviour: f64,
    /// ISI of species (shape × behaviour).
    pub species: f64,
}

/// The species of one run over its snapshots.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct RunSpecies {
    /// Its setting (colour index).
    pub setting: usize,
    /// The run, as tables name it.
    pub run: String,
    /// Diversity per snapshot (snapshots with no replayable individual left out).
    pub snapshots: Vec<SnapshotIsi>,
    /// The individuals of its last labelled snapshot (the final population).
    pub last: Vec<Labelled>,
}

/// Classifies the individuals of every snapshot of every replayable run.
pub(crate) fn species_over_time(
    experiments: &[ExperimentData],
    settings: &[Setting],
    setups: &[Option<ReplaySetup>],
    cls: &Classifiers,
    sample: usize,
    pool: &rayon::ThreadPool,
    progress: &dyn Progress,
) -> Result<Vec<RunSpecies>, AnalysisError> {
    let mut runs = Vec::new();
    for s in settings {
        for &e in &s.experiments {
            let exp = &experiments[e];
            let Some(setup) = &setups[e] else { continue };
            for r in &exp.runs {
                progress.note(&format!(
                    "species: {} run {:02}: {} snapshots…",
                    s.name,
                    r.index,
                    r.snapshots.len()
                ));
                let mut run = RunSpecies {
                    setting: s.color,
                    run: exp.run_label(r),
                    snapshots: Vec::new(),
                    last: Vec::new(),
                };
                for (evals, path) in &r.snapshots {
                    let labelled = label_snapshot(path, setup, cls, sample, pool, progress)?;
                    if labelled.is_empty() {
                        continue;
                    }
                    run.snapshots.push(snapshot_isi(*evals, &labelled, cls));
                    run.last = labelled;
                }
                runs.push(run);
            }
        }
    }
    Ok(runs)
}

/// Replays and classifies the evaluated individuals of one snapshot (`sample` of them evenly
/// spread, 0 = all); individuals that cannot be replayed are left out with a warning.
fn label_snapshot(
    path: &Path,
    setup: &ReplaySetup,
    cls: &Classifiers,
    sample: usize,
    pool: &rayon::ThreadPool,
    progress: &dyn Progress,
) -> Result<Vec<Labelled>, AnalysisError> {
    let rows = results::read_snapshot(path)?;
    let rows: Vec<&SnapshotRow> = rows
        .iter()
        .filter(|x| x.error().is_none() && x.fitness().is_some())
        .collect();
    let picked: Vec<&SnapshotRow> = spread(rows.len(), sample).into_iter().map(|i| rows[i]).collect();
    Ok(pool.install(|| {
        picked
            .par_iter()
            .filter_map(|row| {
                let (_, trace) = setup
                    .replay_row(row)
                    .map_err(|err| progress.note(&format!("warning: {}: {err}", path.display())))
                    .ok()?;
                let f = RobotFeatures::from_trace(&trace, &FeatureParams::default());
                Some(Labelled {
                    shape: cls.shape.predict_index(&f.morphology_vector()),
                    behaviour: cls.behaviour.predict_index(&f.behaviour_vector()),
                    velocity: row.velocity().unwrap_or(f64::NAN),
                })
            })
            .collect()
    }))
}

/// The ISI of shapes, behaviours and species of one snapshot's individuals.
fn snapshot_isi(evaluations: u64, labelled: &[Labelled], cls: &Classifiers) -> SnapshotIsi {
    let nb = cls.behaviour.classes.len();
    let shapes: Vec<usize> = labelled.iter().map(|l| l.shape).collect();
    let behaviours: Vec<usize> = labelled.iter().map(|l| l.behaviour).collect();
    let species: Vec<usize> = labelled
        .iter()
        .map(|l| species_index(l.shape, l.behaviour, nb))
        .collect();
    SnapshotIsi {
        evaluations,
        shape: inverse_simpson(&shapes),
        behaviour: inverse_simpson(&behaviours),
        species: inverse_simpson(&species),
    }
}

/// `isi.csv`: per run and snapshot, the ISI of species, shape and behaviour.
pub(crate) fn isi_csv(settings: &[Setting], runs: &[RunSpecies]) -> String {
    let mut s = String::from("setting,run,evaluations,isi_species,isi_shape,isi_behaviour\n");
    for run in runs {
        for x in &run.snapshots {
            let _ = writeln!(
                s,
                "{},{},{},{},{},{}",
                csv_field(&settings[run.setting].name),
                csv_field(&run.run),
                x.evaluations,
                x.species,
                x.shape,
                x.behaviour
            );
        }
    }
    s
}
