//! [`MassSpringLanes`]: up to [`LANES`] worlds of one shape stepped together, the springs' and the
//! integrator's work in f64 lanes (one per world), the contacts found for all worlds together,
//! the checks and boxes world by world.
//!
//! The worlds stay their owners' (an environment's, an episode's): a step borrows them, loads
//! their state into the lanes, and leaves each world as stepping it alone would. A substep finds
//! the contacts of all its worlds together ([`ContactLanes`]), runs its scalar start in every
//! world (count, the state to undo), then, in lanes, rest-length tracking, the RK4 step and both
//! length projections, then writes the free points back and runs each world's scalar end
//! (non-finite check, displacement velocities, boxes, self-overlap). Every lane has the bits of its world stepped alone: the laned kernels are the
//! scalar computations lane by lane, in the same order. A world whose episode ended is simply
//! not passed again, and another episode's world takes its lane: lanes are refilled by the caller.
//! The lanes are plain arrays compiled with AVX2 enabled where the CPU has it (chosen at run
//! time), else the baseline instructions, the same bits either way.

use super::contact_lanes::ContactLanes;
use super::lane_shape::LaneShape;
use super::rk4_lanes::{PointLanes, Rk4Lanes};
use super::spring_lanes::{project_bands, project_limits, Pull, SpringLanes};
use super::{MassSpringError, MassSpringSettings, MassSpringWorld, StepReport};
use vsrlab_lanes::{F64s, Lanes};

/// Worlds stepped together at most: four f64 lanes, one AVX2 register. One lane count, compiled
/// here once: every count is a copy of the kernels in every crate that uses it (the test build,
/// CI's longest stage, grew by a minute with two).
pub const LANES: usize = 4;

/// Lanes for up to [`LANES`] worlds of one shape: what the laned work reads of the shape, and
/// the laned state and buffers (reloaded from the worlds at every step).
#[derive(Debug, Clone)]
pub struct MassSpringLanes {
    /// A world of the shape, for its settings and for checking the worlds of a step.
    model: MassSpringWorld,
    /// Builds whose worlds were found to have the model's shape: their copies fit without
    /// comparing every constant again at every step (a few thousand comparisons per world).
    fitting_builds: Vec<u64>,
    shape: LaneShape,
    laned: Laned<F64s<LANES>>,
    contacts: ContactLanes,
}

/// Builds a lanes value remembers as fitting, at most.
const MAX_REMEMBERED: usize = 64;

/// What a step did to each world (`None` for lanes without one).
pub type LaneReports = [Option<Result<StepReport, MassSpringError>>; LANES];

/// The laned state and buffers.
#[derive(Debug, Clone)]
struct Laned<L> {
    points: PointLanes<L>,
    springs: SpringLanes<L>,
    rk4: Rk4Lanes<L>,
    shift_x: Vec<L>,
    shift_y: Vec<L>,
}

impl MassSpringLanes {
    /// Lanes for worlds of `model`'s shape: the same points, masses, springs, stiffnesses,
    /// bands, limits and settings (their states may differ).
    pub fn new(model: &MassSpringWorld) -> Self {
        let shape = LaneShape::of(&model.points, &model.springs, &model.projection);
        let (p, s) = (shape.points.len(), shape.springs.len());
        let zeros = |n: usize| vec![F64s::splat(0.0); n];
        let laned = Laned {
            points: PointLanes {
                x: zeros(p),
                y: zeros(p),
                vx: zeros(p),
                vy: zeros(p),
                contact_fx: zeros(p),
                contact_fy: zeros(p),
            },
            springs: SpringLanes {
                rest: zeros(s),
                goal: zeros(s),
                tracked: zeros(s),
                pull: vec![Pull::zero(); s],
            },
            rk4: Rk4Lanes::new(p),
            shift_x: zeros(p),
            shift_y: zeros(p),
        };
        MassSpringLanes {
            model: model.clone(),
            fitting_builds: vec![model.build()],
            shape,
            laned,
            contacts: ContactLanes::new(model),
        }
    }

