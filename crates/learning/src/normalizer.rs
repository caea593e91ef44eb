//! Observation normalisation as the PPO reference (Stable Baselines' `VecNormalize`): a running
//! mean and variance of every observation value, observations shifted and scaled by them and
//! clipped to ±10.

/// Running mean and variance of each value of a vector (Chan et al.'s parallel update).
#[derive(Debug, Clone, PartialEq)]
pub struct Normalizer {
    mean: Vec<f64>,
    var: Vec<f64>,
    count: f64,
}

/// Observations are clipped to ± this many standard deviations.
const CLIP: f64 = 10.0;
/// Added to the variance before its root.
const EPSILON: f64 = 1e-8;

impl Normalizer {
    /// Statistics of vectors of `n` values, starting from mean 0, variance 1 and a count of
    /// 1e-4 (the reference's start).
    pub fn new(n: usize) -> Normalizer {
        Normalizer {
            mean: vec![0.0; n],
            var: vec![1.0; n],
            count: 1e-4,
        }
    }

    /// Adds a batch of vectors to the statistics.
    pub fn update(&mut self, batch: &[Vec<f64>]) {
        if batch.is_empty() {
            return;
        }
        let n = batch.len() as f64;
        for i in 0..self.mean.len() {
            let mean = batch.iter().map(|x| x[i]).sum::<f64>() / n;
            let var = batch.iter().map(|x| (x[i] - mean).powi(2)).sum::<f64>() / n;
            let delta = mean - self.mean[i];
            let total = self.count + n;
            let m2 = self.var[i] * self.count + var * n + delta * delta * self.count * n / total;
            self.mean[i] += delta * n / total;
            self.var[i] = m2 / total;
        }
        self.count += n;
    }

    /// The running mean of each value.
    pub fn mean(&self) -> &[f64] {
        &self.mean
    }

    /// The running variance of each value.
    pub fn var(&self) -> &[f64] {
        &self.var
    }

    /// Values per vector.
    pub fn len(&self) -> usize {
        self.mean.len()
    }

    /// Whether the vectors are empty.
    pub fn is_empty(&self) -> bool {
        self.mean.is_empty()
    }

    /// `x` shifted and scaled by the statistics, clipped to ±10.
    pub fn normalize(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .enumerate()
            .map(|(i, &v)| ((v - self.mean[i]) / (self.var[i] + EPSILON).sqrt()).clamp(-CLIP, CLIP))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn batches_give_the_mean_and_variance_of_everything_seen() {
        let data: Vec<Vec<f64>> = (0..100).map(|i| vec![i as f64, 5.0 - 0.5 * i as f64]).collect();
        let mut n = Normalizer::new(2);
        n.update(&data[..30]);
        n.update(&data[30..]);
        let mean0 = 49.5;
        let var0 = (0..100).map(|i| (i as f64 - mean0).powi(2)).sum::<f64>() / 100.0;
        assert!(
            (n.mean[0] - mean0).abs() < 1e-3 && (n.var[0] - var0).abs() / var0 < 1e-3,
            "{n:?}"
        );
        assert!((n.var[1] - 0.25 * var0).abs() / var0 < 1e-3);
        let z = n.normalize(&[mean0 + var0.sqrt(), 1e9]);
        assert!((z[0] - 1.0).abs() < 1e-3 && z[1] == CLIP, "{z:?}");
    }
}
