//! Species and diversity (thesis §3.3.2–3.3.4; thesis-code-facts §3.7): labelled classifiers for
//! the morphology and behaviour classes, species = behaviour + n_behaviour · shape, and the
//! Inverse Simpson Index of a population.

use crate::forest::{cross_validate, CvReport, Folds, ForestParams, RandomForest};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::hash::Hash;

/// Inverse Simpson Index 1 / Σ pₛ² of the labels' species shares (NaN when empty): 1 for a
/// single species, k for k equally common ones.
pub fn inverse_simpson<T: Eq + Hash>(labels: &[T]) -> f64 {
    if labels.is_empty() {
        return f64::NAN;
    }
    let mut counts: HashMap<&T, usize> = HashMap::new();
    for l in labels {
        *counts.entry(l).or_default() += 1;
    }
    let n = labels.len() as f64;
    1.0 / counts.values().map(|&c| (c as f64 / n).powi(2)).sum::<f64>()
}

/// Shares of each label, sorted by decreasing share (ties by label).
pub fn shares<T: Eq + Hash + Ord + Clone>(labels: &[T]) -> Vec<(T, f64)> {
    let mut counts: HashMap<&T, usize> = HashMap::new();
    for l in labels {
        *counts.entry(l).or_default() += 1;
    }
    let n = labels.len() as f64;
    let mut v: Vec<(T, f64)> = counts.into_iter().map(|(k, c)| (k.clone(), c as f64 / n)).collect();
    v.sort_by(|a, b| b.1.total_cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    v
}

/// Species index of a (shape, behaviour) pair: behaviour + n_behaviour · shape (thesis: 4 × 4).
pub fn species_index(shape: usize, behaviour: usize, behaviour_classes: usize) -> usize {
    behaviour + behaviour_classes * shape
}

/// A random forest over named classes, with its cross-validated accuracy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Classifier {
    /// Class names, in label order (sorted).
    pub classes: Vec<String>,
    /// The forest, fitted on every labelled example.
    pub forest: RandomForest,
    /// k-fold cross-validated accuracy beside the majority-class accuracy.
    pub cv: CvReport,
}

impl Classifier {
    /// Cross-validates with `k` folds and fits the final forest on all examples. Classes are
    /// the distinct labels, sorted.
    pub fn train(x: &[Vec<f64>], labels: &[String], k: usize, folds: Folds, params: &ForestParams) -> Classifier {
        let mut classes: Vec<String> = labels.to_vec();
        classes.sort();
        classes.dedup();
        let y: Vec<usize> = labels.iter().map(|l| classes.binary_search(l).unwrap()).collect();
        let cv = cross_validate(x, &y, classes.len(), k, folds, params);
        let forest = RandomForest::fit(x, &y, classes.len(), params);
        Classifier { classes, forest, cv }
    }

    /// Predicted class index.
    pub fn predict_index(&self, x: &[f64]) -> usize {
        self.forest.predict(x)
    }

    /// Predicted class name.
    pub fn predict(&self, x: &[f64]) -> &str {
        &self.classes[self.forest.predict(x)]
    }
}

/// The thesis' (TELO) morphology classes.
pub const SHAPE_CLASSES: [&str; 4] = ["blob", "limbed", "elongated", "other"];
/// The thesis' (TELO) behaviour classes.
pub const BEHAVIOUR_CLASSES: [&str; 4] = ["jumping", "walking", "rolling", "other"];

/// A rule-of-thumb morphology class, to pre-fill the labelling page (not the thesis' labels,
/// which were given by hand): elongated when elongation ≥ 0.9 (the body's second moments differ
/// by more than 5:1, a worm of 2 × 5 or longer; a 4 × 3 biped is 0.78) and compactness ≥ 0.8; blob
/// when compactness ≥ 0.9 (at most one cell in ten of its convex hull empty); limbed otherwise
/// (a 4 × 3 biped, compactness 0.83, has two legs); other for bodies of fewer than 3 voxels.
pub fn propose_shape(d: &crate::morphology::MorphologyDescriptors) -> &'static str {
    if d.voxels < 3 {
        "other"
    } else if d.elongation >= 0.9 && d.compactness >= 0.8 {
        "elongated"
    } else if d.compactness >= 0.9 {
        "blob"
    } else {
        "limbed"
    }
}

/// A rule-of-thumb behaviour class, to pre-fill the labelling page: rolling when the body turns
/// over at least once in the episode; jumping when the whole body is off the ground in ≥ 15% of
/// the steps ([`crate::features::airborne_fraction`]); walking when the main footprint n-gram
/// repeats at least 3 times with purity ≥ 0.5 and holds at least two different footprints, or
/// when the centre moved at least 2 voxel sides (either way) over the episode; other otherwise
/// (robots that stay in place).
pub fn propose_behaviour(f: &crate::features::RobotFeatures) -> &'static str {
    let distinct = {
        let mut g = f.gait.ngram.clone();
        g.sort_unstable();
        g.dedup();
        g.len()
    };
    if f.turns.abs() >= 1.0 {
        "rolling"
    } else if f.airborne >= 0.15 {
        "jumping"
    } else if (f.gait.occurrences >= 3 && f.gait.purity >= 0.5 && distinct >= 2) || f.displacement.abs() >= 2.0 {
        "walking"
    } else {
        "other"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn isi_known_values() {
        assert_eq!(inverse_simpson(&[1, 1, 1, 1]), 1.0);
        assert!((inverse_simpson(&["a", "b", "a", "b"]) - 2.0).abs() < 1e-12);
        assert!((inverse_simpson(&[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15]) - 16.0).abs() < 1e-9);
        // Shares ¾, ¼: 1 / (9/16 + 1/16) = 1.6.
        assert!((inverse_simpson(&[0, 0, 0, 1]) - 1.6).abs() < 1e-12);
        assert!(inverse_simpson::<u8>(&[]).is_nan());
        assert_eq!(shares(&[2, 1, 2]), vec![(2, 2.0 / 3.0), (1, 1.0 / 3.0)]);
        assert_eq!(species_index(2, 3, 4), 11);
    }

    #[test]
    fn proposals() {
        use crate::morphology::MorphologyDescriptors;
        let d = |s: &str| MorphologyDescriptors::of(&vsrlab_body::Morphology::parse(s).unwrap());
        assert_eq!(propose_shape(&d("####/####/####/####")), "blob");
        assert_eq!(propose_shape(&d("##########/##########")), "elongated");
        assert_eq!(propose_shape(&d("#####/#...#/#...#")), "limbed");
        assert_eq!(propose_shape(&d("####/####/#..#")), "limbed");
        assert_eq!(propose_shape(&d("#####/#####")), "elongated");
        assert_eq!(propose_shape(&d("####/####")), "blob");
        assert_eq!(propose_shape(&d("##")), "other");
    }

    #[test]
    fn classifier_names_classes() {
        let x: Vec<Vec<f64>> = (0..40).map(|i| vec![i as f64, (i % 3) as f64]).collect();
        let labels: Vec<String> = (0..40)
            .map(|i| if i < 20 { "blob".into() } else { "limbed".into() })
            .collect();
        let p = ForestParams {
            trees: 10,
            ..Default::default()
        };
        let c = Classifier::train(&x, &labels, 5, Folds::Shuffled(1), &p);
        assert_eq!(c.classes, vec!["blob", "limbed"]);
        assert_eq!(c.predict(&[3.0, 0.0]), "blob");
        assert_eq!(c.predict(&[35.0, 1.0]), "limbed");
        assert!(c.cv.accuracy > 0.9);
    }
}
