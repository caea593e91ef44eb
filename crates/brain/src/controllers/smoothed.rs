//! Smoothed wrapper (2D-VSR-Sim `SmoothedController`, vsr-model.md §4.6): each voxel's actuation
//! moves towards the inner controller's output by at most `speed·dt` per call, starting from 0, with
//! dt the time since the previous call (the first call measures from t = 0). No parameters of its
//! own.

use crate::Controller;

/// Rate-limits the inner controller's output to `speed` per second.
pub struct SmoothedController {
    inner: Box<dyn Controller>,
    speed: f64,
    last_t: f64,
    target: Vec<f64>,
    current: Vec<f64>,
}

impl SmoothedController {
    /// Wraps `inner` for a body of `voxels` voxels.
    pub fn new(inner: Box<dyn Controller>, speed: f64, voxels: usize) -> Self {
        SmoothedController {
            inner,
            speed,
            last_t: 0.0,
            target: vec![0.0; voxels],
            current: vec![0.0; voxels],
        }
    }
}

impl Controller for SmoothedController {
    fn reset(&mut self) {
        self.inner.reset();
        self.last_t = 0.0;
        self.current.fill(0.0);
    }

    fn control(&mut self, t: f64, readings: &[f64], actuations: &mut [f64]) {
        self.inner.control(t, readings, &mut self.target);
        let max_change = self.speed * (t - self.last_t).max(0.0);
        self.last_t = t;
        for ((a, c), target) in actuations.iter_mut().zip(&mut self.current).zip(&self.target) {
            *c += (target - *c).clamp(-max_change, max_change);
            *a = *c;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ConstantController;

    /// A square wave jumping between −1 and +1 every 10 calls.
    struct Square(u32);
    impl Controller for Square {
        fn reset(&mut self) {
            self.0 = 0;
        }
        fn control(&mut self, _t: f64, _r: &[f64], a: &mut [f64]) {
            self.0 += 1;
            a.fill(if (self.0 / 10) & 1 == 0 { 1.0 } else { -1.0 });
        }
    }

    #[test]
    fn changes_by_at_most_speed_dt_per_step_from_zero() {
        let (speed, dt) = (3.0, 1.0 / 60.0);
        let mut c = SmoothedController::new(Box::new(Square(0)), speed, 2);
        let mut a = [0.0; 2];
        let mut previous = 0.0;
        let mut t = 0.0;
        let mut largest: f64 = 0.0;
        for _ in 0..300 {
            t += dt;
            c.control(t, &[], &mut a);
            let change = (a[0] - previous).abs();
            assert!(change <= speed * dt + 1e-12, "{change}");
            largest = largest.max(change);
            previous = a[0];
        }
        assert!((largest - speed * dt).abs() < 1e-9, "the limit is reached: {largest}");
    }

    #[test]
    fn reaches_a_constant_target_and_stays() {
        let mut c = SmoothedController::new(Box::new(ConstantController { value: 0.5 }), 6.0, 1);
        let mut a = [0.0];
        c.control(1.0 / 60.0, &[], &mut a);
        assert!((a[0] - 0.1).abs() < 1e-12, "first step from 0 by 6/60: {}", a[0]);
        for k in 2..=10 {
            c.control(k as f64 / 60.0, &[], &mut a);
        }
        assert_eq!(a[0], 0.5);
        c.reset();
        c.control(1.0 / 60.0, &[], &mut a);
        assert!((a[0] - 0.1).abs() < 1e-12, "reset starts from 0 again");
    }
}
