//! The shape and behaviour classifiers of `analyze --labels`: random forests trained on the
//! features of the hand-labelled robots, replayed as the labels file says.

use crate::error::AnalysisError;
use crate::replay::replay;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::Path;
use vsrlab_analysis::diversity::Classifier;
use vsrlab_analysis::features::{FeatureParams, RobotFeatures};
use vsrlab_analysis::forest::{Folds, ForestParams};
use vsrlab_analysis::labels::{read_labels, LabelRow};
use vsrlab_analysis::progress::Progress;
use vsrlab_tasks::files::load_robot;
use vsrlab_tasks::{Locomotion, Terrain, TraceLevel};

/// The two trained classifiers.
#[derive(Debug, Clone)]
pub(crate) struct Classifiers {
    /// Morphology classes from the dynamic pose.
    pub shape: Classifier,
    /// Behaviour classes from the spectra and the gait.
    pub behaviour: Classifier,
    /// Training examples of each (shape, behaviour).
    pub examples: (usize, usize),
}

/// Replays every robot of the labels file on `pool` and trains both classifiers with `folds`-fold
/// cross-validation (folds shuffled with `seed`, as the labels come in the page's order).
pub(crate) fn train_classifiers(
    labels: &Path,
    folds: usize,
    seed: u64,
    pool: &rayon::ThreadPool,
    progress: &dyn Progress,
) -> Result<Classifiers, AnalysisError> {
    let rows = read_labels(labels)?;
    progress.note(&format!(
        "replaying {} labelled robots from {}…",
        rows.len(),
        labels.display()
    ));
    let feats: Vec<Result<RobotFeatures, AnalysisError>> =
        pool.install(|| rows.par_iter().map(|r| labelled_features(r, labels)).collect());
    let (mut sx, mut sy, mut bx, mut by) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (r, f) in rows.iter().zip(feats) {
        let f = f?;
        if !r.shape.trim().is_empty() {
            sx.push(f.morphology_vector());
            sy.push(r.shape.trim().to_string());
        }
        if !r.behaviour.trim().is_empty() {
            bx.push(f.behaviour_vector());
            by.push(r.behaviour.trim().to_string());
        }
    }
    if sx.len() < folds.max(2) || bx.len() < folds.max(2) {
        return Err(AnalysisError::TooFewLabels {
            labels: labels.to_path_buf(),
            shapes: sx.len(),
            behaviours: bx.len(),
            folds,
        });
    }
    let params = ForestParams {
        seed,
        ..Default::default()
    };
    let shape = Classifier::train(&sx, &sy, folds, Folds::Shuffled(seed), &params);
    let behaviour = Classifier::train(&bx, &by, folds, Folds::Shuffled(seed), &params);
    Ok(Classifiers {
        shape,
        behaviour,
        examples: (sx.len(), bx.len()),
    })
}

/// The features of one labelled robot, replayed on the episode its row names.
fn labelled_features(row: &LabelRow, labels: &Path) -> Result<RobotFeatures, AnalysisError> {
    let robot = load_robot(&row.robot_path(labels))?;
    let terrain = row.terrain.parse::<Terrain>().map_err(|e| AnalysisError::Terrain {
        robot: row.robot.clone(),
        terrain: row.terrain.clone(),
        message: e.to_string(),
    })?;
    let task = Locomotion {
        terrain,
        duration: row.duration,
        transient: row.transient,
        ..Locomotion::default()
    };
    let trace = replay(&robot, &task, row.seed, TraceLevel::Full).map_err(|source| AnalysisError::Replay {
        robot: row.robot.clone(),
        source,
    })?;
    Ok(RobotFeatures::from_trace(&trace, &FeatureParams::default()))
}

/// A warning when a classifier was trained on fewer than two classes: its accuracy is then 1 by
/// construction and its species mean nothing.
fn one_class_warning(name: &str, classes: &[String]) -> Option<String> {
    (classes.len() < 2).then(|| {
        format!(
            "{name}: the labels hold only {} class ({}), so its accuracy of 1.000 says nothing; label robots of at least two classes",
            classes.len(),
            classes.join(", ")
        )
    })
}

/// The classifiers as a Markdown table for `summary.md`, each also noted to `progress`.
pub(crate) fn classifier_table(cls: &Classifiers, folds: usize, progress: &dyn Progress) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "Classifiers (random forests, 100 trees, ⌊√p⌋ features per split, {} examples for shape, {} for behaviour; {}-fold cross-validation):\n",
        cls.examples.0, cls.examples.1, folds
    );
    let _ = writeln!(
        text,
        "| classifier | classes | CV accuracy | majority-class accuracy |\n|---|---|---:|---:|"
    );
    for (name, c) in [
        ("shape (dynamic pose, 256 features)", &cls.shape),
        ("behaviour (spectra + gait, 205 features)", &cls.behaviour),
    ] {
        let _ = writeln!(
            text,
            "| {name} | {} | {:.3} | {:.3} |",
            c.classes.join(", "),
            c.cv.accuracy,
            c.cv.majority_accuracy
        );
        progress.note(&format!(
            "{name}: CV accuracy {:.3} (majority class {:.3})",
            c.cv.accuracy, c.cv.majority_accuracy
        ));
        if let Some(warning) = one_class_warning(name, &c.classes) {
            progress.note(&warning);
            let _ = writeln!(text, "\n**Warning**: {warning}\n");
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_class_is_warned_about() {
        let one = vec!["walking".to_string()];
        let warning = one_class_warning("behaviour", &one).unwrap();
        assert!(warning.contains("only 1 class (walking)"), "{warning}");
        assert_eq!(one_class_warning("shape", &["blob".into(), "limbed".into()]), None);
    }
}
