//! A random-forest classifier (Breiman 2001) with scikit-learn's defaults, and k-fold
//! cross-validation beside the majority-class baseline (thesis §3.3.3.3).
//!
//! - Each tree is a CART tree grown on a bootstrap sample (n draws with replacement, kept as
//!   per-sample weights) until its leaves are pure or cannot be split; Gini impurity.
//! - At every node, features are drawn in random order and the best threshold of each is found;
//!   the search stops after `max_features` (⌊√p⌋ by default) features, or later if all of those
//!   were constant in the node (scikit-learn's rule). Thresholds are midpoints between
//!   consecutive distinct values; values closer than 1e-7 count as equal. A sample goes left iff
//!   its value ≤ threshold.
//! - Trees vote with their leaves' class distributions (soft voting), ties → lowest class.
//! - Tree t draws its numbers from its own ChaCha8 stream derived from (seed, t), so a forest is
//!   a pure function of its data and seed, whatever the number of threads.

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

const FEATURE_THRESHOLD: f64 = 1e-7;

/// How many features a split considers.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MaxFeatures {
    /// ⌊√p⌋ (at least 1).
    Sqrt,
    /// All p features (bagged trees).
    All,
    /// A fixed number (clamped to 1..=p).
    Count(usize),
}

impl MaxFeatures {
    fn resolve(self, p: usize) -> usize {
        match self {
            MaxFeatures::Sqrt => ((p as f64).sqrt().floor() as usize).max(1),
            MaxFeatures::All => p,
            MaxFeatures::Count(k) => k.clamp(1, p.max(1)),
        }
    }
}

/// Forest settings; the defaults are scikit-learn's `RandomForestClassifier()` ones.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ForestParams {
    /// Number of trees.
    pub trees: usize,
    /// Features considered per split.
    pub max_features: MaxFeatures,
    /// Grow each tree on a bootstrap sample (true) or on the whole data.
    pub bootstrap: bool,
    /// Maximum depth (None: until pure).
    pub max_depth: Option<usize>,
    /// Seed of the forest.
    pub seed: u64,
}

impl Default for ForestParams {
    fn default() -> Self {
        ForestParams {
            trees: 100,
            max_features: MaxFeatures::Sqrt,
            bootstrap: true,
            max_depth: None,
            seed: 0,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
enum Node {
    Leaf(Vec<f64>),
    Split {
        feature: usize,
        threshold: f64,
        left: usize,
        right: usize,
    },
}

/// One classification tree.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Tree {
    nodes: Vec<Node>,
}

impl Tree {
    /// Class probabilities of a sample.
    pub fn predict_proba(&self, x: &[f64]) -> &[f64] {
        let mut i = 0;
        loop {
            match &self.nodes[i] {
                Node::Leaf(p) => return p,
                Node::Split {
                    feature,
                    threshold,
                    left,
                    right,
                } => {
                    i = if x[*feature] <= *threshold { *left } else { *right };
                }
            }
        }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the tree has no node (never, once fitted).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }
}

/// A uniform integer in [0, n) (Lemire's multiply-and-reject).
fn below(rng: &mut ChaCha8Rng, n: usize) -> usize {
    let n = n as u64;
    let threshold = n.wrapping_neg() % n;
    loop {
        let m = (rng.next_u64() as u128) * (n as u128);
        if (m as u64) >= threshold {
            return (m >> 64) as usize;
        }
    }
}

/// SplitMix64 finaliser, to derive independent stream seeds.
pub(crate) fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A ChaCha8 generator for stream `index` of `seed`.
pub(crate) fn stream(seed: u64, index: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(mix(mix(seed) ^ mix(index.wrapping_add(0x5EED))))
}

struct Builder<'a> {
    x: &'a [Vec<f64>],
    y: &'a [usize],
    w: &'a [f64],
    classes: usize,
    mtry: usize,
    max_depth: usize,
    nodes: Vec<Node>,
    rng: ChaCha8Rng,
}

impl Builder<'_> {
    fn counts(&self, samples: &[usize]) -> Vec<f64> {
        let mut c = vec![0.0; self.classes];
        for &s in samples {
            c[self.y[s]] += self.w[s];
        }
        c
    }