    /// Whether `world` has the lanes' shape.
    pub fn fits(&self, world: &MassSpringWorld) -> bool {
        self.fitting_builds.contains(&world.build()) || same_shape(&self.model, world)
    }

    /// [`Self::fits`], remembering a fitting world's build (at most a few dozen).
    fn fits_remembered(&mut self, world: &MassSpringWorld) -> bool {
        if self.fitting_builds.contains(&world.build()) {
            return true;
        }
        let fits = same_shape(&self.model, world);
        if fits && self.fitting_builds.len() < MAX_REMEMBERED {
            self.fitting_builds.push(world.build());
        }
        fits
    }

    /// One step of each of `worlds` (at most [`LANES`], each of the lanes' shape) with its `targets`, as
    /// [`MassSpringWorld::step`] would do it to each alone: the same reports, the same states.
    /// Refuses more than [`LANES`] worlds, or a world of another shape, before stepping any.
    pub fn step(
        &mut self,
        worlds: &mut [&mut MassSpringWorld],
        targets: &[&[f64]],
    ) -> Result<LaneReports, MassSpringError> {
        self.check(worlds, targets)?;
        let mut out: LaneReports = std::array::from_fn(|_| None);
        let mut stepping = [false; LANES];
        for (l, world) in worlds.iter_mut().enumerate() {
            let started = world.start_step(targets[l]);
            stepping[l] = started.is_ok();
            out[l] = Some(started.map(|()| StepReport::default()));
        }
        for (l, world) in worlds.iter().enumerate().filter(|&(l, _)| stepping[l]) {
            self.load(l, world);
        }
        for _ in 0..self.model.settings.substeps {
            if !stepping.contains(&true) {
                break;
            }
            self.substep(worlds, &mut stepping, &mut out);
        }
        for (l, world) in worlds.iter_mut().enumerate().filter(|&(l, _)| stepping[l]) {
            self.store_springs(l, world);
        }
        Ok(out)
    }

    /// The step's arguments: at most [`LANES`] worlds of the lanes' shape, one target list each.
    fn check(&mut self, worlds: &[&mut MassSpringWorld], targets: &[&[f64]]) -> Result<(), MassSpringError> {
        if worlds.len() > LANES || targets.len() != worlds.len() {
            return Err(MassSpringError::Invalid(format!(
                "{LANES} lanes step at most {LANES} worlds with one target list each, got {} worlds and {} lists",
                worlds.len(),
                targets.len()
            )));
        }
        match worlds.iter().position(|w| !self.fits_remembered(w)) {
            Some(l) => Err(MassSpringError::Invalid(format!(
                "world {l} has another shape than the lanes' (points, springs, limits or settings)"
            ))),
            None => Ok(()),
        }
    }

    /// One substep of the worlds in `stepping`; a world that fails leaves `stepping`, its
    /// error in `out`.
    fn substep(&mut self, worlds: &mut [&mut MassSpringWorld], stepping: &mut [bool; LANES], out: &mut LaneReports) {
        let mut numbers = [0u64; LANES];
        let contacts = self.contacts.compute(worlds, stepping);
        for (l, world) in worlds.iter_mut().enumerate().filter(|&(l, _)| stepping[l]) {
            numbers[l] = world.begin_substep_after_contacts();
            if let Some(Ok(report)) = &mut out[l] {
                report.contacts += contacts[l];
            }
            let (points, state) = (&world.points, &mut self.laned.points);
            for i in self.shape.stage[0].indices() {
                let p = self.shape.points[i] as usize;
                state.contact_fx[i].set(l, points.contact_fx[p]);
                state.contact_fy[i].set(l, points.contact_fy[p]);
            }
        }
        self.laned_work();
        for (l, world) in worlds.iter_mut().enumerate() {
            if !stepping[l] {
                continue;
            }
            let state = &self.laned.points;
            for i in self.shape.free.indices() {
                let p = self.shape.points[i] as usize;
                world.points.x[p] = state.x[i].get(l);
                world.points.y[p] = state.y[i].get(l);
                world.points.vx[p] = state.vx[i].get(l);
                world.points.vy[p] = state.vy[i].get(l);
            }
            match world.end_substep(numbers[l]) {
                Ok(()) => {
                    if let Some(Ok(report)) = &mut out[l] {
                        report.substeps += 1;
                    }
                }
                Err(e) => {
                    out[l] = Some(Err(e));
                    stepping[l] = false;
                    self.store_springs(l, world);
                }
            }
        }
    }

