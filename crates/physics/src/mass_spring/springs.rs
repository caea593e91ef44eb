//! Springs: Hooke forces along the line between two points, with rest lengths that track a goal.

use super::quad_geometry::norm;
use super::runs::Runs;

/// Spring data, one entry per spring.
#[derive(Debug, Clone)]
pub(crate) struct Springs {
    pub a: Vec<u32>,
    pub b: Vec<u32>,
    pub stiffness: Vec<f64>,
    /// Rest length used by the force in the current substep.
    pub rest: Vec<f64>,
    /// Rest length given at build time: the reference of goals and bands.
    pub initial: Vec<f64>,
    /// Length the rest length tracks (initial length × actuation).
    pub goal: Vec<f64>,
    /// Loose band: lengths are pushed back into `initial × [1 - band, 1 + band]`.
    pub band: Vec<f64>,
    /// Springs with an end that moves in the first RK4 stage; the others never matter.
    pub active: Runs,
    /// The springs each RK4 stage needs: those with an end among the stage's points.
    pub stages: [Runs; 4],
    /// Length of each active spring when its rest length last tracked its goal: the first RK4
    /// stage reads the same positions, so it takes these instead of a second square root each.
    pub tracked_length: Vec<f64>,
}

impl Springs {
    /// The springs with a free end (the last RK4 stage's set): the only ones whose projection
    /// moves anything.
    pub fn touching_free(&self) -> &Runs {
        &self.stages[3]
    }

    /// Sets every active spring's rest length to its current length plus `rate` × (goal − current
    /// length), EvoGym's rule before each substep, and keeps those lengths in `tracked_length`.
    pub fn track_goals(&mut self, x: &[f64], y: &[f64], rate: f64) {
        for r in self.active.ranges() {
            let ends = self.a[r.clone()].iter().zip(&self.b[r.clone()]);
            let lengths = self.tracked_length[r.clone()].iter_mut();
            for (((&a, &b), (rest, &goal)), tracked) in ends
                .zip(self.rest[r.clone()].iter_mut().zip(&self.goal[r]))
                .zip(lengths)
            {
                let len = length(x, y, a as usize, b as usize);
                *tracked = len;
                *rest = len + (goal - len) * rate;
            }
        }
    }

    /// Adds the force of every spring in `which` to `fx`, `fy` for the positions `x`, `y`. A
    /// spring of zero length has no direction and pushes nothing.
    pub fn add_forces(&self, which: &Runs, x: &[f64], y: &[f64], fx: &mut [f64], fy: &mut [f64]) {
        self.accumulate::<false>(which, x, y, fx, fy);
    }

    /// [`Springs::add_forces`] for positions at which [`Springs::track_goals`] just ran (the first
    /// RK4 stage): the lengths come from `tracked_length`, the same bits without the square roots.
    /// Every spring of `which` must be active.
    pub fn add_forces_at_tracked(&self, which: &Runs, x: &[f64], y: &[f64], fx: &mut [f64], fy: &mut [f64]) {
        self.accumulate::<true>(which, x, y, fx, fy);
    }

    fn accumulate<const TRACKED: bool>(&self, which: &Runs, x: &[f64], y: &[f64], fx: &mut [f64], fy: &mut [f64]) {
        for r in which.ranges() {
            let ends = self.a[r.clone()].iter().zip(&self.b[r.clone()]);
            let constants = self.rest[r.clone()].iter().zip(&self.stiffness[r.clone()]);
            for (((&a, &b), (&rest, &stiffness)), &tracked) in ends.zip(constants).zip(&self.tracked_length[r]) {
                let (a, b) = (a as usize, b as usize);
                let (dx, dy) = (x[a] - x[b], y[a] - y[b]);
                let len = if TRACKED { tracked } else { norm(dx, dy) };
                if len == 0.0 {
                    continue;
                }
                let k = (len - rest) * stiffness / len;
                fx[a] -= dx * k;
                fy[a] -= dy * k;
                fx[b] += dx * k;
                fy[b] += dy * k;
            }
        }
    }
}