    fn leaf(&mut self, counts: &[f64]) -> usize {
        let total: f64 = counts.iter().sum();
        let p = counts
            .iter()
            .map(|c| if total > 0.0 { c / total } else { 0.0 })
            .collect();
        self.nodes.push(Node::Leaf(p));
        self.nodes.len() - 1
    }

    /// Best (score, feature, threshold, left samples, right samples) over the drawn features.
    fn best_split(&mut self, samples: &mut [usize]) -> Option<(usize, f64, usize)> {
        let p = self.x[0].len();
        let mut order: Vec<usize> = (0..p).collect();
        let mut drawn = 0;
        let mut visited = 0;
        let mut constant = 0;
        let mut best: Option<(f64, usize, f64)> = None;
        let total = self.counts(samples);
        let w_total: f64 = total.iter().sum();
        while drawn < p && (visited < self.mtry || visited <= constant) {
            let j = drawn + below(&mut self.rng, p - drawn);
            order.swap(drawn, j);
            let f = order[drawn];
            drawn += 1;
            visited += 1;
            samples.sort_unstable_by(|&a, &b| self.x[a][f].total_cmp(&self.x[b][f]));
            let (lo, hi) = (self.x[samples[0]][f], self.x[samples[samples.len() - 1]][f]);
            if hi <= lo + FEATURE_THRESHOLD {
                constant += 1;
                continue;
            }
            let mut left = vec![0.0; self.classes];
            let mut w_left = 0.0;
            for i in 1..samples.len() {
                let s = samples[i - 1];
                left[self.y[s]] += self.w[s];
                w_left += self.w[s];
                let (a, b) = (self.x[s][f], self.x[samples[i]][f]);
                if b <= a + FEATURE_THRESHOLD {
                    continue;
                }
                let w_right = w_total - w_left;
                // Maximising Σ l²/w_l + Σ r²/w_r minimises the weighted Gini of the children.
                let mut score = 0.0;
                for k in 0..self.classes {
                    let r = total[k] - left[k];
                    score += left[k] * left[k] / w_left + r * r / w_right;
                }
                if best.is_none_or(|(s, _, _)| score > s) {
                    let mut t = a / 2.0 + b / 2.0;
                    if t == b || !t.is_finite() {
                        t = a;
                    }
                    best = Some((score, f, t));
                }
            }
        }
        let (_, f, t) = best?;
        // Partition: samples with value ≤ t first.
        let mut i = 0;
        for k in 0..samples.len() {
            if self.x[samples[k]][f] <= t {
                samples.swap(i, k);
                i += 1;
            }
        }
        Some((f, t, i))
    }

    fn grow(&mut self, samples: &mut [usize], depth: usize) -> usize {
        let counts = self.counts(samples);
        let nonzero = counts.iter().filter(|&&c| c > 0.0).count();
        if nonzero <= 1 || samples.len() < 2 || depth >= self.max_depth {
            return self.leaf(&counts);
        }
        match self.best_split(samples) {
            None => self.leaf(&counts),
            Some((feature, threshold, cut)) => {
                let id = self.nodes.len();
                self.nodes.push(Node::Leaf(Vec::new()));
                let (l, r) = samples.split_at_mut(cut);
                let left = self.grow(l, depth + 1);
                let right = self.grow(r, depth + 1);
                self.nodes[id] = Node::Split {
                    feature,
                    threshold,
                    left,
                    right,
                };
                id
            }
        }
    }
}

/// A fitted random forest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RandomForest {
    /// Number of classes (labels are 0..classes).
    pub classes: usize,
    /// Number of features.
    pub features: usize,
    trees: Vec<Tree>,
}

impl RandomForest {
    /// Fits a forest to rows `x` (all of the same length) with labels `y` in 0..classes.
    ///
    /// # Panics
    /// If `x` is empty, rows differ in length, or a label is ≥ `classes`.
    pub fn fit(x: &[Vec<f64>], y: &[usize], classes: usize, params: &ForestParams) -> RandomForest {
        assert!(
            !x.is_empty() && x.len() == y.len(),
            "need as many labels as rows, and at least one row"
        );
        let p = x[0].len();
        assert!(x.iter().all(|r| r.len() == p), "rows must have the same length");
        assert!(y.iter().all(|&c| c < classes), "labels must be < classes");
        let mtry = params.max_features.resolve(p);
        let trees = (0..params.trees)
            .into_par_iter()
            .map(|t| {
                let mut rng = stream(params.seed, t as u64);
                let n = x.len();
                let mut w = vec![0.0; n];
                if params.bootstrap {
                    for _ in 0..n {
                        w[below(&mut rng, n)] += 1.0;
                    }
                } else {
                    w.fill(1.0);
                }
                let mut samples: Vec<usize> = (0..n).filter(|&i| w[i] > 0.0).collect();
                let mut b = Builder {
                    x,
                    y,
                    w: &w,
                    classes,
                    mtry,
                    max_depth: params.max_depth.unwrap_or(usize::MAX),
                    nodes: Vec::new(),
                    rng,
                };
                b.grow(&mut samples, 0);
                Tree { nodes: b.nodes }
            })
            .collect();
        RandomForest {
            classes,
            features: p,
            trees,
        }
    }

