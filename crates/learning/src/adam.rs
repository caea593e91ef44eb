//! Adam (Kingma & Ba 2015) over a flat parameter vector, with the global gradient-norm clipping
//! PPO implementations apply before each step.

/// Adam's moments and settings for one parameter vector.
#[derive(Debug, Clone, PartialEq)]
pub struct Adam {
    /// First-moment decay (0.9).
    pub beta1: f64,
    /// Second-moment decay (0.999).
    pub beta2: f64,
    /// Added to the root of the second moment (1e-5, as the EvoGym examples' PPO).
    pub epsilon: f64,
    m: Vec<f64>,
    v: Vec<f64>,
    steps: i32,
}

impl Adam {
    /// Adam for `n` parameters, with PyTorch's defaults but ε = 1e-5.
    pub fn new(n: usize) -> Adam {
        Adam {
            beta1: 0.9,
            beta2: 0.999,
            epsilon: 1e-5,
            m: vec![0.0; n],
            v: vec![0.0; n],
            steps: 0,
        }
    }

    /// One step of size `learning_rate` along `gradient` (of a loss to minimise), after scaling
    /// the gradient down to norm `max_norm` when it is longer. Returns the norm before clipping.
    pub fn step(&mut self, parameters: &mut [f64], gradient: &[f64], learning_rate: f64, max_norm: f64) -> f64 {
        assert_eq!(parameters.len(), self.m.len(), "one moment per parameter");
        assert_eq!(gradient.len(), self.m.len(), "one gradient per parameter");
        let norm = gradient.iter().map(|g| g * g).sum::<f64>().sqrt();
        let scale = if norm > max_norm && norm > 0.0 {
            max_norm / norm
        } else {
            1.0
        };
        self.steps = self.steps.saturating_add(1);
        let c1 = 1.0 - self.beta1.powi(self.steps);
        let c2 = 1.0 - self.beta2.powi(self.steps);
        for i in 0..parameters.len() {
            let g = gradient[i] * scale;
            self.m[i] = self.beta1 * self.m[i] + (1.0 - self.beta1) * g;
            self.v[i] = self.beta2 * self.v[i] + (1.0 - self.beta2) * g * g;
            let m_hat = self.m[i] / c1;
            let v_hat = self.v[i] / c2;
            parameters[i] -= learning_rate * m_hat / (v_hat.sqrt() + self.epsilon);
        }
        norm
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn it_walks_down_a_quadratic_and_clips_long_gradients() {
        // f(x) = Σ (x_i − 3)², from 0
        let mut x = vec![0.0; 3];
        let mut adam = Adam::new(3);
        for _ in 0..2000 {
            let g: Vec<f64> = x.iter().map(|v| 2.0 * (v - 3.0)).collect();
            adam.step(&mut x, &g, 0.05, f64::INFINITY);
        }
        assert!(x.iter().all(|v| (v - 3.0).abs() < 1e-3), "{x:?}");
        // the first step of Adam moves each parameter by about the learning rate whatever the
        // gradient's size; clipping changes the direction only through the ratio of components
        let mut y = vec![0.0, 0.0];
        let norm = Adam::new(2).step(&mut y, &[30.0, 40.0], 0.1, 0.5);
        assert_eq!(norm, 50.0);
        assert!((y[0] + 0.1).abs() < 1e-3 && (y[1] + 0.1).abs() < 1e-3, "{y:?}");
    }
}
