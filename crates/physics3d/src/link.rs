//! A link: the beam between two face-adjacent voxels. Each step it reads both voxels' positions
//! and orientations, expresses their relative configuration in its canonical frame (small-angle
//! or large-angle, with hysteresis), and gives each end a force and a moment in that voxel's own
//! frame: the Euler–Bernoulli frame element plus internal damping (`docs/voxelyze-model.md`
//! §3.4–§3.5, §4.1).

use crate::axis::Axis;
use crate::material::LinkConstants;
use crate::quat::{align_to_x, rotate, rotate_inverse, to_rotation_vector};
use glam::{DQuat, DVec3};

/// Small-angle mode ends beyond this turn (rad) or relative extension, and comes back below
/// them divided by the hysteresis factor.
pub(crate) const SMALL_TURN: f64 = 0.05;
pub(crate) const SMALL_EXTENSION: f64 = 0.5;
pub(crate) const HYSTERESIS: f64 = 1.2;

/// One end of a link as the link reads it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct End {
    pub pos: DVec3,
    pub orient: DQuat,
    /// `2 √m ζ_int / dt_prev` of the voxel (0 before its first step).
    pub damping: f64,
}

/// A link's constants and the state it carries from step to step.
#[derive(Debug, Clone)]
pub(crate) struct Link {
    pub neg: usize,
    pub pos: usize,
    pub axis: Axis,
    pub k: LinkConstants,
    /// Cross-section (s², Poisson's ratio 0).
    pub area: f64,
    /// Rest length: the mean of the two voxels' rest sizes along the axis.
    pub rest: f64,
    pub(crate) small_angle: bool,
    pub(crate) velocity_valid: bool,
    pub(crate) d_old: DVec3,
    pub(crate) theta1_old: DVec3,
    pub(crate) theta2_old: DVec3,
    /// Results of the last update, in each voxel's own frame.
    pub force_neg: DVec3,
    pub force_pos: DVec3,
    pub moment_neg: DVec3,
    pub moment_pos: DVec3,
    /// Axial strain of the last update.
    pub strain: f64,
}

impl Link {
    pub fn new(neg: usize, pos: usize, axis: Axis, k: LinkConstants, area: f64, rest: f64) -> Link {
        Link {
            neg,
            pos,
            axis,
            k,
            area,
            rest,
            small_angle: true,
            velocity_valid: false,
            d_old: DVec3::ZERO,
            theta1_old: DVec3::ZERO,
            theta2_old: DVec3::ZERO,
            force_neg: DVec3::ZERO,
            force_pos: DVec3::ZERO,
            moment_neg: DVec3::ZERO,
            moment_pos: DVec3::ZERO,
            strain: 0.0,
        }
    }

    /// Whether the link is in its small-angle mode.
    #[cfg(test)]
    pub fn small_angle(&self) -> bool {
        self.small_angle
    }

    /// Back to the state of a new link (no damping on its next update).
    pub fn reset(&mut self) {
        let (neg, pos, axis, k, area, rest) = (self.neg, self.pos, self.axis, self.k, self.area, self.rest);
        *self = Link::new(neg, pos, axis, k, area, rest);
    }

    /// The relative configuration: the positive end's offset (elongation along x in small-angle
    /// mode, or the axial elongation alone in large-angle mode), the two end rotations, and the
    /// rotation `q1` that aligned the link (identity in small-angle mode) and the positive end's
    /// rotation `q2`, all in the canonical frame of the negative voxel.
    fn orient(&mut self, a: &End, b: &End) -> (DVec3, DQuat, DQuat) {
        let mut d = self.axis.to_x(b.pos - a.pos);
        let q1 = self.axis.quat_to_x(a.orient);
        let mut q2 = self.axis.quat_to_x(b.orient);
        let rot = q1.conjugate();
        d = rotate(rot, d);
        q2 = rot * q2;
        let turn = (d.z.abs() + d.y.abs()) / d.x;
        let extension = (1.0 - d.x / self.rest).abs();
        if !self.small_angle && turn < SMALL_TURN && extension < SMALL_EXTENSION {
            self.small_angle = true;
            self.velocity_valid = false;
        } else if self.small_angle && (turn > SMALL_TURN * HYSTERESIS || extension > SMALL_EXTENSION * HYSTERESIS) {
            self.small_angle = false;
            self.velocity_valid = false;
        }
        if self.small_angle {
            d.x -= self.rest;
            return (d, DQuat::IDENTITY, q2);
        }
        let align = align_to_x(d, DQuat::IDENTITY);
        q2 = align * q2;
        let length = d.length();
        (DVec3::new(length - self.rest, 0.0, 0.0), align, q2)
    }