    /// Mean of the trees' class distributions.
    pub fn predict_proba(&self, x: &[f64]) -> Vec<f64> {
        let mut p = vec![0.0; self.classes];
        for t in &self.trees {
            for (a, b) in p.iter_mut().zip(t.predict_proba(x)) {
                *a += b;
            }
        }
        let n = self.trees.len().max(1) as f64;
        p.iter_mut().for_each(|v| *v /= n);
        p
    }

    /// Most probable class (ties → the lowest).
    pub fn predict(&self, x: &[f64]) -> usize {
        argmax(&self.predict_proba(x))
    }

    /// The trees.
    pub fn trees(&self) -> &[Tree] {
        &self.trees
    }
}

fn argmax(v: &[f64]) -> usize {
    let mut best = 0;
    for (i, &p) in v.iter().enumerate() {
        if p > v[best] {
            best = i;
        }
    }
    best
}

/// How k-fold cross-validation splits the rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Folds {
    /// Contiguous blocks in row order (scikit-learn's `KFold(shuffle=False)`; the thesis
    /// protocol): the first n mod k folds hold one row more.
    Contiguous,
    /// Contiguous blocks of a seeded permutation of the rows.
    Shuffled(u64),
}

/// Test-row indices of each of the k folds.
pub fn kfold(n: usize, k: usize, folds: Folds) -> Vec<Vec<usize>> {
    let mut rows: Vec<usize> = (0..n).collect();
    if let Folds::Shuffled(seed) = folds {
        let mut rng = stream(seed, u64::MAX);
        for i in (1..n).rev() {
            let j = below(&mut rng, i + 1);
            rows.swap(i, j);
        }
    }
    let k = k.clamp(1, n.max(1));
    let mut out = Vec::with_capacity(k);
    let mut start = 0;
    for f in 0..k {
        let size = n / k + usize::from(f < n % k);
        out.push(rows[start..start + size].to_vec());
        start += size;
    }
    out
}

/// Cross-validated accuracy of the forest beside the majority-class baseline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CvReport {
    /// Accuracy on each test fold.
    pub fold_accuracy: Vec<f64>,
    /// Accuracy of always predicting the training folds' most frequent class.
    pub fold_majority_accuracy: Vec<f64>,
    /// Mean of `fold_accuracy`.
    pub accuracy: f64,
    /// Mean of `fold_majority_accuracy`.
    pub majority_accuracy: f64,
}

