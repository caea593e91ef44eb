//! The pendulum swing-up (Gymnasium's `Pendulum-v1`, the classic control benchmark whose PPO
//! results the literature reports): a pole of mass 1 and length 1 under gravity 10, a torque in
//! [−2, 2] per step of 0.05 s, the angular speed clipped to ±8; observation (cos θ, sin θ, θ̇),
//! reward −(θ² + 0.1 θ̇² + 0.001 u²) with θ in [−π, π), 200-step episodes starting at
//! θ ~ U[−π, π], θ̇ ~ U[−1, 1]. An episode's return lies in about [−1,600, 0]; a swung-up,
//! balanced pole earns about −150.

use crate::environment::{Environment, StepError, Transition};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::f64::consts::PI;

/// Steps of an episode.
pub const PENDULUM_STEPS: usize = 200;

/// The pendulum (see the module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Pendulum {
    theta: f64,
    speed: f64,
    t: usize,
}

impl Pendulum {
    fn observation(&self) -> Vec<f64> {
        vec![self.theta.cos(), self.theta.sin(), self.speed]
    }
}

/// θ into [−π, π).
fn normalize(theta: f64) -> f64 {
    (theta + PI).rem_euclid(2.0 * PI) - PI
}

impl Environment for Pendulum {
    fn observation_size(&self) -> usize {
        3
    }

    fn action_size(&self) -> usize {
        1
    }

    fn reset(&mut self, seed: u64) -> Vec<f64> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        self.theta = rng.random_range(-PI..PI);
        self.speed = rng.random_range(-1.0..1.0);
        self.t = 0;
        self.observation()
    }

    fn step(&mut self, action: &[f64]) -> Result<Transition, StepError> {
        let (g, m, l, dt) = (10.0, 1.0, 1.0, 0.05);
        let u = action[0].clamp(-2.0, 2.0);
        let cost = normalize(self.theta).powi(2) + 0.1 * self.speed.powi(2) + 0.001 * u * u;
        let speed = self.speed + (3.0 * g / (2.0 * l) * self.theta.sin() + 3.0 / (m * l * l) * u) * dt;
        self.speed = speed.clamp(-8.0, 8.0);
        self.theta += self.speed * dt;
        self.t += 1;
        Ok(Transition {
            observation: self.observation(),
            reward: -cost,
            done: self.t == PENDULUM_STEPS,
            truncated: self.t == PENDULUM_STEPS,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pendulum_falls_and_costs_what_gymnasium_charges() {
        let mut p = Pendulum::default();
        let first = p.reset(3);
        assert!((first[0].powi(2) + first[1].powi(2) - 1.0).abs() < 1e-12);
        // hanging down at rest with no torque: cost π², and it stays down
        p.theta = PI;
        p.speed = 0.0;
        let step = p.step(&[0.0]).unwrap();
        assert!((step.reward + PI * PI).abs() < 1e-12, "{}", step.reward);
        // upright at rest: free, and an unbalanced push makes it fall faster and faster
        p.theta = 0.01;
        p.speed = 0.0;
        let mut speeds = Vec::new();
        for _ in 0..5 {
            p.step(&[0.0]).unwrap();
            speeds.push(p.speed);
        }
        assert!(speeds.windows(2).all(|w| w[1] > w[0] && w[0] > 0.0), "{speeds:?}");
        // the torque is clipped to ±2 and the speed to ±8
        p.theta = 0.0;
        p.speed = 7.99;
        let big = p.step(&[100.0]).unwrap();
        assert!((p.speed - 8.0).abs() < 1e-12 && (big.reward + 0.1 * 7.99f64.powi(2) + 0.004).abs() < 1e-12);
        p.reset(0);
        let done: Vec<bool> = (0..PENDULUM_STEPS).map(|_| p.step(&[0.0]).unwrap().done).collect();
        assert!(done[..PENDULUM_STEPS - 1].iter().all(|d| !d) && done[PENDULUM_STEPS - 1]);
    }
}
