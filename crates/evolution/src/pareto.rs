//! Pareto dominance, fast non-dominated sorting, crowding distance (Deb et al. 2002) and the
//! two-objective hypervolume indicator.

use crate::optimizer::Sense;
use std::cmp::Ordering;

/// Whether `a` Pareto-dominates `b`: no worse in every objective and better in at least one.
/// Identical vectors do not dominate each other (unlike the Voxcraft code, thesis-code-facts
/// §7.4). NaN counts as the worst value.
pub fn dominates(a: &[f64], b: &[f64], senses: &[Sense]) -> bool {
    let mut strictly = false;
    for ((&x, &y), sense) in a.iter().zip(b).zip(senses) {
        match sense.compare(x, y) {
            Ordering::Less => return false,
            Ordering::Greater => strictly = true,
            Ordering::Equal => {}
        }
    }
    strictly
}

/// Fast non-dominated sort: the fronts as lists of indices into `objectives`, best front
/// first; indices inside a front are ascending.
pub fn non_dominated_sort(objectives: &[&[f64]], senses: &[Sense]) -> Vec<Vec<usize>> {
    let n = objectives.len();
    let mut dominated_by_me: Vec<Vec<usize>> = vec![Vec::new(); n];
    let mut domination_count = vec![0usize; n];
    for i in 0..n {
        for j in i + 1..n {
            if dominates(objectives[i], objectives[j], senses) {
                dominated_by_me[i].push(j);
                domination_count[j] += 1;
            } else if dominates(objectives[j], objectives[i], senses) {
                dominated_by_me[j].push(i);
                domination_count[i] += 1;
            }
        }
    }
    let mut fronts = Vec::new();
    let mut current: Vec<usize> = (0..n).filter(|&i| domination_count[i] == 0).collect();
    while !current.is_empty() {
        let mut next = Vec::new();
        for &i in &current {
            for &j in &dominated_by_me[i] {
                domination_count[j] -= 1;
                if domination_count[j] == 0 {
                    next.push(j);
                }
            }
        }
        next.sort_unstable();
        fronts.push(std::mem::replace(&mut current, next));
    }
    fronts
}

/// Crowding distance of each member of `front` (same order): for every objective, the
/// members sorted by that objective get +∞ at both ends and, inside, the gap between their
/// neighbours divided by the objective's range over the front. An objective with zero range
/// adds nothing.
pub fn crowding_distances(front: &[usize], objectives: &[&[f64]], senses: &[Sense]) -> Vec<f64> {
    let n = front.len();
    let mut distance = vec![0.0; n];
    if n <= 2 {
        return vec![f64::INFINITY; n];
    }
    for (m, sense) in senses.iter().enumerate() {
        let value = |k: usize| sense.utility(objectives[front[k]][m]);
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| value(a).total_cmp(&value(b)));
        let (lo, hi) = (value(order[0]), value(order[n - 1]));
        let range = hi - lo;
        if !(range > 0.0 && range.is_finite()) {
            continue;
        }
        distance[order[0]] = f64::INFINITY;
        distance[order[n - 1]] = f64::INFINITY;
        for w in order.windows(3) {
            distance[w[1]] += (value(w[2]) - value(w[0])) / range;
        }
    }
    distance
}

/// Area dominated by `points` and bounded by `reference` (a point worse than all of interest)
/// in a two-objective space with the given senses. Points not strictly better than the
/// reference in both objectives contribute nothing.
pub fn hypervolume_2d(points: &[[f64; 2]], reference: [f64; 2], senses: [Sense; 2]) -> f64 {
    // Work in minimisation coordinates.
    let to_min = |p: [f64; 2]| [-senses[0].utility(p[0]), -senses[1].utility(p[1])];
    let r = to_min(reference);
    let mut pts: Vec<[f64; 2]> = points
        .iter()
        .map(|&p| to_min(p))
        .filter(|p| p[0] < r[0] && p[1] < r[1])
        .collect();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    let mut volume = 0.0;
    let mut lowest = r[1];
    for p in pts {
        if p[1] < lowest {
            volume += (r[0] - p[0]) * (lowest - p[1]);
            lowest = p[1];
        }
    }
    volume
}

#[cfg(test)]
mod tests {
    use super::*;

    const MIN2: [Sense; 2] = [Sense::Minimize, Sense::Minimize];

    #[test]
    fn sorts_fronts_and_handles_ties() {
        let pts: Vec<Vec<f64>> = vec![
            vec![1.0, 5.0],
            vec![2.0, 2.0],
            vec![5.0, 1.0],
            vec![3.0, 3.0],
            vec![2.0, 2.0],
            vec![6.0, 6.0],
        ];
        let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
        let fronts = non_dominated_sort(&refs, &MIN2);
        assert_eq!(fronts, vec![vec![0, 1, 2, 4], vec![3], vec![5]]);
        assert!(!dominates(&[2.0, 2.0], &[2.0, 2.0], &MIN2));
        assert!(dominates(&[2.0, 2.0], &[2.0, 3.0], &MIN2));
        let maxmin = [Sense::Maximize, Sense::Minimize];
        assert!(dominates(&[3.0, 1.0], &[2.0, 1.0], &maxmin));
    }

    #[test]
    fn crowding_is_normalised_with_infinite_extremes() {
        let pts: Vec<Vec<f64>> = vec![vec![0.0, 10.0], vec![1.0, 5.0], vec![3.0, 1.0], vec![4.0, 0.0]];
        let refs: Vec<&[f64]> = pts.iter().map(|p| p.as_slice()).collect();
        let d = crowding_distances(&[0, 1, 2, 3], &refs, &MIN2);
        assert!(d[0].is_infinite() && d[3].is_infinite());
        assert!((d[1] - (3.0 / 4.0 + 9.0 / 10.0)).abs() < 1e-12);
        assert!((d[2] - (3.0 / 4.0 + 5.0 / 10.0)).abs() < 1e-12);
    }

    #[test]
    fn hypervolume_of_simple_sets() {
        let hv = hypervolume_2d(&[[1.0, 2.0], [2.0, 1.0], [3.0, 3.0]], [4.0, 4.0], MIN2);
        // Union of [1,4]x[2,4] and [2,4]x[1,4]: 6 + 6 − 4 = 8.
        assert!((hv - 8.0).abs() < 1e-12);
        let hv = hypervolume_2d(&[[-1.0, 2.0]], [-4.0, 4.0], [Sense::Maximize, Sense::Minimize]);
        assert!((hv - 6.0).abs() < 1e-12);
        assert_eq!(hypervolume_2d(&[[5.0, 0.0]], [4.0, 4.0], MIN2), 0.0);
    }
}