/// Distance between points `a` and `b`.
pub(crate) fn length(x: &[f64], y: &[f64], a: usize, b: usize) -> f64 {
    norm(x[a] - x[b], y[a] - y[b])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(rest: f64, goal: f64) -> Springs {
        Springs {
            a: vec![0],
            b: vec![1],
            stiffness: vec![10.0],
            rest: vec![rest],
            initial: vec![rest],
            goal: vec![goal],
            band: vec![0.25],
            active: Runs::where_(1, |_| true),
            stages: std::array::from_fn(|_| Runs::where_(1, |_| true)),
            tracked_length: vec![0.0],
        }
    }

    #[test]
    fn a_stretched_spring_pulls_its_ends_together_with_k_times_stretch() {
        let s = one(1.0, 1.0);
        let (x, y) = ([0.0, 0.6], [0.0, 0.8]); // length 1 → stretch 0 → no force
        let (mut fx, mut fy) = ([0.0; 2], [0.0; 2]);
        s.add_forces(&s.active, &x, &y, &mut fx, &mut fy);
        assert!(fx.iter().chain(&fy).all(|f| f.abs() < 1e-12));
        let (x, y) = ([0.0, 1.2], [0.0, 1.6]); // length 2 → force 10 toward each other
        s.add_forces(&s.active, &x, &y, &mut fx, &mut fy);
        assert!((fx[0] - 6.0).abs() < 1e-12 && (fy[0] - 8.0).abs() < 1e-12);
        assert!((fx[1] + 6.0).abs() < 1e-12 && (fy[1] + 8.0).abs() < 1e-12);
    }

    #[test]
    fn tracking_moves_the_rest_length_a_fraction_of_the_way_from_the_current_length() {
        let mut s = one(1.0, 1.5);
        // Current length 2 (not the old rest length 1): 2 + 0.1 * (1.5 - 2) = 1.95.
        s.track_goals(&[0.0, 2.0], &[0.0, 0.0], 0.1);
        assert!((s.rest[0] - 1.95).abs() < 1e-12);
    }

    #[test]
    fn forces_at_the_tracked_positions_take_the_tracked_lengths_bit_for_bit() {
        let mut s = one(1.0, 1.3);
        let (x, y) = ([0.1, 1.37], [-0.2, 0.93]);
        s.track_goals(&x, &y, 0.1);
        assert_eq!(s.tracked_length[0].to_bits(), length(&x, &y, 0, 1).to_bits());
        let (mut fx, mut fy) = ([0.0; 2], [0.0; 2]);
        let (mut tx, mut ty) = ([0.0; 2], [0.0; 2]);
        s.add_forces(&s.active, &x, &y, &mut fx, &mut fy);
        s.add_forces_at_tracked(&s.active, &x, &y, &mut tx, &mut ty);
        assert!(fx[0] != 0.0 && fy[1] != 0.0);
        assert_eq!(
            (fx.map(f64::to_bits), fy.map(f64::to_bits)),
            (tx.map(f64::to_bits), ty.map(f64::to_bits))
        );
        // the stored length is what is used (the caller guarantees it is the positions' own)
        s.tracked_length[0] = 2.0;
        let (mut sx, mut sy) = ([0.0; 2], [0.0; 2]);
        s.add_forces_at_tracked(&s.active, &x, &y, &mut sx, &mut sy);
        assert_ne!(sx[0], fx[0]);
    }

    #[test]
    fn a_zero_length_spring_gives_no_force_instead_of_nan() {
        let s = one(1.0, 1.0);
        let (mut fx, mut fy) = ([0.0; 2], [0.0; 2]);
        s.add_forces(&s.active, &[0.5, 0.5], &[0.5, 0.5], &mut fx, &mut fy);
        assert_eq!((fx, fy), ([0.0; 2], [0.0; 2]));
    }
}
