//! The sequential-impulse solver: the pipeline of dyn4j, the engine behind 2D-VSR-Sim.
//!
//! One step, in dyn4j's order (vsr-model.md §2.1–2.2): gravity, forces and damping; contacts and
//! joints initialised and warm started with last step's impulses; `velocity_iterations` sweeps
//! over the joints, then the contacts; positions integrated (speeds clamped to the per-step
//! limits); up to `position_iterations` sweeps that push overlapping shapes and drifting welds and
//! ropes back, stopping once all are within tolerance. Contacts for the next step are detected at
//! the end of the step. Every part is its own body: welds are rigid joints, solved iteratively.
//!
//! Written from dyn4j's documented algorithm (sequential impulses in the style of Box2D), not
//! ported from its code; where dyn4j has a quirk that changes motion, the quirk is kept and named.

mod ccd;
mod colour;
mod contacts;
mod distance;
mod island;
mod joints;
mod rest;

pub(crate) use ccd::Ccd;
pub(crate) use contacts::Contacts;
pub(crate) use island::{Island, Joint};
pub(crate) use joints::{Joints, Rope, Spring, Weld};
pub(crate) use rest::Rest;

use super::contact::ContactConstraint;
use super::settings::{Dyn4jVersion, WorldSettings};
use super::world::{Bodies, BodyState};
use crate::math::{Rot, Vec2};

/// The settings one step of the sequential-impulse solver reads, copied out of [`WorldSettings`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Params {
    pub dt: f64,
    pub velocity_iterations: u32,
    pub position_iterations: u32,
    pub warm_starting: bool,
    pub baumgarte: f64,
    pub linear_slop: f64,
    pub angular_slop: f64,
    pub max_linear_correction: f64,
    pub max_translation: f64,
    pub max_rotation: f64,
    pub restitution_threshold: f64,
    /// dyn4j 3.3.0's contact position pass treats every dynamic body as mass 1.
    pub unit_position_mass: bool,
    pub version: Dyn4jVersion,
    pub continuous_collision: bool,
    /// Sweep the joints grouped by colour ([`WorldSettings::coloured_joints`]).
    pub coloured_joints: bool,
}

impl Params {
    pub fn of(s: &WorldSettings) -> Params {
        let version = s.dyn4j_version();
        Params {
            dt: s.dt / f64::from(s.sequential_substeps),
            velocity_iterations: s.velocity_iterations,
            position_iterations: s.position_iterations,
            warm_starting: s.warm_starting,
            baumgarte: s.baumgarte,
            linear_slop: s.linear_slop,
            angular_slop: s.angular_slop,
            max_linear_correction: s.max_linear_correction,
            max_translation: s.max_translation,
            max_rotation: s.max_rotation,
            restitution_threshold: s.restitution_threshold,
            unit_position_mass: version == Dyn4jVersion::V3_3_0,
            version,
            continuous_collision: s.continuous_collision,
            coloured_joints: s.coloured_joints,
        }
    }
}

/// The joints and contacts of a world stepped by sequential impulses.
#[derive(Debug, Clone, Default)]
pub(crate) struct SequentialSolver {
    pub joints: Joints,
    pub contacts: Contacts,
    pub ccd: Ccd,
    pub island: Island,
    /// dyn4j 4.2.1's at-rest detection: each body's time at rest and sleep.
    pub rest: Rest,
    /// Buffers of the coloured joint order ([`Params::coloured_joints`]).
    colours: colour::JointColours,
}

