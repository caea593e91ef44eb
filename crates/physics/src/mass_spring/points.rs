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
        for i in self.free.indices() {
            self.moved_vx[i] = (self.x[i] - self.x_last[i]) / dt;
            self.moved_vy[i] = (self.y[i] - self.y_last[i]) / dt;
        }
    }

    /// The first moving point whose position or velocity is NaN or infinite.
    pub fn first_non_finite(&self) -> Option<usize> {
        self.free.indices().find(|&i| {
            !(self.x[i].is_finite() && self.y[i].is_finite() && self.vx[i].is_finite() && self.vy[i].is_finite())
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
