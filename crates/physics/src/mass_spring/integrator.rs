//! Classical fourth-order Runge–Kutta over positions and velocities, as EvoGym integrates. The
//! stages move every point of `points.stage` (fixed ones near free ones included, as EvoGym lets
//! them drift inside a substep); only free points keep their increment.

use super::forces::{total_forces, Stage};
use super::points::Points;
use super::settings::MassSpringSettings;
use super::springs::Springs;

/// Stage state, forces and the weighted sum of increments, preallocated.
#[derive(Debug, Clone)]
pub(crate) struct Rk4 {
    sx: Vec<f64>,
    sy: Vec<f64>,
    svx: Vec<f64>,
    svy: Vec<f64>,
    fx: Vec<f64>,
    fy: Vec<f64>,
    ax: Vec<f64>,
    ay: Vec<f64>,
    avx: Vec<f64>,
    avy: Vec<f64>,
}

/// For each stage: the fraction of its increment that gives the next stage's state, and its
/// weight in the final sum.
const STAGES: [(f64, f64); 4] = [(0.5, 1.0 / 6.0), (0.5, 2.0 / 6.0), (1.0, 2.0 / 6.0), (0.0, 1.0 / 6.0)];

impl Rk4 {
    /// Buffers for `n` points.
    pub fn new(n: usize) -> Self {
        let z = vec![0.0; n];
        Self {
            sx: z.clone(),
            sy: z.clone(),
            svx: z.clone(),
            svy: z.clone(),
            fx: z.clone(),
            fy: z.clone(),
            ax: z.clone(),
            ay: z.clone(),
            avx: z.clone(),
            avy: z,
        }
    }

    /// Advances every free point by one substep of `set.dt`.
    pub fn step(&mut self, points: &mut Points, springs: &Springs, set: &MassSpringSettings) {
        self.sx.copy_from_slice(&points.x);
        self.sy.copy_from_slice(&points.y);
        self.svx.copy_from_slice(&points.vx);
        self.svy.copy_from_slice(&points.vy);
        for i in points.stage[0].indices() {
            (self.ax[i], self.ay[i], self.avx[i], self.avy[i]) = (0.0, 0.0, 0.0, 0.0);
        }
        for (k, (next, weight)) in STAGES.into_iter().enumerate() {
            self.stage(k, points, springs, set, next, weight);
        }
        for i in points.free.indices() {
            points.x[i] += self.ax[i];
            points.y[i] += self.ay[i];
            points.vx[i] += self.avx[i];
            points.vy[i] += self.avy[i];
        }
    }

    /// Evaluates stage `k`, adds its weighted increment and prepares the next stage's state (of the
    /// points stage `k` moves: all the next stage reads).
    fn stage(
        &mut self,
        k: usize,
        points: &Points,
        springs: &Springs,
        set: &MassSpringSettings,
        next: f64,
        weight: f64,
    ) {
        let s = Stage {
            x: &self.sx,
            y: &self.sy,
            vx: &self.svx,
            vy: &self.svy,
        };
        total_forces(&s, k, points, springs, set, &mut self.fx, &mut self.fy);
        let dt = set.dt;
        for i in points.stage[k].indices() {
            let (kx, ky) = (self.svx[i] * dt, self.svy[i] * dt);
            let (kvx, kvy) = (self.fx[i] / points.mass[i] * dt, self.fy[i] / points.mass[i] * dt);
            self.ax[i] += weight * kx;
            self.ay[i] += weight * ky;
            self.avx[i] += weight * kvx;
            self.avy[i] += weight * kvy;
            self.sx[i] = points.x[i] + next * kx;
            self.sy[i] = points.y[i] + next * ky;
            self.svx[i] = points.vx[i] + next * kvx;
            self.svy[i] = points.vy[i] + next * kvy;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::runs::Runs;
    use super::*;

    /// One free point under gravity only: RK4 is exact for constant acceleration.
    #[test]
    fn free_fall_is_integrated_exactly_and_fixed_points_stay() {
        let mut p = Points::new(
            &[(0.0, 1.0), (5.0, 5.0)],
            &[(2.0, 0.0), (0.0, 0.0)],
            vec![1.0, 1.0],
            vec![false, true],
        );
        let springs = Springs {
            a: vec![],
            b: vec![],
            stiffness: vec![],
            rest: vec![],
            initial: vec![],
            goal: vec![],
            band: vec![],
            active: Runs::default(),
            stages: Default::default(),
        };
        let set = MassSpringSettings {
            drag: 0.0,
            ground: None,
            ..MassSpringSettings::evogym()
        };
        let mut rk = Rk4::new(2);
        for _ in 0..1000 {
            rk.step(&mut p, &springs, &set);
        }
        let t = 0.1;
        assert!((p.y[0] - (1.0 - 0.5 * 110.0 * t * t)).abs() < 1e-9);
        assert!((p.vy[0] + 110.0 * t).abs() < 1e-9);
        assert!((p.x[0] - 2.0 * t).abs() < 1e-12);
        assert_eq!((p.x[1], p.y[1], p.vy[1]), (5.0, 5.0, 0.0));
    }
}
