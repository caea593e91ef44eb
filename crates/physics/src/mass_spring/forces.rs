//! The force on every free point for one integrator stage: springs, drag, gravity, the contact
//! forces of the substep, and the ground.

use super::ground::ground_force;
use super::points::Points;
use super::settings::MassSpringSettings;
use super::springs::Springs;

/// Positions and velocities of one integrator stage.
pub(crate) struct Stage<'a> {
    pub x: &'a [f64],
    pub y: &'a [f64],
    pub vx: &'a [f64],
    pub vy: &'a [f64],
}

/// Writes the total force on each point RK4 stage `stage` moves, in state `s`, into `fx`, `fy`
/// (other entries are meaningless). The first stage's positions must be those at which the rest
/// lengths last tracked their goals (`Springs::track_goals`), as in every substep.
pub(crate) fn total_forces(
    s: &Stage,
    stage: usize,
    points: &Points,
    springs: &Springs,
    set: &MassSpringSettings,
    fx: &mut [f64],
    fy: &mut [f64],
) {
    fx.fill(0.0);
    fy.fill(0.0);
    // the first stage's positions are those at which the rest lengths just tracked their goals
    match stage {
        0 => springs.add_forces_at_tracked(&springs.stages[0], s.x, s.y, fx, fy),
        _ => springs.add_forces(&springs.stages[stage], s.x, s.y, fx, fy),
    }
    for i in points.stage[stage].indices() {
        fx[i] += -set.drag * s.vx[i] + points.contact_fx[i];
        fy[i] += -set.drag * s.vy[i] - set.gravity * points.mass[i] + points.contact_fy[i];
        if let Some(g) = &set.ground {
            let (gx, gy) = ground_force(g, s.y[i], s.vx[i]);
            fx[i] += gx;
            fy[i] += gy;
        }
    }
}
