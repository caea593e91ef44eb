//! The world and its step: a pipeline of named stages per substep.

use super::actuators::Actuators;
use super::bodies::Bodies;
use super::broad_phase::BroadPhase;
use super::contact::compute_contact_forces;
use super::handles::{BodyId, PointId, SpringId};
use super::integrator::Rk4;
use super::overlap::{check_self_overlap, overlapping_pairs};
use super::points::Points;
use super::projection::Projection;
use super::springs::{length, Springs};
use super::{MassSpringError, MassSpringSettings};

/// What a successful [`MassSpringWorld::step`] did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StepReport {
    /// Substeps run.
    pub substeps: u32,
    /// Point-in-quad contacts that pushed, summed over the substeps.
    pub contacts: usize,
}

/// A built mass-spring world. Positions and velocities are readable as slices indexed by
/// [`PointId::index`].
#[derive(Debug, Clone)]
pub struct MassSpringWorld {
    pub(super) settings: MassSpringSettings,
    pub(super) points: Points,
    pub(super) springs: Springs,
    actuators: Actuators,
    pub(super) bodies: Bodies,
    broad: BroadPhase,
    pub(super) projection: Projection,
    rk4: Rk4,
    substeps_done: u64,
    /// Which build this world is a copy of: copies share the build's constants (nothing changes
    /// them after the build), so lanes that checked one copy's shape need not check the others'.
    build: u64,
    /// Names the positions of the fixed points: copies share it, and it changes whenever a point
    /// is moved by hand, so lanes reload a world's terrain only when it may differ.
    pub(super) fixed_points: u64,
}

/// Builds and hand-moved positions so far, numbering them (no result depends on the numbers).
static BUILDS: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

