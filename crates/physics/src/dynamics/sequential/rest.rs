//! dyn4j 4.2.1's at-rest detection ("sleeping"), which the 2022 preset's original runs with its
//! default settings: after a step, a body whose speed is at most 0.01 (length/s) and whose turning
//! speed is at most 2°/s adds the step to its time at rest, any other body starts its count again;
//! when every dynamic body of an island has been at rest for 0.5 s and the island's position pass
//! converged, the whole island is put at rest: its velocities become exactly 0 and it is left out
//! of the following steps (no gravity, no solve, no motion) until something wakes it: a body of
//! an awake island that reaches it through a contact or a joint, or a spring whose rest length
//! changes (dyn4j's `setRestDistance`, which wakes only on a new value). dyn4j 3.3.0 (the 2021
//! preset) is not followed here: 2D-VSR-Sim v1.10.0 sets every spring's length at every step, and
//! 3.3.0's `setDistance` wakes the bodies whatever the value.

use super::super::world::Bodies;

/// Largest speed (length/s) of a body at rest (dyn4j's default).
pub(crate) const MAX_LINEAR_SPEED: f64 = 0.01;
/// Largest turning speed (rad/s) of a body at rest (dyn4j's default, 2°/s).
pub(crate) const MAX_ANGULAR_SPEED: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// Time (s) every body of an island must have been at rest before the island is put at rest.
pub(crate) const MIN_REST_TIME: f64 = 0.5;

/// Each body's time at rest and whether it sleeps (index 0, the static world, never does).
#[derive(Debug, Clone, Default)]
pub(crate) struct Rest {
    time: Vec<f64>,
    asleep: Vec<bool>,
    /// How many bodies sleep (0: [`Rest::hold`] has nothing to do).
    sleeping: usize,
}

impl Rest {
    /// Every one of `n_bodies` bodies awake, with no time at rest.
    pub fn new(n_bodies: usize) -> Rest {
        Rest {
            time: vec![0.0; n_bodies],
            asleep: vec![false; n_bodies],
            sleeping: 0,
        }
    }

    /// Whether body `b` sleeps.
    #[inline]
    pub fn asleep(&self, b: usize) -> bool {
        self.asleep.get(b).copied().unwrap_or(false)
    }

    /// Wakes body `b`: a sleeping body starts its time at rest again (an awake one keeps it).
    #[inline]
    pub fn wake(&mut self, b: usize) {
        if self.asleep(b) {
            self.asleep[b] = false;
            self.time[b] = 0.0;
            self.sleeping -= 1;
        }
    }

    /// Keeps sleeping bodies out of a step once its velocities were integrated: no gravity, no
    /// forces (their velocities were exactly 0 and their forces cleared when they fell asleep).
    pub fn hold(&self, bodies: &mut Bodies) {
        if self.sleeping == 0 {
            return;
        }
        for (s, _) in bodies.state.iter_mut().zip(&self.asleep).filter(|(_, &asleep)| asleep) {
            s.vel = crate::math::Vec2::ZERO;
            s.omega = 0.0;
        }
    }

    /// After a step of `dt`: updates the time at rest of the bodies of one island (`island`,
    /// static world excluded) and puts them all at rest when each has been for
    /// [`MIN_REST_TIME`] and the island's position pass converged.
    pub fn settle(&mut self, bodies: &mut Bodies, island: &[u32], dt: f64, positions_solved: bool) {
        let mut least = f64::MAX;
        for &b in island {
            let (b, s) = (b as usize, &bodies.state[b as usize]);
            let moving =
                s.vel.length_squared() > MAX_LINEAR_SPEED * MAX_LINEAR_SPEED || s.omega.abs() > MAX_ANGULAR_SPEED;
            self.time[b] = if moving { 0.0 } else { self.time[b] + dt };
            least = least.min(self.time[b]);
        }
        if island.is_empty() || least < MIN_REST_TIME || !positions_solved {
            return;
        }
        for &b in island {
            let s = &mut bodies.state[b as usize];
            s.vel = crate::math::Vec2::ZERO;
            s.omega = 0.0;
            bodies.force[b as usize] = crate::math::Vec2::ZERO;
            bodies.torque[b as usize] = 0.0;
            self.asleep[b as usize] = true;
        }
        self.sleeping += island.len();
    }
}