impl SequentialSolver {
    /// Solves velocities, integrates positions, corrects them and stops bodies at their time of
    /// impact with static geometry: everything of a step between integrating forces and detecting
    /// the next step's contacts. `detected` are the contacts the step solves (`static_of` maps a
    /// static contact's key to its polygon).
    pub fn solve(
        &mut self,
        bodies: &mut Bodies,
        detected: &[ContactConstraint],
        static_of: fn(u64) -> u32,
        p: &Params,
    ) {
        let sleeps = p.version == Dyn4jVersion::V4_2_1;
        let rest = sleeps.then_some(&mut self.rest);
        self.island.walk(self.contacts.pairs(), sleeps, rest);
        if p.coloured_joints {
            let j = &self.joints;
            let ends = |joint| match joint {
                Joint::Spring(i) => (j.springs[i as usize].a, j.springs[i as usize].b),
                Joint::Rope(i) => (j.ropes[i as usize].a, j.ropes[i as usize].b),
                Joint::Weld(i) => (j.welds[i as usize].a, j.welds[i as usize].b),
            };
            self.colours.group(&mut self.island.joints, bodies.len(), ends);
        }
        let (joints, contacts) = (&self.island.joints, &self.island.contacts);
        self.contacts.initialize(bodies, p, contacts);
        self.joints.initialize(bodies, p, joints);
        for _ in 0..p.velocity_iterations {
            self.joints.solve_velocities(bodies, joints);
            self.contacts.solve_velocities(bodies, contacts);
        }
        integrate_positions(bodies, p);
        let mut positions_solved = false;
        for _ in 0..p.position_iterations {
            let contacts_done = self.contacts.solve_positions(bodies, p, contacts);
            let joints_done = self.joints.solve_positions(bodies, p, joints);
            if contacts_done && joints_done {
                positions_solved = true;
                break;
            }
        }
        if sleeps {
            for island in self.island.islands() {
                self.rest.settle(bodies, island, p.dt, positions_solved);
            }
        }
        if p.continuous_collision {
            self.ccd.solve(bodies, detected, static_of, p);
        }
    }
}

/// x += v·dt and θ += ω·dt, after scaling down speeds that would pass the per-step limits.
fn integrate_positions(bodies: &mut Bodies, p: &Params) {
    let (max_t, max_r) = (p.max_translation, p.max_rotation);
    for s in &mut bodies.state[1..] {
        let travel = s.vel * p.dt;
        if travel.length_squared() > max_t * max_t {
            s.vel *= max_t / travel.length();
        }
        let turn = s.omega * p.dt;
        if turn * turn > max_r * max_r {
            s.omega *= max_r / turn.abs();
        }
        s.pos += s.vel * p.dt;
        s.rot = turned(s.rot, Rot::new(s.omega * p.dt));
    }
}

/// `rot` turned further by `by`.
#[inline]
fn turned(rot: Rot, by: Rot) -> Rot {
    Rot {
        c: by.c * rot.c - by.s * rot.s,
        s: by.s * rot.c + by.c * rot.s,
    }
}

/// Turns a body by `angle` (radians) about its centre of mass.
#[inline]
fn rotate(b: &mut BodyState, angle: f64) {
    b.rot = turned(b.rot, Rot::new(angle));
}

/// Turns a body by `angle` about the point `pivot`. dyn4j's position passes over contacts and
/// ropes turn a body about its centre as it was *before* the same correction moved it, so the
/// centre swings a little too; kept, as it changes motion.
#[inline]
fn rotate_about(b: &mut BodyState, angle: f64, pivot: Vec2) {
    let r = Rot::new(angle);
    b.rot = turned(b.rot, r);
    b.pos = pivot + r.apply(b.pos - pivot);
}

/// Velocity of the point at arm `r` from a body's centre of mass.
#[inline]
fn point_velocity(b: &BodyState, r: Vec2) -> Vec2 {
    b.vel + Vec2::cross_scalar_left(b.omega, r)
}

/// An angle brought into [−π, π] by one turn, as dyn4j does.
fn wrap_angle(mut r: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    if r < -PI {
        r += TAU;
    }
    if r > PI {
        r -= TAU;
    }
    r
}

/// The body's angle in (−π, π], as dyn4j reads it off its rotation matrix.
#[inline]
fn angle_of(b: &BodyState) -> f64 {
    b.rot.s.atan2(b.rot.c)
}

#[cfg(test)]
mod tests;
