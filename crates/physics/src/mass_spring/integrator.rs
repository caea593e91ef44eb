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
        for r in points.free.ranges() {
            add(&mut points.x[r.clone()], &self.ax[r.clone()]);
            add(&mut points.y[r.clone()], &self.ay[r.clone()]);
            add(&mut points.vx[r.clone()], &self.avx[r.clone()]);
            add(&mut points.vy[r.clone()], &self.avy[r]);
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
        for r in points.stage[k].ranges() {
            // the increments of velocity: force / mass × dt, with a multiplication by the
            // reciprocal where that is the same float (masses that are powers of two)
            let (fx, fy) = (&mut self.fx[r.clone()], &mut self.fy[r.clone()]);
            match points.masses_are_powers_of_two {
                true => {
                    let inverse = &points.inverse_mass[r.clone()];
                    for ((fx, fy), &inverse) in fx.iter_mut().zip(fy.iter_mut()).zip(inverse) {
                        (*fx, *fy) = (*fx * inverse * dt, *fy * inverse * dt);
                    }
                }
                false => {
                    let mass = &points.mass[r.clone()];
                    for ((fx, fy), &mass) in fx.iter_mut().zip(fy.iter_mut()).zip(mass) {
                        (*fx, *fy) = (*fx / mass * dt, *fy / mass * dt);
                    }
                }
            }
            let n = r.len();
            let (kvx, kvy) = (&self.fx[r.clone()], &self.fy[r.clone()]);
            let (x, y) = (&points.x[r.clone()], &points.y[r.clone()]);
            let (vx, vy) = (&points.vx[r.clone()], &points.vy[r.clone()]);
            let (ax, ay) = (&mut self.ax[r.clone()], &mut self.ay[r.clone()]);
            let (avx, avy) = (&mut self.avx[r.clone()], &mut self.avy[r.clone()]);
            let (sx, sy) = (&mut self.sx[r.clone()], &mut self.sy[r.clone()]);
            let (svx, svy) = (&mut self.svx[r.clone()], &mut self.svy[r]);
            for j in 0..n {
                let (kx, ky) = (svx[j] * dt, svy[j] * dt);
                ax[j] += weight * kx;
                ay[j] += weight * ky;
                avx[j] += weight * kvx[j];
                avy[j] += weight * kvy[j];
                sx[j] = x[j] + next * kx;
                sy[j] = y[j] + next * ky;
                svx[j] = vx[j] + next * kvx[j];
                svy[j] = vy[j] + next * kvy[j];
            }
        }
    }
}

/// `to[i] += by[i]` for every i.
fn add(to: &mut [f64], by: &[f64]) {
    for (t, &b) in to.iter_mut().zip(by) {
        *t += b;
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
            tracked_length: vec![],
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
