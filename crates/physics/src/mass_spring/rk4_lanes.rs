//! One RK4 substep in population lanes: `integrator.rs` and `forces.rs` with one lane per episode
//! of one world shape, every operation the scalar one lane by lane. The ground's force, rare in
//! EvoGym's worlds (they have none), is the scalar function applied lane by lane.

use super::ground::ground_force;
use super::lane_shape::LaneShape;
use super::settings::MassSpringSettings;
use super::spring_lanes::{SpringLanes, Xy};
use vsrlab_lanes::Lanes;

/// The per-episode point state the RK4 step reads and moves, with the contact forces of the
/// substep (computed lane by lane by the scalar worlds).
#[derive(Debug, Clone)]
pub(crate) struct PointLanes<L> {
    pub x: Vec<L>,
    pub y: Vec<L>,
    pub vx: Vec<L>,
    pub vy: Vec<L>,
    pub contact_fx: Vec<L>,
    pub contact_fy: Vec<L>,
}

/// Stage state, forces and the weighted sums of increments (as `integrator::Rk4`), in lanes.
#[derive(Debug, Clone)]
pub(crate) struct Rk4Lanes<L> {
    /// Stage positions and forces, x and y side by side (what the springs gather and add to).
    s: Vec<Xy<L>>,
    svx: Vec<L>,
    svy: Vec<L>,
    f: Vec<Xy<L>>,
    ax: Vec<L>,
    ay: Vec<L>,
    avx: Vec<L>,
    avy: Vec<L>,
}

/// For each stage: the fraction of its increment that gives the next stage's state, and its
/// weight in the final sum (as `integrator::STAGES`).
const STAGES: [(f64, f64); 4] = [(0.5, 1.0 / 6.0), (0.5, 2.0 / 6.0), (1.0, 2.0 / 6.0), (0.0, 1.0 / 6.0)];

impl<L: Lanes> Rk4Lanes<L> {
    /// Buffers for `n` points.
    pub fn new(n: usize) -> Self {
        let z = vec![L::splat(0.0); n];
        Self {
            s: vec![Xy::zero(); n],
            svx: z.clone(),
            svy: z.clone(),
            f: vec![Xy::zero(); n],
            ax: z.clone(),
            ay: z.clone(),
            avx: z.clone(),
            avy: z,
        }
    }

    /// `Rk4::step` in lanes: `shape` gives the masses and which points each stage moves,
    /// `state` the episodes' positions, velocities and contact forces.
    #[inline(always)]
    pub fn step(
        &mut self,
        state: &mut PointLanes<L>,
        shape: &LaneShape,
        spring_state: &mut SpringLanes<L>,
        set: &MassSpringSettings,
    ) {
        for ((s, &x), &y) in self.s.iter_mut().zip(&state.x).zip(&state.y) {
            *s = Xy { x, y };
        }
        self.svx.copy_from_slice(&state.vx);
        self.svy.copy_from_slice(&state.vy);
        let zero = L::splat(0.0);
        for i in shape.stage[0].indices() {
            (self.ax[i], self.ay[i], self.avx[i], self.avy[i]) = (zero, zero, zero, zero);
        }
        for (k, (next, weight)) in STAGES.into_iter().enumerate() {
            self.forces(k, state, shape, spring_state, set);
            self.advance(k, state, shape, set.dt, next, weight);
        }
        for i in shape.free.indices() {
            state.x[i] = state.x[i] + self.ax[i];
            state.y[i] = state.y[i] + self.ay[i];
            state.vx[i] = state.vx[i] + self.avx[i];
            state.vy[i] = state.vy[i] + self.avy[i];
        }
    }

    /// `forces::total_forces` in lanes for stage `k` at the stage state, into `fx`, `fy`.
    #[inline(always)]
    fn forces(
        &mut self,
        k: usize,
        state: &PointLanes<L>,
        shape: &LaneShape,
        spring_state: &mut SpringLanes<L>,
        set: &MassSpringSettings,
    ) {
        self.f.fill(Xy::zero());
        match k {
            0 => spring_state.add_forces::<true>(shape, 0, &self.s, &mut self.f),
            _ => spring_state.add_forces::<false>(shape, k, &self.s, &mut self.f),
        }
        for i in shape.stage[k].indices() {
            let weight = set.gravity * shape.mass[i];
            let f = &mut self.f[i];
            f.x = f.x + (self.svx[i] * -set.drag + state.contact_fx[i]);
            f.y = f.y + (self.svy[i] * -set.drag - weight + state.contact_fy[i]);
            if let Some(g) = &set.ground {
                for lane in 0..L::LANES {
                    let (gx, gy) = ground_force(g, self.s[i].y.get(lane), self.svx[i].get(lane));
                    let (fx, fy) = (f.x.get(lane), f.y.get(lane));
                    f.x.set(lane, fx + gx);
                    f.y.set(lane, fy + gy);
                }
            }
        }
    }

    /// Stage `k`'s increments from its forces: added with `weight` to the sums, and `next` of
    /// them to the substep's start state for the next stage.
    #[inline(always)]
    fn advance(&mut self, k: usize, state: &PointLanes<L>, shape: &LaneShape, dt: f64, next: f64, weight: f64) {
        for r in shape.stage[k].ranges() {
            for i in r {
                let (kvx, kvy) = match shape.masses_are_powers_of_two {
                    true => {
                        let inverse = shape.inverse_mass[i];
                        (self.f[i].x * inverse * dt, self.f[i].y * inverse * dt)
                    }
                    false => {
                        let mass = shape.mass[i];
                        (self.f[i].x / mass * dt, self.f[i].y / mass * dt)
                    }
                };
                let (kx, ky) = (self.svx[i] * dt, self.svy[i] * dt);
                self.ax[i] = self.ax[i] + kx * weight;
                self.ay[i] = self.ay[i] + ky * weight;
                self.avx[i] = self.avx[i] + kvx * weight;
                self.avy[i] = self.avy[i] + kvy * weight;
                self.s[i] = Xy {
                    x: state.x[i] + kx * next,
                    y: state.y[i] + ky * next,
                };
                self.svx[i] = state.vx[i] + kvx * next;
                self.svy[i] = state.vy[i] + kvy * next;
            }
        }
    }
}