    /// Computes the forces and moments on both ends from their current state.
    pub fn update(&mut self, a: &End, b: &End) {
        let (d, q1, q2) = self.orient(a, b);
        let (theta1, theta2) = (
            if self.small_angle {
                DVec3::ZERO
            } else {
                to_rotation_vector(q1)
            },
            to_rotation_vector(q2),
        );
        let k = self.k;
        self.strain = d.x / self.rest;
        let axial = k.e * self.strain * self.area;
        let mut fn_ = DVec3::new(
            axial,
            k.b1 * d.y - k.b2 * (theta1.z + theta2.z),
            k.b1 * d.z + k.b2 * (theta1.y + theta2.y),
        );
        let mut fp = -fn_;
        let mut mn = DVec3::new(
            k.a2 * (theta2.x - theta1.x),
            -k.b2 * d.z - k.b3 * (2.0 * theta1.y + theta2.y),
            k.b2 * d.y - k.b3 * (2.0 * theta1.z + theta2.z),
        );
        let mut mp = DVec3::new(
            k.a2 * (theta1.x - theta2.x),
            -k.b2 * d.z - k.b3 * (theta1.y + 2.0 * theta2.y),
            k.b2 * d.y - k.b3 * (theta1.z + 2.0 * theta2.z),
        );
        if self.velocity_valid {
            let dd = 0.5 * (d - self.d_old);
            let (t1, t2) = (0.5 * (theta1 - self.theta1_old), 0.5 * (theta2 - self.theta2_old));
            let c = DVec3::new(
                k.sqrt_a1 * dd.x,
                k.sqrt_b1 * dd.y - k.sqrt_b2 * (t1.z + t2.z),
                k.sqrt_b1 * dd.z + k.sqrt_b2 * (t1.y + t2.y),
            );
            fn_ += a.damping * c;
            fp -= b.damping * c;
            let twist = k.sqrt_a2 * (t2.x - t1.x);
            mn -= 0.5
                * a.damping
                * DVec3::new(
                    -twist,
                    k.sqrt_b2 * dd.z + k.sqrt_b3 * (2.0 * t1.y + t2.y),
                    -k.sqrt_b2 * dd.y + k.sqrt_b3 * (2.0 * t1.z + t2.z),
                );
            mp -= 0.5
                * b.damping
                * DVec3::new(
                    twist,
                    k.sqrt_b2 * dd.z + k.sqrt_b3 * (t1.y + 2.0 * t2.y),
                    -k.sqrt_b2 * dd.y + k.sqrt_b3 * (t1.z + 2.0 * t2.z),
                );
        } else {
            self.velocity_valid = true;
        }
        (self.d_old, self.theta1_old, self.theta2_old) = (d, theta1, theta2);
        if !self.small_angle {
            fn_ = rotate_inverse(q1, fn_);
            mn = rotate_inverse(q1, mn);
        }
        fp = rotate_inverse(q2, fp);
        mp = rotate_inverse(q2, mp);
        self.force_neg = self.axis.back_from_x(fn_);
        self.force_pos = self.axis.back_from_x(fp);
        self.moment_neg = self.axis.back_from_x(mn);
        self.moment_pos = self.axis.back_from_x(mp);
    }
}