    /// The laned part of a substep, in AVX2 instructions where the CPU has them.
    fn laned_work(&mut self) {
        #[cfg(target_arch = "x86_64")]
        if is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2
            return unsafe { laned_work_avx2(&mut self.laned, &self.shape, &self.model.settings) };
        }
        self.laned.work(&self.shape, &self.model.settings);
    }

    /// Copies `world`'s state into lane `lane`.
    fn load(&mut self, lane: usize, w: &MassSpringWorld) {
        let p = &mut self.laned.points;
        for (i, &k) in self.shape.points.iter().enumerate() {
            let k = k as usize;
            p.x[i].set(lane, w.points.x[k]);
            p.y[i].set(lane, w.points.y[k]);
            p.vx[i].set(lane, w.points.vx[k]);
            p.vy[i].set(lane, w.points.vy[k]);
        }
        let s = &mut self.laned.springs;
        for (i, &k) in self.shape.springs.iter().enumerate() {
            let k = k as usize;
            s.rest[i].set(lane, w.springs.rest[k]);
            s.goal[i].set(lane, w.springs.goal[k]);
            s.tracked[i].set(lane, w.springs.tracked_length[k]);
        }
    }

    /// Copies lane `lane`'s rest and tracked lengths back to its world.
    fn store_springs(&self, lane: usize, world: &mut MassSpringWorld) {
        let (springs, laned) = (&mut world.springs, &self.laned.springs);
        for (i, &k) in self.shape.springs.iter().enumerate() {
            springs.rest[k as usize] = laned.rest[i].get(lane);
            springs.tracked_length[k as usize] = laned.tracked[i].get(lane);
        }
    }
}

/// The laned work compiled with AVX2.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn laned_work_avx2<L: Lanes>(laned: &mut Laned<L>, shape: &LaneShape, set: &MassSpringSettings) {
    laned.work(shape, set)
}

impl<L: Lanes> Laned<L> {
    /// Tracking, RK4 and both projections for every lane, with `shape`'s constants.
    #[inline(always)]
    fn work(&mut self, shape: &LaneShape, set: &MassSpringSettings) {
        let p = &mut self.points;
        self.springs.track_goals(shape, &p.x, &p.y, set.tracking_rate);
        self.rk4.step(p, shape, &mut self.springs, set);
        project_bands(
            shape,
            (&mut self.shift_x, &mut self.shift_y),
            (&mut p.x, &mut p.y),
            set.band_correction,
        );
        project_limits(shape, (&mut p.x, &mut p.y), set.limit_correction);
    }
}

/// Whether two worlds have the same constants for the laned work.
fn same_shape(a: &MassSpringWorld, b: &MassSpringWorld) -> bool {
    let (pa, pb) = (&a.points, &b.points);
    let (sa, sb) = (&a.springs, &b.springs);
    a.settings == b.settings
        && pa.mass == pb.mass
        && pa.fixed == pb.fixed
        && pa.stage == pb.stage
        && sa.a == sb.a
        && sa.b == sb.b
        && sa.stiffness == sb.stiffness
        && sa.initial == sb.initial
        && sa.band == sb.band
        && sa.active == sb.active
        && sa.stages == sb.stages
        && a.projection.limit_spring == b.projection.limit_spring
        && a.projection.limit_band == b.projection.limit_band
        && a.bodies.same_quads(&b.bodies)
}