impl MassSpringWorld {
    pub(crate) fn assemble(
        settings: MassSpringSettings,
        points: Points,
        springs: Springs,
        actuators: Actuators,
        bodies: Bodies,
        projection: Projection,
        rk4: Rk4,
    ) -> Self {
        Self {
            settings,
            points,
            springs,
            actuators,
            broad: BroadPhase::new(&bodies),
            bodies,
            projection,
            rk4,
            substeps_done: 0,
            build: BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
            fixed_points: BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed),
        }
    }

    /// Runs `settings.substeps` substeps with `targets` (one per actuator, clipped into
    /// `settings.target_range`, as fractions of the driven springs' initial rest lengths).
    ///
    /// Each substep: contact forces from the current state; rest lengths track their goals; one
    /// RK4 step; loose bands then tight limits; non-finite check; displacement velocities and
    /// boxes; self-overlap check. On an error the remaining substeps are skipped. Allocates
    /// nothing.
    pub fn step(&mut self, targets: &[f64]) -> Result<StepReport, MassSpringError> {
        self.start_step(targets)?;
        let mut report = StepReport::default();
        for _ in 0..self.settings.substeps {
            report.contacts += self.substep()?;
            report.substeps += 1;
        }
        Ok(report)
    }

    /// Checks `targets` and sets the goal lengths they ask for: the start of [`Self::step`].
    pub(crate) fn start_step(&mut self, targets: &[f64]) -> Result<(), MassSpringError> {
        self.actuators.check(targets)?;
        self.actuators
            .set_goals(targets, self.settings.target_range, &mut self.springs);
        Ok(())
    }

    /// One substep; returns the number of contacts.
    fn substep(&mut self) -> Result<usize, MassSpringError> {
        let (n, contacts) = self.begin_substep();
        self.springs
            .track_goals(&self.points.x, &self.points.y, self.settings.tracking_rate);
        self.rk4.step(&mut self.points, &self.springs, &self.settings);
        self.projection
            .project_bands(&self.springs, &mut self.points, self.settings.band_correction);
        self.projection
            .project_limits(&self.springs, &mut self.points, self.settings.limit_correction);
        self.end_substep(n)?;
        Ok(contacts)
    }

    /// The part of a substep before the springs move anything: counts it, computes the contact
    /// forces (held through the substep) and remembers the state to undo; returns the substep's
    /// number and its contacts.
    pub(crate) fn begin_substep(&mut self) -> (u64, usize) {
        let contacts = compute_contact_forces(&self.bodies, &mut self.broad, &mut self.points, &self.settings.contact);
        (self.begin_substep_after_contacts(), contacts)
    }

    /// [`Self::begin_substep`] once the contact forces are in place (lanes compute those of
    /// several worlds together): counts the substep and remembers the state to undo; returns
    /// the substep's number.
    pub(crate) fn begin_substep_after_contacts(&mut self) -> u64 {
        let n = self.substeps_done;
        self.substeps_done += 1;
        self.points.remember();
        n
    }

    /// The part of substep `n` after the points moved: the non-finite check (undoing the
    /// substep), displacement velocities, boxes and the self-overlap check.
    pub(crate) fn end_substep(&mut self, n: u64) -> Result<(), MassSpringError> {
        if let Some(point) = self.points.first_non_finite() {
            self.points.restore();
            return Err(MassSpringError::NonFinite { substep: n, point });
        }
        self.points.update_moved_velocity(self.settings.dt);
        self.bodies.update_boxes(&self.points.x, &self.points.y, false);
        check_self_overlap(&self.bodies, n)
    }

    /// The settings.
    pub fn settings(&self) -> &MassSpringSettings {
        &self.settings
    }

    /// Number of points.
    pub fn point_count(&self) -> usize {
        self.points.x.len()
    }

    /// Number of springs.
    pub fn spring_count(&self) -> usize {
        self.springs.a.len()
    }

    /// Number of actuators (the length `step` expects of its targets).
    pub fn actuator_count(&self) -> usize {
        self.actuators.len()
    }

    /// x of every point.
    pub fn positions_x(&self) -> &[f64] {
        &self.points.x
    }

    /// y of every point.
    pub fn positions_y(&self) -> &[f64] {
        &self.points.y
    }

    /// Velocity along x of every point (the integrator's state).
    pub fn velocities_x(&self) -> &[f64] {
        &self.points.vx
    }

    /// Velocity along y of every point.
    pub fn velocities_y(&self) -> &[f64] {
        &self.points.vy
    }

    /// Mass of every point.
    pub fn masses(&self) -> &[f64] {
        &self.points.mass
    }

    /// Whether a point is fixed.
    pub fn is_fixed(&self, p: PointId) -> bool {
        self.points.fixed[p.index()]
    }

    /// Rest length of every spring as used in the last substep.
    pub fn rest_lengths(&self) -> &[f64] {
        &self.springs.rest
    }

    /// Rest length of every spring given at build time.
    pub fn initial_rest_lengths(&self) -> &[f64] {
        &self.springs.initial
    }

    /// Current goal length of every spring.
    pub fn goal_lengths(&self) -> &[f64] {
        &self.springs.goal
    }

    /// The two ends of a spring.
    pub fn spring_ends(&self, s: SpringId) -> (PointId, PointId) {
        (PointId(self.springs.a[s.index()]), PointId(self.springs.b[s.index()]))
    }

    /// Current length of a spring.
    pub fn spring_length(&self, s: SpringId) -> f64 {
        let (a, b) = (self.springs.a[s.index()] as usize, self.springs.b[s.index()] as usize);
        length(&self.points.x, &self.points.y, a, b)
    }

    /// The number of the build this world is a copy of.
    pub(crate) fn build(&self) -> u64 {
        self.build
    }

    /// Substeps run since the world was built.
    pub fn substeps_done(&self) -> u64 {
        self.substeps_done
    }

    /// Simulated time in seconds.
    pub fn time(&self) -> f64 {
        self.substeps_done as f64 * self.settings.dt
    }

    /// Ordered pairs of a body's non-neighbouring boundary quads whose boxes overlap now (the
    /// quantity the self-overlap check compares with the body's boundary-quad count).
    pub fn self_overlap_pairs(&self, b: BodyId) -> usize {
        overlapping_pairs(&self.bodies, b.index())
    }

    /// Moves a point (its displacement velocity is left as it was).
    pub fn set_position(&mut self, p: PointId, x: f64, y: f64) {
        self.points.x[p.index()] = x;
        self.points.y[p.index()] = y;
        self.bodies.update_boxes(&self.points.x, &self.points.y, true);
        self.fixed_points = BUILDS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }

    /// Sets a free point's velocity, both the integrated one and the displacement velocity that
    /// contacts damp; a fixed point stays at rest.
    pub fn set_velocity(&mut self, p: PointId, vx: f64, vy: f64) {
        let i = p.index();
        if self.points.fixed[i] {
            return;
        }
        (self.points.vx[i], self.points.vy[i]) = (vx, vy);
        (self.points.moved_vx[i], self.points.moved_vy[i]) = (vx, vy);
    }
}
