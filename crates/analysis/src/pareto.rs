//! Pareto fronts of multi-objective runs (thesis §5.1.3.4): the first non-dominated front of a
//! population, its knee (the member closest to the centre of the front's bounding box, each
//! objective scaled by its range over the front) and its specialists (the best in each
//! objective).

/// Whether `a` dominates `b`: no worse in every objective and better in at least one.
/// `minimize[i]` says whether objective i is minimised. Identical points do not dominate each
/// other (the original's NSGA-II counted ties as domination, thesis-code-facts §7.4).
pub fn dominates(a: &[f64], b: &[f64], minimize: &[bool]) -> bool {
    let mut better = false;
    for ((&x, &y), &min) in a.iter().zip(b).zip(minimize) {
        let (x, y) = if min { (-x, -y) } else { (x, y) };
        if x < y {
            return false;
        }
        better |= x > y;
    }
    better
}

/// Indices of the points no other point dominates, in index order; points with a non-finite
/// value are left out.
pub fn first_front(points: &[Vec<f64>], minimize: &[bool]) -> Vec<usize> {
    let finite = |p: &Vec<f64>| p.iter().all(|v| v.is_finite());
    (0..points.len())
        .filter(|&i| finite(&points[i]))
        .filter(|&i| !points.iter().any(|q| finite(q) && dominates(q, &points[i], minimize)))
        .collect()
}

/// The knee of `front` (indices into `points`): the member closest to the centre of the front's
/// bounding box, each objective divided by its range over the front (1 where the range is 0);
/// ties go to the lower index.
pub fn knee(points: &[Vec<f64>], front: &[usize]) -> Option<usize> {
    let first = points.get(*front.first()?)?;
    let objectives = first.len();
    let (mut low, mut high) = (vec![f64::INFINITY; objectives], vec![f64::NEG_INFINITY; objectives]);
    for &i in front {
        for (k, &v) in points[i].iter().enumerate() {
            low[k] = low[k].min(v);
            high[k] = high[k].max(v);
        }
    }
    let distance = |i: usize| -> f64 {
        (0..objectives)
            .map(|k| {
                let range = if high[k] > low[k] { high[k] - low[k] } else { 1.0 };
                let centre = 0.5 * (low[k] + high[k]);
                ((points[i][k] - centre) / range).powi(2)
            })
            .sum()
    };
    front
        .iter()
        .copied()
        .min_by(|&a, &b| distance(a).total_cmp(&distance(b)).then(a.cmp(&b)))
}

/// The specialist of objective `k` in `front`: the best value of that objective; ties go to the
/// lower index.
pub fn specialist(points: &[Vec<f64>], front: &[usize], k: usize, minimize: bool) -> Option<usize> {
    let key = |i: usize| if minimize { points[i][k] } else { -points[i][k] };
    front
        .iter()
        .copied()
        .min_by(|&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (locomotion, minimised; sensing, maximised), the affordance study's objectives.
    const SENSES: [bool; 2] = [true, false];

    fn points() -> Vec<Vec<f64>> {
        vec![
            vec![0.10, 0.20], // 0: front
            vec![0.05, 0.10], // 1: front (best locomotion)
            vec![0.30, 0.90], // 2: front (best sensing)
            vec![0.20, 0.50], // 3: front, the middle
            vec![0.25, 0.40], // 4: dominated by 3
            vec![0.10, 0.20], // 5: the same as 0: not dominated by it
            vec![f64::NAN, 1.0],
        ]
    }

    #[test]
    fn the_front_keeps_the_non_dominated_and_ties() {
        assert!(dominates(&[0.2, 0.5], &[0.25, 0.4], &SENSES));
        assert!(!dominates(&[0.1, 0.2], &[0.1, 0.2], &SENSES));
        assert!(!dominates(&[0.05, 0.1], &[0.1, 0.2], &SENSES));
        assert_eq!(first_front(&points(), &SENSES), vec![0, 1, 2, 3, 5]);
    }

    #[test]
    fn knee_and_specialists() {
        let p = points();
        let front = first_front(&p, &SENSES);
        assert_eq!(specialist(&p, &front, 0, true), Some(1));
        assert_eq!(specialist(&p, &front, 1, false), Some(2));
        // box: locomotion [0.05, 0.30], sensing [0.10, 0.90]; centre (0.175, 0.5): point 3
        assert_eq!(knee(&p, &front), Some(3));
        assert_eq!(knee(&p, &[]), None);
    }
}
