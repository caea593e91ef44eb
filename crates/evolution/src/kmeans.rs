//! k-means clustering with k-means++ seeding (Arthur & Vassilvitskii 2007), for the speciated
//! evolver.
//!
//! Seeding draws from the caller's generator, so clustering is reproducible from the run seed
//! (the original used Apache Commons Math with an unseeded generator; thesis-code-facts §2.4).
//! Lloyd iterations run until no assignment changes or `max_iterations`. An empty cluster takes
//! the point farthest from its centroid in the cluster with the largest sum of squared errors
//! (a deterministic version of Commons Math's "largest variance" strategy). Ties go to the
//! lowest index. If the points have fewer than `k` distinct values, fewer clusters are made.

use crate::rng::SeededRng;

/// Squared Euclidean distance.
pub(crate) fn squared_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| (x - y) * (x - y)).sum()
}

fn nearest(point: &[f64], centroids: &[Vec<f64>]) -> (usize, f64) {
    let mut best = (0, f64::INFINITY);
    for (c, centroid) in centroids.iter().enumerate() {
        let d = squared_distance(point, centroid);
        if d < best.1 {
            best = (c, d);
        }
    }
    best
}

/// Clusters `points`; returns the cluster index of every point and the centroids. Every
/// returned cluster is non-empty.
pub(crate) fn kmeans(
    points: &[Vec<f64>],
    k: usize,
    max_iterations: usize,
    rng: &mut SeededRng,
) -> (Vec<usize>, Vec<Vec<f64>>) {
    assert!(!points.is_empty() && k > 0);
    let mut centroids = plus_plus_seeds(points, k, rng);
    let mut assignment = vec![usize::MAX; points.len()];
    for _ in 0..max_iterations.max(1) {
        let mut changed = false;
        for (a, p) in assignment.iter_mut().zip(points) {
            let (c, _) = nearest(p, &centroids);
            if *a != c {
                *a = c;
                changed = true;
            }
        }
        fill_empty_clusters(points, &mut assignment, &centroids);
        let previous = centroids.clone();
        update_centroids(points, &assignment, &mut centroids);
        if !changed && previous == centroids {
            break;
        }
    }
    (assignment, centroids)
}

fn plus_plus_seeds(points: &[Vec<f64>], k: usize, rng: &mut SeededRng) -> Vec<Vec<f64>> {
    let mut centroids = vec![points[rng.below(points.len())].clone()];
    let mut d2: Vec<f64> = points.iter().map(|p| squared_distance(p, &centroids[0])).collect();
    while centroids.len() < k {
        let total: f64 = d2.iter().sum();
        if total <= 0.0 {
            break; // every point coincides with a centroid already
        }
        let mut target = rng.uniform() * total;
        let mut chosen = d2.iter().rposition(|&d| d > 0.0).expect("total > 0");
        for (i, &d) in d2.iter().enumerate() {
            if d > 0.0 && target < d {
                chosen = i;
                break;
            }
            target -= d;
        }
        centroids.push(points[chosen].clone());
        for (d, p) in d2.iter_mut().zip(points) {
            *d = d.min(squared_distance(p, &points[chosen]));
        }
    }
    centroids
}

fn fill_empty_clusters(points: &[Vec<f64>], assignment: &mut [usize], centroids: &[Vec<f64>]) {
    let k = centroids.len();
    loop {
        let mut sizes = vec![0usize; k];
        let mut sse = vec![0.0; k];
        for (p, &a) in points.iter().zip(assignment.iter()) {
            sizes[a] += 1;
            sse[a] += squared_distance(p, &centroids[a]);
        }
        let Some(empty) = sizes.iter().position(|&s| s == 0) else {
            return;
        };
        // The donor must keep at least one point.
        let donor = (0..k)
            .filter(|&c| sizes[c] > 1)
            .max_by(|&a, &b| sse[a].total_cmp(&sse[b]).then(b.cmp(&a)));
        let Some(donor) = donor else {
            return;
        };
        let farthest = (0..points.len())
            .filter(|&i| assignment[i] == donor)
            .max_by(|&a, &b| {
                squared_distance(&points[a], &centroids[donor])
                    .total_cmp(&squared_distance(&points[b], &centroids[donor]))
                    .then(b.cmp(&a))
            })
            .expect("donor is non-empty");
        assignment[farthest] = empty;
    }
}

fn update_centroids(points: &[Vec<f64>], assignment: &[usize], centroids: &mut [Vec<f64>]) {
    let dim = points[0].len();
    let mut sums = vec![vec![0.0; dim]; centroids.len()];
    let mut counts = vec![0usize; centroids.len()];
    for (p, &a) in points.iter().zip(assignment) {
        counts[a] += 1;
        for (s, x) in sums[a].iter_mut().zip(p) {
            *s += x;
        }
    }
    for ((centroid, sum), count) in centroids.iter_mut().zip(sums).zip(counts) {
        if count > 0 {
            *centroid = sum.into_iter().map(|s| s / count as f64).collect();
        }
    }
}

/// Min–max normalises each dimension over the points to [0, 1]; a constant dimension becomes 0.
pub(crate) fn normalise(points: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let dim = points.first().map_or(0, Vec::len);
    let mut lo = vec![f64::INFINITY; dim];
    let mut hi = vec![f64::NEG_INFINITY; dim];
    for p in points {
        for j in 0..dim {
            lo[j] = lo[j].min(p[j]);
            hi[j] = hi[j].max(p[j]);
        }
    }
    points
        .iter()
        .map(|p| {
            (0..dim)
                .map(|j| {
                    let range = hi[j] - lo[j];
                    if range > 0.0 && range.is_finite() {
                        (p[j] - lo[j]) / range
                    } else {
                        0.0
                    }
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Stream;

    #[test]
    fn separates_well_separated_blobs() {
        let mut rng = SeededRng::derive(2, 0, 0, Stream::Speciation);
        let centres = [[0.0, 0.0], [10.0, 0.0], [0.0, 10.0], [10.0, 10.0]];
        let points: Vec<Vec<f64>> = (0..200)
            .map(|i| {
                let c = centres[i % 4];
                vec![c[0] + 0.5 * rng.normal(), c[1] + 0.5 * rng.normal()]
            })
            .collect();
        let (assignment, centroids) = kmeans(&points, 4, 200, &mut rng);
        assert_eq!(centroids.len(), 4);
        for blob in 0..4 {
            let label = assignment[blob];
            assert!((blob..200).step_by(4).all(|i| assignment[i] == label));
        }
    }

    #[test]
    fn duplicates_give_fewer_clusters_and_none_empty() {
        let mut rng = SeededRng::derive(2, 0, 1, Stream::Speciation);
        let points = vec![vec![1.0], vec![1.0], vec![2.0], vec![2.0], vec![1.0]];
        let (assignment, centroids) = kmeans(&points, 10, 200, &mut rng);
        assert_eq!(centroids.len(), 2);
        assert_eq!(assignment[0], assignment[1]);
        assert_ne!(assignment[0], assignment[2]);
        let normalised = normalise(&[vec![1.0, 5.0], vec![3.0, 5.0]]);
        assert_eq!(normalised, vec![vec![0.0, 0.0], vec![1.0, 0.0]]);
    }
}
