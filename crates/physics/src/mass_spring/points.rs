//! The point masses, stored as structure of arrays.

use super::runs::Runs;

/// Positions, velocities and per-point constants, one entry per point.
#[derive(Debug, Clone)]
pub(crate) struct Points {
    pub x: Vec<f64>,
    pub y: Vec<f64>,
    /// Integrated velocities (the state of the integrator).
    pub vx: Vec<f64>,
    pub vy: Vec<f64>,
    pub mass: Vec<f64>,
    /// `1 / mass` of every point, and whether every mass is a power of two: then `f / m` and
    /// `f * (1 / m)` are the same float (both the rounding of one exact value), and the
    /// integrator multiplies instead of dividing (EvoGym's masses are all 1).
    pub inverse_mass: Vec<f64>,
    pub masses_are_powers_of_two: bool,
    pub fixed: Vec<bool>,
    /// The points that move.
    pub free: Runs,
    /// The points each RK4 stage moves: the free ones and the fixed ones whose drift inside a
    /// substep reaches a free point (see `stage_points`); the free points unless set otherwise.
    pub stage: [Runs; 4],
    /// Positions at the start of the current substep.
    pub x_last: Vec<f64>,
    pub y_last: Vec<f64>,
    /// Velocities at the start of the current substep (to undo a substep that exploded).
    pub vx_last: Vec<f64>,
    pub vy_last: Vec<f64>,
    /// Displacement over the last substep divided by dt, projection included: what contacts damp.
    pub moved_vx: Vec<f64>,
    pub moved_vy: Vec<f64>,
    /// Contact forces of the current substep, held constant through its integrator stages.
    pub contact_fx: Vec<f64>,
    pub contact_fy: Vec<f64>,
}

impl Points {
    /// Points at rest positions with velocities `v`; `fixed` points never move.
    pub fn new(pos: &[(f64, f64)], vel: &[(f64, f64)], mass: Vec<f64>, fixed: Vec<bool>) -> Self {
        let n = pos.len();
        let x: Vec<f64> = pos.iter().map(|p| p.0).collect();
        let y: Vec<f64> = pos.iter().map(|p| p.1).collect();
        // A fixed point is at rest whatever velocity it was given.
        let at_rest = |i: usize, v: f64| if fixed[i] { 0.0 } else { v };
        let vx: Vec<f64> = vel.iter().enumerate().map(|(i, v)| at_rest(i, v.0)).collect();
        let vy: Vec<f64> = vel.iter().enumerate().map(|(i, v)| at_rest(i, v.1)).collect();
        let free = Runs::where_(n, |i| !fixed[i]);
        let inverse_mass = mass.iter().map(|m| 1.0 / m).collect();
        let masses_are_powers_of_two = mass.iter().all(|&m| is_power_of_two(m));
        Self {
            x_last: x.clone(),
            y_last: y.clone(),
            vx_last: vx.clone(),
            vy_last: vy.clone(),
            moved_vx: vx.clone(),
            moved_vy: vy.clone(),
            x,
            y,
            vx,
            vy,
            mass,
            inverse_mass,
            masses_are_powers_of_two,
            fixed,
            stage: std::array::from_fn(|_| free.clone()),
            free,
            contact_fx: vec![0.0; n],
            contact_fy: vec![0.0; n],
        }
    }

    /// Remembers the state at the start of a substep.
    pub fn remember(&mut self) {
        self.x_last.copy_from_slice(&self.x);
        self.y_last.copy_from_slice(&self.y);
        self.vx_last.copy_from_slice(&self.vx);
        self.vy_last.copy_from_slice(&self.vy);
    }

    /// Puts back the state remembered at the start of the substep.
    pub fn restore(&mut self) {
        self.x.copy_from_slice(&self.x_last);
        self.y.copy_from_slice(&self.y_last);
        self.vx.copy_from_slice(&self.vx_last);
        self.vy.copy_from_slice(&self.vy_last);
    }

    /// Velocities from the displacement over the substep that just ended.
    pub fn update_moved_velocity(&mut self, dt: f64) {
        for r in self.free.ranges() {
            let (x, x_last, moved_vx) = (
                &self.x[r.clone()],
                &self.x_last[r.clone()],
                &mut self.moved_vx[r.clone()],
            );
            for ((v, &now), &last) in moved_vx.iter_mut().zip(x).zip(x_last) {
                *v = (now - last) / dt;
            }
            let (y, y_last, moved_vy) = (&self.y[r.clone()], &self.y_last[r.clone()], &mut self.moved_vy[r]);
            for ((v, &now), &last) in moved_vy.iter_mut().zip(y).zip(y_last) {
                *v = (now - last) / dt;
            }
        }
    }

    /// The first moving point whose position or velocity is NaN or infinite.
    pub fn first_non_finite(&self) -> Option<usize> {
        self.free.indices().find(|&i| {
            !(self.x[i].is_finite() && self.y[i].is_finite() && self.vx[i].is_finite() && self.vy[i].is_finite())
        })
    }
}

/// Whether `m` is a power of two whose reciprocal is a normal float, so that dividing by `m` and
/// multiplying by `1 / m` round the same exact value.
fn is_power_of_two(m: f64) -> bool {
    const MANTISSA: u64 = (1 << 52) - 1;
    m > 0.0 && m.is_normal() && m.to_bits() & MANTISSA == 0 && (1.0 / m).is_normal()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dividing_by_a_power_of_two_is_multiplying_by_its_reciprocal() {
        for m in [1.0, 2.0, 0.5, 1024.0, 2f64.powi(-1000)] {
            assert!(is_power_of_two(m), "{m}");
        }
        for m in [
            3.0,
            0.1,
            0.0,
            -2.0,
            f64::INFINITY,
            f64::NAN,
            2f64.powi(1023),
            f64::MIN_POSITIVE / 2.0,
        ] {
            assert!(!is_power_of_two(m), "{m}");
        }
        // the claim the integrator rests on, over awkward values (subnormal results included)
        let values = [1e-310, 3.7, -1e300, 0.1 + 0.2, f64::MIN_POSITIVE, 123456.789e-20];
        for m in [1.0, 2.0, 0.25, 2f64.powi(40), 2f64.powi(-40)] {
            for &f in &values {
                assert_eq!((f / m).to_bits(), (f * (1.0 / m)).to_bits(), "{f} / {m}");
            }
        }
        // and why other masses keep the division: 1 / 3 is rounded (5 / 3 ≠ 5 × (1 / 3))
        assert_ne!((5.0f64 / 3.0).to_bits(), (5.0f64 * (1.0 / 3.0)).to_bits());
    }

    #[test]
    fn restore_undoes_changes_since_remember_and_moved_velocity_is_a_difference_quotient() {
        let mut p = Points::new(
            &[(0.0, 0.0), (1.0, 0.0)],
            &[(0.0, 0.0); 2],
            vec![1.0; 2],
            vec![false, true],
        );
        p.remember();
        p.x[0] = 0.5;
        p.update_moved_velocity(0.25);
        assert_eq!(p.moved_vx[0], 2.0);
        p.vx[0] = f64::NAN;
        assert_eq!(p.first_non_finite(), Some(0));
        p.restore();
        assert_eq!((p.x[0], p.vx[0]), (0.0, 0.0));
        assert_eq!(p.first_non_finite(), None);
        assert_eq!(p.free.indices().collect::<Vec<_>>(), vec![0]);
    }
}