/// k-fold cross-validation: for each fold, fit on the others (with seed `params.seed` + fold)
/// and score on it.
pub fn cross_validate(
    x: &[Vec<f64>],
    y: &[usize],
    classes: usize,
    k: usize,
    folds: Folds,
    params: &ForestParams,
) -> CvReport {
    let parts = kfold(x.len(), k, folds);
    let mut fold_accuracy = Vec::new();
    let mut fold_majority_accuracy = Vec::new();
    for (f, test) in parts.iter().enumerate() {
        let mut is_test = vec![false; x.len()];
        test.iter().for_each(|&i| is_test[i] = true);
        let train: Vec<usize> = (0..x.len()).filter(|&i| !is_test[i]).collect();
        if train.is_empty() || test.is_empty() {
            continue;
        }
        let tx: Vec<Vec<f64>> = train.iter().map(|&i| x[i].clone()).collect();
        let ty: Vec<usize> = train.iter().map(|&i| y[i]).collect();
        let p = ForestParams {
            seed: params.seed.wrapping_add(f as u64),
            ..*params
        };
        let forest = RandomForest::fit(&tx, &ty, classes, &p);
        let hits = test.iter().filter(|&&i| forest.predict(&x[i]) == y[i]).count();
        fold_accuracy.push(hits as f64 / test.len() as f64);
        let mut counts = vec![0usize; classes];
        ty.iter().for_each(|&c| counts[c] += 1);
        let majority = argmax(&counts.iter().map(|&c| c as f64).collect::<Vec<_>>());
        let hits = test.iter().filter(|&&i| y[i] == majority).count();
        fold_majority_accuracy.push(hits as f64 / test.len() as f64);
    }
    let mean = |v: &[f64]| {
        if v.is_empty() {
            f64::NAN
        } else {
            v.iter().sum::<f64>() / v.len() as f64
        }
    };
    CvReport {
        accuracy: mean(&fold_accuracy),
        majority_accuracy: mean(&fold_majority_accuracy),
        fold_accuracy,
        fold_majority_accuracy,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn below_is_uniform_enough() {
        let mut rng = stream(1, 2);
        let mut counts = [0usize; 5];
        for _ in 0..50_000 {
            counts[below(&mut rng, 5)] += 1;
        }
        assert!(counts.iter().all(|&c| (9_500..10_500).contains(&c)), "{counts:?}");
    }

    #[test]
    fn kfold_sizes_match_scikit_learn() {
        let f = kfold(10, 3, Folds::Contiguous);
        assert_eq!(f, vec![vec![0, 1, 2, 3], vec![4, 5, 6], vec![7, 8, 9]]);
        let s = kfold(10, 3, Folds::Shuffled(4));
        let mut all: Vec<usize> = s.concat();
        all.sort();
        assert_eq!(all, (0..10).collect::<Vec<_>>());
        assert_ne!(s, f);
    }

    #[test]
    fn a_single_tree_without_bagging_separates_separable_data() {
        // Class = (x0 > 0.5) xor (x1 > 0.5): needs two levels of splits.
        let mut x = Vec::new();
        let mut y = Vec::new();
        for i in 0..20 {
            for j in 0..20 {
                let (a, b) = (i as f64 / 19.0, j as f64 / 19.0);
                x.push(vec![a, b]);
                y.push(usize::from((a > 0.5) != (b > 0.5)));
            }
        }
        let p = ForestParams {
            trees: 1,
            bootstrap: false,
            max_features: MaxFeatures::All,
            ..Default::default()
        };
        let f = RandomForest::fit(&x, &y, 2, &p);
        assert!(x.iter().zip(&y).all(|(r, &c)| f.predict(r) == c));
        assert!(!f.trees()[0].is_empty());
    }

    #[test]
    fn forests_are_deterministic_and_learn_noisy_data() {
        let mut rng = stream(9, 9);
        let mut unit = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
        let mut x = Vec::new();
        let mut y = Vec::new();
        for _ in 0..300 {
            let c = (unit() * 3.0) as usize;
            x.push(vec![c as f64 + unit() * 1.2, unit(), unit(), unit() * 2.0 - c as f64]);
            y.push(c);
        }
        let p = ForestParams {
            trees: 30,
            seed: 3,
            ..Default::default()
        };
        let a = RandomForest::fit(&x, &y, 3, &p);
        let b = RandomForest::fit(&x, &y, 3, &p);
        assert_eq!(a, b);
        let cv = cross_validate(&x, &y, 3, 5, Folds::Contiguous, &p);
        assert!(cv.accuracy > 0.9, "{cv:?}");
        assert!(cv.majority_accuracy < 0.5, "{cv:?}");
        assert_eq!(cv.fold_accuracy.len(), 5);
    }

    #[test]
    fn constant_features_are_skipped() {
        // Only feature 3 of 4 varies: with max_features = 1 the search must go on past constants.
        let x: Vec<Vec<f64>> = (0..10).map(|i| vec![1.0, 1.0, 1.0, i as f64]).collect();
        let y: Vec<usize> = (0..10).map(|i| usize::from(i >= 5)).collect();
        let p = ForestParams {
            trees: 5,
            max_features: MaxFeatures::Count(1),
            bootstrap: false,
            ..Default::default()
        };
        let f = RandomForest::fit(&x, &y, 2, &p);
        assert!(x.iter().zip(&y).all(|(r, &c)| f.predict(r) == c));
    }
}
