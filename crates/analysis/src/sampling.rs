//! Stratified sampling of robots for labelling (thesis §3.3.2.2): every descriptor is split into
//! equal-size bins (by rank), the pool into the bins' product (4 × 4 × 4 = 64 by default), and
//! robots are drawn round-robin from the non-empty bins, in a seeded random order within each.
//! Also [`spread`], an even sample of a population.

use crate::forest::stream;
use rand_chacha::rand_core::RngCore;

/// Bin of every item for one descriptor: items sorted by value (ties by index) and cut into
/// `bins` equal-size groups.
pub fn rank_bins(values: &[f64], bins: usize) -> Vec<usize> {
    let n = values.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| values[a].total_cmp(&values[b]).then(a.cmp(&b)));
    let mut out = vec![0; n];
    for (pos, &i) in order.iter().enumerate() {
        out[i] = (pos * bins.max(1) / n.max(1)).min(bins.max(1) - 1);
    }
    out
}

/// Picks up to `count` item indices, stratified by the descriptors of each item
/// (`descriptors[i]` = the item's values, all of the same length), `bins` bins per descriptor.
/// Returns the indices in drawing order (the first ones cover as many bins as possible).
pub fn stratified_sample(descriptors: &[Vec<f64>], bins: usize, count: usize, seed: u64) -> Vec<usize> {
    let n = descriptors.len();
    if n == 0 || count == 0 {
        return Vec::new();
    }
    let d = descriptors[0].len();
    let per_descriptor: Vec<Vec<usize>> = (0..d)
        .map(|j| rank_bins(&descriptors.iter().map(|v| v[j]).collect::<Vec<f64>>(), bins))
        .collect();
    let key = |i: usize| per_descriptor.iter().fold(0usize, |k, b| k * bins.max(1) + b[i]);
    let mut cells: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    for i in 0..n {
        cells.entry(key(i)).or_default().push(i);
    }
    let mut rng = stream(seed, 0x5A3F);
    let mut queues: Vec<Vec<usize>> = cells
        .into_values()
        .map(|mut v| {
            for i in (1..v.len()).rev() {
                let j = (rng.next_u64() % (i as u64 + 1)) as usize;
                v.swap(i, j);
            }
            v.reverse(); // pop() then yields the shuffled order
            v
        })
        .collect();
    let mut out = Vec::new();
    while out.len() < count.min(n) {
        for q in queues.iter_mut() {
            if let Some(i) = q.pop() {
                out.push(i);
                if out.len() == count.min(n) {
                    break;
                }
            }
        }
    }
    out
}

/// Evenly spread indices: `k` of `0..n` (all when k = 0 or k ≥ n), e.g. to replay a sample of
/// a population.
pub fn spread(n: usize, k: usize) -> Vec<usize> {
    if k == 0 || k >= n {
        (0..n).collect()
    } else {
        (0..k).map(|i| i * n / k).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_picks_evenly() {
        assert_eq!(spread(10, 0), (0..10).collect::<Vec<_>>());
        assert_eq!(spread(10, 5), vec![0, 2, 4, 6, 8]);
        assert_eq!(spread(3, 5), vec![0, 1, 2]);
    }

    #[test]
    fn bins_are_equal_size() {
        assert_eq!(
            rank_bins(&[5.0, 1.0, 3.0, 2.0, 4.0, 0.0, 7.0, 6.0], 4),
            vec![2, 0, 1, 1, 2, 0, 3, 3]
        );
    }

    #[test]
    fn sample_covers_every_bin_first() {
        // Two descriptors, 2 bins each → 4 cells of 25 items; 8 picks take 2 from each cell.
        let items: Vec<Vec<f64>> = (0..100).map(|i| vec![(i % 10) as f64, (i / 10) as f64]).collect();
        let s = stratified_sample(&items, 2, 8, 7);
        assert_eq!(s.len(), 8);
        let cell = |i: usize| (usize::from(items[i][0] >= 5.0), usize::from(items[i][1] >= 5.0));
        let mut counts = std::collections::HashMap::new();
        for &i in &s {
            *counts.entry(cell(i)).or_insert(0) += 1;
        }
        assert_eq!(counts.len(), 4);
        assert!(counts.values().all(|&c| c == 2));
        assert_eq!(s, stratified_sample(&items, 2, 8, 7));
        assert_ne!(s, stratified_sample(&items, 2, 8, 8));
        let all = stratified_sample(&items, 2, 500, 7);
        assert_eq!(all.len(), 100);
    }
}
