//! A world of N episodes at once (issue 52, population lanes): the same body shape in every lane,
//! each lane with its own temperatures and so its own motion, stepped as `World::step` does, lane
//! by lane: every link from the state at the start of the step, the voxel–voxel contacts
//! (`collision_lanes.rs`), then every voxel. The lanes are AVX-512 registers where the CPU has
//! them and N is a multiple of 8 (`vsrlab_lanes::avx512`), else AVX2 registers where the CPU has
//! them and N is a multiple of 4 (`vsrlab_lanes::avx`), else plain arrays, the same bits in every
//! form. Tests hold every lane to a scalar world's bits, with and without collisions, in each
//! form.

use crate::collision_lanes::{ColliderLanes, CollisionLanes};
use crate::lanes::V3;
use crate::link_lanes::{EndLanes, LinkLanes};
use crate::voxel::rest_edge;
use crate::voxel_lanes::{VoxelLanes, VoxelShared};
use crate::world::{VoxelId, World, DIVERGED_STRAIN};
use crate::Physics3dError;
use glam::DVec3;
use std::sync::Arc;
#[cfg(target_arch = "x86_64")]
use vsrlab_lanes::avx::Avx;
#[cfg(target_arch = "x86_64")]
use vsrlab_lanes::avx512::Avx512;
use vsrlab_lanes::{F64s, LaneMask, Lanes};

/// One voxel's parts: what the lanes share, and each lane's state.
#[derive(Debug, Clone)]
struct Voxel<L: Lanes> {
    shared: VoxelShared,
    lanes: VoxelLanes<L>,
    /// Its links (link index, whether it is the negative end), in the order forces are summed.
    links: Vec<(usize, bool)>,
    external_force: DVec3,
    external_moment: DVec3,
}

/// N episodes of one body, stepped together.
#[derive(Debug, Clone)]
pub struct WorldLanes<const N: usize> {
    engine: Engine<N>,
}

/// The lanes' number type: AVX-512 or AVX2 registers where the CPU has them, plain arrays
/// elsewhere.
#[derive(Debug, Clone)]
enum Engine<const N: usize> {
    Portable(Laned<F64s<N>>),
    #[cfg(target_arch = "x86_64")]
    Avx(Laned<Avx<N>>),
    #[cfg(target_arch = "x86_64")]
    Avx512(Laned<Avx512<N>>),
}

/// The world's state in lanes of type `L`.
#[derive(Debug, Clone)]
struct Laned<L: Lanes> {
    voxels: Vec<Voxel<L>>,
    links: Vec<LinkLanes<L>>,
    /// Each link's negative and positive voxel.
    ends_of: Vec<(usize, usize)>,
    ends: Vec<EndLanes<L>>,
    lattice: f64,
    rests_stale: bool,
    steps: u64,
    /// Voxel–voxel collisions, when the world has them, and each voxel as they see it.
    collisions: Option<CollisionLanes<L>>,
    colliders: Vec<ColliderLanes<L>>,
    /// Each lane's divergence, the first: (steps its episode took before, voxel), as
    /// `World::step` names it.
    diverged: Vec<Option<(u64, usize)>>,
    /// The step at which each lane's episode started (0, or when it was restarted).
    started: Vec<u64>,
    /// Every lane's voxels and links as they were before the first step, which a restarted lane
    /// copies.
    first: Arc<FirstState<L>>,
}

/// A laned world's voxel and link states before its first step.
#[derive(Debug)]
struct FirstState<L: Lanes> {
    voxels: Vec<VoxelLanes<L>>,
    links: Vec<LinkLanes<L>>,
}

impl<const N: usize> WorldLanes<N> {
    /// N copies of `world` as it is now: its voxels at rest at their lattice positions (a world
    /// that has not stepped), its links, loads and settings. Refuses a world that has stepped.
    pub fn of(world: &World) -> Result<WorldLanes<N>, Physics3dError> {
        #[cfg(target_arch = "x86_64")]
        if N.is_multiple_of(8) && vsrlab_lanes::avx512::available() {
            return Ok(WorldLanes {
                engine: Engine::Avx512(Laned::of(world)?),
            });
        }
        #[cfg(target_arch = "x86_64")]
        if N.is_multiple_of(4) && vsrlab_lanes::avx::available() {
            return WorldLanes::avx2(world);
        }
        WorldLanes::portable(world)
    }

    /// As [`WorldLanes::of`], in AVX2 registers whatever else the CPU has (the tests compare
    /// every form). The CPU must have AVX2 and N must be a multiple of 4.
    #[cfg(target_arch = "x86_64")]
    pub(crate) fn avx2(world: &World) -> Result<WorldLanes<N>, Physics3dError> {
        assert!(N.is_multiple_of(4) && vsrlab_lanes::avx::available());
        Ok(WorldLanes {
            engine: Engine::Avx(Laned::of(world)?),
        })
    }

    /// As [`WorldLanes::of`], in plain arrays whatever the CPU (the tests compare both forms).
    pub(crate) fn portable(world: &World) -> Result<WorldLanes<N>, Physics3dError> {
        Ok(WorldLanes {
            engine: Engine::Portable(Laned::of(world)?),
        })
    }

    /// Sets voxel `v`'s temperature in lane `lane` (its rest edge, and its links' rest lengths
    /// at the next step), as `World::set_temperature`.
    pub fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64) {
        self.state_mut().set_temperature(v, lane, temperature);
    }

    /// Sets voxel `v`'s temperature in every lane at once, as [`WorldLanes::set_temperature`].
    pub fn set_temperatures(&mut self, v: VoxelId, temperatures: [f64; N]) {
        for (lane, t) in temperatures.into_iter().enumerate() {
            self.set_temperature(v, lane, t);
        }
    }

    /// One step of `dt` seconds in every lane, compiled for the widest vector unit this CPU has
    /// (AVX-512, AVX2, or portable), the same bits on each. A lane that diverges (as
    /// `World::step` finds it: a link strained 100-fold, or a voxel state not finite) is kept in
    /// [`WorldLanes::diverged`] and steps on without touching the other lanes; an error here is
    /// about `dt` only.
    pub fn step(&mut self, dt: f64) -> Result<(), Physics3dError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Physics3dError::Invalid(format!(
                "dt: must be a finite number > 0, got {dt}"
            )));
        }
        match &mut self.engine {
            Engine::Portable(w) => w.step_lanes(dt),
            #[cfg(target_arch = "x86_64")]
            Engine::Avx(w) => {
                if is_x86_feature_detected!("avx512f") {
                    // SAFETY: the CPU supports AVX-512F (and AVX2: `Engine::Avx` was chosen)
                    unsafe { step_avx512(w, dt) };
                } else {
                    // SAFETY: the CPU supports AVX2 (`Engine::Avx` was chosen for it)
                    unsafe { step_avx2(w, dt) };
                }
            }
            #[cfg(target_arch = "x86_64")]
            // SAFETY: the CPU supports AVX-512F (`Engine::Avx512` was chosen for it)
            Engine::Avx512(w) => unsafe { step_avx512_wide(w, dt) },
        }
        Ok(())
    }

    /// The error `World::step` gave in lane `lane` when that lane diverged (its first), if it did.
    pub fn diverged(&self, lane: usize) -> Option<Physics3dError> {
        let diverged = self.state().diverged(lane);
        diverged.map(|(step, voxel)| Physics3dError::Diverged { step, voxel })
    }

    /// Starts lane `lane` over: its state becomes the world's before the first step (temperatures
    /// included), as a fresh episode of the same world, while the other lanes step on. This is
    /// how a population refills a lane whose episode ended early.
    pub fn restart(&mut self, lane: usize) {
        self.state_mut().restart(lane);
    }

    /// Voxel `v`'s centre in lane `lane` (m).
    pub fn position(&self, v: VoxelId, lane: usize) -> DVec3 {
        self.state().position(v, lane)
    }

    /// Voxel `v`'s velocity in lane `lane` (m/s), as `World::velocity`.
    pub fn velocity(&self, v: VoxelId, lane: usize) -> DVec3 {
        self.state().velocity(v, lane)
    }

    /// Whether voxel `v` reaches into the floor in lane `lane`, as `World::touches_floor`.
    pub fn touches_floor(&self, v: VoxelId, lane: usize) -> bool {
        self.state().touches_floor(v, lane)
    }

    /// Voxel `v`'s orientation in lane `lane`.
    pub fn orientation(&self, v: VoxelId, lane: usize) -> glam::DQuat {
        self.state().orientation(v, lane)
    }

    /// Whether voxel `v` touched another voxel in lane `lane` in the last step (as
    /// `World::touches_voxel`).
    pub fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool {
        self.state().touches_voxel(v, lane)
    }

    /// The pairs of voxels that touched in lane `lane` in the last step (not linked; the lower
    /// index first, in `World::contacts`'s order).
    pub fn contacts(&self, lane: usize) -> impl Iterator<Item = (VoxelId, VoxelId)> + '_ {
        let state = self.state();
        (0..state.contact_count()).filter_map(move |i| state.contact(i, lane))
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.state().voxel_count()
    }

    /// The state, whichever number type its lanes have (everything but the step, which is
    /// compiled for each).
    fn state(&self) -> &dyn LaneState {
        match &self.engine {
            Engine::Portable(w) => w,
            #[cfg(target_arch = "x86_64")]
            Engine::Avx(w) => w,
            #[cfg(target_arch = "x86_64")]
            Engine::Avx512(w) => w,
        }
    }

    /// [`WorldLanes::state`], to change.
    fn state_mut(&mut self) -> &mut dyn LaneState {
        match &mut self.engine {
            Engine::Portable(w) => w,
            #[cfg(target_arch = "x86_64")]
            Engine::Avx(w) => w,
            #[cfg(target_arch = "x86_64")]
            Engine::Avx512(w) => w,
        }
    }
}

/// What the public interface reads and sets of a laned world, the same for every number type.
trait LaneState {
    fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64);
    fn diverged(&self, lane: usize) -> Option<(u64, usize)>;
    fn restart(&mut self, lane: usize);
    fn position(&self, v: VoxelId, lane: usize) -> DVec3;
    fn velocity(&self, v: VoxelId, lane: usize) -> DVec3;
    fn touches_floor(&self, v: VoxelId, lane: usize) -> bool;
    fn orientation(&self, v: VoxelId, lane: usize) -> glam::DQuat;
    fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool;
    fn contact_count(&self) -> usize;
    /// The `i`-th pair that touched in some lane in the last step, if it touched in `lane`.
    fn contact(&self, i: usize, lane: usize) -> Option<(VoxelId, VoxelId)>;
    fn voxel_count(&self) -> usize;
}

/// The AVX2 step.
///
/// # Safety
/// The CPU must support AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn step_avx2<const N: usize>(w: &mut Laned<Avx<N>>, dt: f64) {
    w.step_lanes(dt)
}

/// The AVX2 step compiled with AVX-512 available (twice the registers).
///
/// # Safety
/// The CPU must support AVX2 and AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f")]
unsafe fn step_avx512<const N: usize>(w: &mut Laned<Avx<N>>, dt: f64) {
    w.step_lanes(dt)
}

/// The AVX-512 step: eight lanes per register.
///
/// # Safety
/// The CPU must support AVX-512F.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,avx512f")]
unsafe fn step_avx512_wide<const N: usize>(w: &mut Laned<Avx512<N>>, dt: f64) {
    w.step_lanes(dt)
}

impl<L: Lanes> Laned<L> {
    fn of(world: &World) -> Result<Laned<L>, Physics3dError> {
        let (voxels, links, settings) = world.parts();
        if world.steps() > 0 {
            return Err(Physics3dError::Invalid(
                "a laned copy starts from a world that has not stepped".into(),
            ));
        }
        let voxels: Vec<Voxel<L>> = voxels
            .into_iter()
            .map(|(shared, size, links, external_force, external_moment)| Voxel {
                lanes: VoxelLanes::at_rest(shared.home, size),
                shared,
                links,
                external_force,
                external_moment,
            })
            .collect();
        let ends_of: Vec<(usize, usize)> = links.iter().map(|l| (l.0, l.1)).collect();
        let links: Vec<LinkLanes<L>> = links
            .into_iter()
            .map(|(neg, pos, axis, k, area)| {
                let rest = (voxels[neg].lanes.size + voxels[pos].lanes.size) * 0.5;
                LinkLanes::new(axis, k, area, rest)
            })
            .collect();
        let ends = voxels
            .iter()
            .map(|v| EndLanes {
                pos: v.lanes.pos,
                orient: v.lanes.orient,
                damping: L::splat(0.0),
            })
            .collect();
        let collisions = settings.collisions.then(|| {
            let surface: Vec<usize> = (0..voxels.len()).filter(|&v| voxels[v].links.len() < 6).collect();
            let fixed = surface
                .iter()
                .map(|&v| voxels[v].shared.fixed.iter().all(|&f| f))
                .collect();
            CollisionLanes::new(voxels.len(), surface, fixed, ends_of.clone())
        });
        let colliders = voxels
            .iter()
            .map(|v| ColliderLanes {
                pos: v.lanes.pos,
                velocity: V3::splat(DVec3::ZERO),
                size: v.lanes.size,
                stiffness: v.shared.constants.floor_stiffness,
                damping: v.shared.material.collision_damping * v.shared.constants.linear_damping,
            })
            .collect();
        let first = Arc::new(FirstState {
            voxels: voxels.iter().map(|v| v.lanes.clone()).collect(),
            links: links.clone(),
        });
        Ok(Laned {
            voxels,
            links,
            ends_of,
            ends,
            lattice: settings.voxel_size,
            rests_stale: false,
            steps: 0,
            collisions,
            colliders,
            diverged: vec![None; L::LANES],
            started: vec![0; L::LANES],
            first,
        })
    }

    /// The step itself, inlined into each of the compiled forms above.
    #[inline(always)]
    fn step_lanes(&mut self, dt: f64) {
        if self.rests_stale {
            for (link, &(neg, pos)) in self.links.iter_mut().zip(&self.ends_of) {
                link.rest = (self.voxels[neg].lanes.size + self.voxels[pos].lanes.size) * 0.5;
            }
            self.rests_stale = false;
        }
        for (end, v) in self.ends.iter_mut().zip(&self.voxels) {
            let zeta = v.shared.material.internal_damping;
            let factor = 2.0 * v.shared.constants.sqrt_mass * zeta;
            let dt_prev = v.lanes.dt_prev;
            *end = EndLanes {
                pos: v.lanes.pos,
                orient: v.lanes.orient,
                damping: L::select(dt_prev.gt(L::splat(0.0)), L::splat(factor) / dt_prev, L::splat(0.0)),
            };
        }
        let limit = L::splat(DIVERGED_STRAIN);
        for l in 0..self.links.len() {
            let (neg, pos) = self.ends_of[l];
            let link = &mut self.links[l];
            link.update(&self.ends[neg], &self.ends[pos]);
            let strain = link.strain;
            let bad = strain.ne(strain).or(strain.abs().gt(limit));
            if bad.any() {
                self.mark_diverged(bad, neg);
            }
        }
        let zero = V3::splat(DVec3::ZERO);
        if let Some(collisions) = &mut self.collisions {
            for i in 0..self.colliders.len() {
                let v = &self.voxels[i];
                let mass = L::splat(v.shared.constants.mass);
                let m = v.lanes.momentum;
                let collider = &mut self.colliders[i];
                collider.pos = v.lanes.pos;
                collider.velocity = V3 {
                    x: m.x / mass,
                    y: m.y / mass,
                    z: m.z / mass,
                };
                collider.size = v.lanes.size;
            }
            collisions.add_forces(&self.colliders, self.lattice);
        }
        for i in 0..self.voxels.len() {
            let (mut force, mut moment) = (zero, zero);
            let v = &self.voxels[i];
            for &(l, is_neg) in &v.links {
                let link = &self.links[l];
                let (f, m) = match is_neg {
                    true => (link.force_neg, link.moment_neg),
                    false => (link.force_pos, link.moment_pos),
                };
                force = force.add(f);
                moment = moment.add(m);
            }
            let (external_force, external_moment) = (V3::splat(v.external_force), V3::splat(v.external_moment));
            let contact = match &self.collisions {
                Some(c) => c.forces[i],
                None => zero,
            };
            let v = &mut self.voxels[i];
            v.lanes
                .step(&v.shared, force, moment, contact, external_force, external_moment, dt);
        }
        for i in 0..self.voxels.len() {
            // a sum of each value times zero is NaN exactly where some value is NaN or infinite
            let l = &self.voxels[i].lanes;
            let values = [
                l.pos.x,
                l.pos.y,
                l.pos.z,
                l.momentum.x,
                l.momentum.y,
                l.momentum.z,
                l.angular_momentum.x,
                l.angular_momentum.y,
                l.angular_momentum.z,
                l.orient.x,
                l.orient.y,
                l.orient.z,
                l.orient.w,
            ];
            let mut sum = L::splat(0.0);
            for x in values {
                sum = sum + x * 0.0;
            }
            let bad = sum.ne(sum);
            if bad.any() {
                self.mark_diverged(bad, i);
            }
        }
        self.steps += 1;
    }

    /// Keeps, for each lane in `bad` that had not diverged yet, this step and `voxel`.
    #[cold]
    fn mark_diverged(&mut self, bad: L::Mask, voxel: usize) {
        for (lane, diverged) in self.diverged.iter_mut().enumerate() {
            if bad.get(lane) && diverged.is_none() {
                *diverged = Some((self.steps - self.started[lane], voxel));
            }
        }
    }
}

impl<L: Lanes> LaneState for Laned<L> {
    fn set_temperature(&mut self, v: VoxelId, lane: usize, temperature: f64) {
        let voxel = &mut self.voxels[v.0];
        voxel
            .lanes
            .size
            .set(lane, rest_edge(self.lattice, voxel.shared.material.cte, temperature));
        self.rests_stale |= !voxel.links.is_empty();
    }

    fn diverged(&self, lane: usize) -> Option<(u64, usize)> {
        self.diverged[lane]
    }

    fn restart(&mut self, lane: usize) {
        for (voxel, first) in self.voxels.iter_mut().zip(&self.first.voxels) {
            voxel.lanes.copy_lane(lane, first);
        }
        for (link, first) in self.links.iter_mut().zip(&self.first.links) {
            link.copy_lane(lane, first);
        }
        if let Some(collisions) = &mut self.collisions {
            collisions.forget_lane(lane);
        }
        self.diverged[lane] = None;
        self.started[lane] = self.steps;
    }

    fn position(&self, v: VoxelId, lane: usize) -> DVec3 {
        self.voxels[v.0].lanes.pos.lane(lane)
    }

    fn orientation(&self, v: VoxelId, lane: usize) -> glam::DQuat {
        self.voxels[v.0].lanes.orient.lane(lane)
    }

    fn voxel_count(&self) -> usize {
        self.voxels.len()
    }

    fn velocity(&self, v: VoxelId, lane: usize) -> DVec3 {
        let voxel = &self.voxels[v.0];
        voxel.lanes.momentum.lane(lane) / voxel.shared.constants.mass
    }

    fn touches_floor(&self, v: VoxelId, lane: usize) -> bool {
        let voxel = &self.voxels[v.0];
        let s = self.lattice;
        voxel.shared.floor && voxel.lanes.size.get(lane) / 2.0 - s / 2.0 - voxel.lanes.pos.z.get(lane) >= 0.0
    }

    fn touches_voxel(&self, v: VoxelId, lane: usize) -> bool {
        self.collisions.as_ref().is_some_and(|c| c.touching[v.0].get(lane))
    }

    fn contact_count(&self) -> usize {
        self.collisions.as_ref().map_or(0, |c| c.contacts.len())
    }

    fn contact(&self, i: usize, lane: usize) -> Option<(VoxelId, VoxelId)> {
        let (a, b, hit) = self.collisions.as_ref()?.contacts[i];
        hit.get(lane).then_some((VoxelId(a), VoxelId(b)))
    }
}

/// A 3 × 2 × 2 block less one voxel on the floor, the affordance study's material, voxel–voxel
/// collisions on or off: the body of the tests and of [`benchmark`].
#[cfg(any(test, feature = "bench"))]
fn block_with(collisions: bool) -> World {
    let settings = crate::world::WorldSettings {
        collisions,
        ..crate::world::WorldSettings::default()
    };
    let mut w = World::new(settings).expect("valid settings");
    let m = w.add_material(crate::Material::affordance()).expect("valid material");
    for z in 0..2 {
        for y in 0..2 {
            for x in 0..3 {
                if (x, y, z) != (2, 1, 1) {
                    w.add_voxel(m, [x, y, z]).expect("free index");
                }
            }
        }
    }
    w
}

/// The argument of the sine of voxel `v`'s gait in lane `lane` at time `t`.
#[cfg(any(test, feature = "bench"))]
fn gait_angle(v: usize, lane: usize, t: f64) -> f64 {
    let phase = v as f64 * 0.7 + lane as f64 * 1.3;
    2.0 * std::f64::consts::PI * (5.0 + lane as f64) * t + phase
}

/// The temperature of voxel `v` in lane `lane` at time `t`: a gait of its own per lane.
#[cfg(any(test, feature = "bench"))]
fn gait(v: usize, lane: usize, t: f64) -> f64 {
    14.0 * vsrlab_lanes::sin(gait_angle(v, lane, t))
}

/// [`gait`] in every lane at once (the same bits).
#[cfg(any(test, feature = "bench"))]
#[inline(always)]
fn gait_lanes<const N: usize>(v: usize, t: f64) -> [f64; N] {
    (14.0 * F64s(std::array::from_fn(|lane| gait_angle(v, lane, t))).sin()).0
}

#[cfg(feature = "bench")]
pub use bench::benchmark;

/// The timings of `--example lanes3d` (feature `bench`: the 8-lane and AVX-512 forms are
/// compiled only for it).
#[cfg(feature = "bench")]
mod bench {
    use super::*;

    /// Times `steps` steps of the block, voxel–voxel collisions on or off (`--example lanes3d`):
    /// nanoseconds per voxel·step and episode for a scalar world and for one laned world of N
    /// episodes, N = 4 and 8. Returns `(scalar, 4 lanes, 8 lanes)`.
    pub fn benchmark(steps: usize, collisions: bool) -> (f64, f64, f64) {
        (
            time_scalar(steps, collisions),
            time_lanes::<4>(steps, collisions),
            time_lanes::<8>(steps, collisions),
        )
    }

    fn time_scalar(steps: usize, collisions: bool) -> f64 {
        let mut w = block_with(collisions);
        let (n, dt) = (w.voxel_count(), w.recommended_time_step());
        let start = std::time::Instant::now();
        for step in 0..steps {
            for v in 0..n {
                w.set_temperature(crate::world::VoxelId(v), gait(v, 0, step as f64 * dt));
            }
            if w.step(dt).is_err() {
                break;
            }
        }
        std::hint::black_box(w.position(crate::world::VoxelId(0)));
        start.elapsed().as_secs_f64() * 1e9 / (steps * n) as f64
    }

    fn time_lanes<const N: usize>(steps: usize, collisions: bool) -> f64 {
        let w = block_with(collisions);
        let (n, dt) = (w.voxel_count(), w.recommended_time_step());
        let mut laned = WorldLanes::<N>::of(&w).expect("a world that has not stepped");
        let start = std::time::Instant::now();
        step_all(&mut laned, steps, dt);
        std::hint::black_box(laned.position(crate::world::VoxelId(0), 0));
        start.elapsed().as_secs_f64() * 1e9 / (steps * n * N) as f64
    }

    /// The laned steps, compiled for the best vector unit this CPU has (the same bits on each).
    fn step_all<const N: usize>(laned: &mut WorldLanes<N>, steps: usize, dt: f64) {
        #[cfg(target_arch = "x86_64")]
        {
            if is_x86_feature_detected!("avx512f") {
                // SAFETY: the CPU supports AVX-512F.
                return unsafe { step_all_avx512(laned, steps, dt) };
            }
            if is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2.
                return unsafe { step_all_avx2(laned, steps, dt) };
            }
        }
        step_all_portable(laned, steps, dt);
    }

    #[inline(always)]
    fn step_all_portable<const N: usize>(laned: &mut WorldLanes<N>, steps: usize, dt: f64) {
        let n = laned.voxel_count();
        for step in 0..steps {
            for v in 0..n {
                laned.set_temperatures(crate::world::VoxelId(v), gait_lanes(v, step as f64 * dt));
            }
            if laned.step(dt).is_err() {
                break;
            }
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn step_all_avx2<const N: usize>(laned: &mut WorldLanes<N>, steps: usize, dt: f64) {
        step_all_portable(laned, steps, dt);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn step_all_avx512<const N: usize>(laned: &mut WorldLanes<N>, steps: usize, dt: f64) {
        step_all_portable(laned, steps, dt);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::VoxelId;

    /// Eight lanes: one AVX-512 register, two AVX2 registers.
    const LANES: usize = 8;

    /// How a test builds its laned world: as `WorldLanes::of` chooses (AVX-512 on CPUs that have
    /// it), in AVX2 registers, or in plain arrays.
    type Make = fn(&World) -> Result<WorldLanes<LANES>, Physics3dError>;

    /// Every form this CPU can run, each run by `test` (the same bits are asked of each).
    fn in_every_form(test: fn(Make)) {
        test(WorldLanes::of);
        #[cfg(target_arch = "x86_64")]
        if vsrlab_lanes::avx::available() {
            test(WorldLanes::avx2);
        }
        test(WorldLanes::portable);
    }

    #[test]
    fn every_lane_of_a_laned_world_gives_a_scalar_worlds_bits() {
        in_every_form(every_lane_of_a_laned_world_gives_a_scalar_worlds_bits_in);
    }

    fn every_lane_of_a_laned_world_gives_a_scalar_worlds_bits_in(make: Make) {
        let mut scalar: Vec<World> = (0..LANES).map(|_| block_with(false)).collect();
        let mut laned = make(&scalar[0]).unwrap();
        let dt = scalar[0].recommended_time_step();
        let n = laned.voxel_count();
        let mut moved = 0.0f64;
        for step in 0..4000 {
            let t = step as f64 * dt;
            for (lane, w) in scalar.iter_mut().enumerate() {
                for v in 0..n {
                    let temperature = gait(v, lane, t);
                    w.set_temperature(VoxelId(v), temperature);
                    match step % 2 {
                        0 => laned.set_temperature(VoxelId(v), lane, temperature),
                        _ => assert_eq!(gait_lanes::<LANES>(v, t)[lane].to_bits(), temperature.to_bits()),
                    }
                }
                w.step(dt).unwrap();
            }
            if step % 2 == 1 {
                for v in 0..n {
                    laned.set_temperatures(VoxelId(v), gait_lanes(v, t));
                }
            }
            laned.step(dt).unwrap();
            for (lane, w) in scalar.iter().enumerate() {
                for v in 0..n {
                    let what = format!("step {step}, lane {lane}, voxel {v}");
                    let (p, q) = (laned.position(VoxelId(v), lane), laned.orientation(VoxelId(v), lane));
                    assert_eq!(
                        p.to_array().map(f64::to_bits),
                        w.position(VoxelId(v)).to_array().map(f64::to_bits),
                        "{what}"
                    );
                    assert_eq!(
                        q.to_array().map(f64::to_bits),
                        w.orientation(VoxelId(v)).to_array().map(f64::to_bits),
                        "{what}"
                    );
                }
            }
        }
        for (lane, w) in scalar.iter().enumerate() {
            moved = moved.max(w.displacement(VoxelId(0)).length());
            assert_eq!(laned.position(VoxelId(0), lane), w.position(VoxelId(0)));
        }
        // the gaits moved the body (not a world at rest compared with itself)
        assert!(moved > 1e-4, "{moved}");
    }

    #[test]
    fn a_lane_that_diverges_is_named_as_the_scalar_world_names_it_and_the_others_step_on() {
        in_every_form(a_lane_that_diverges_is_named_as_the_scalar_world_names_it_and_the_others_step_on_in);
    }

    fn a_lane_that_diverges_is_named_as_the_scalar_world_names_it_and_the_others_step_on_in(make: Make) {
        let mut scalar: Vec<World> = (0..LANES).map(|_| block_with(true)).collect();
        let mut laned = make(&scalar[0]).unwrap();
        let dt = scalar[0].recommended_time_step();
        let n = laned.voxel_count();
        let mut errors: Vec<Option<Physics3dError>> = vec![None; LANES];
        for step in 0..400 {
            let t = step as f64 * dt;
            for (lane, w) in scalar.iter_mut().enumerate() {
                for v in 0..n {
                    // lane 2 heats voxel 3 without bound from step 100
                    let runaway = lane == 2 && v == 3 && step >= 100;
                    let temperature = if runaway { 1e3 * step as f64 } else { gait(v, lane, t) };
                    laned.set_temperature(VoxelId(v), lane, temperature);
                    if errors[lane].is_none() {
                        w.set_temperature(VoxelId(v), temperature);
                    }
                }
                if errors[lane].is_none() {
                    errors[lane] = w.step(dt).err();
                }
            }
            laned.step(dt).unwrap();
            for (lane, w) in scalar.iter().enumerate() {
                assert_eq!(laned.diverged(lane), errors[lane], "step {step}, lane {lane}");
                if errors[lane].is_none() {
                    for v in 0..n {
                        assert_eq!(
                            laned.velocity(VoxelId(v), lane),
                            w.velocity(VoxelId(v)),
                            "step {step}, lane {lane}"
                        );
                        assert_eq!(laned.touches_floor(VoxelId(v), lane), w.touches_floor(VoxelId(v)));
                    }
                }
            }
        }
        assert!(matches!(errors[2], Some(Physics3dError::Diverged { .. })), "{errors:?}");
        assert!(errors.iter().filter(|e| e.is_some()).count() == 1, "{errors:?}");
        assert!(laned.step(0.0).is_err() && laned.step(f64::NAN).is_err());
    }

    #[test]
    fn a_restarted_lane_steps_as_a_fresh_world_and_the_others_step_on() {
        in_every_form(a_restarted_lane_steps_as_a_fresh_world_and_the_others_step_on_in);
    }

    /// Lane 2 heats a voxel without bound 100 steps into each of its episodes and is restarted
    /// whenever it diverges; lane 1 is restarted once, mid-stride and in contact. Every lane must
    /// keep the bits of its own scalar world (a fresh one from each restart), contacts and
    /// divergences included.
    fn a_restarted_lane_steps_as_a_fresh_world_and_the_others_step_on_in(make: Make) {
        let mut scalar: Vec<World> = (0..LANES).map(|_| block_and_falling_voxel()).collect();
        let mut laned = make(&scalar[0]).unwrap();
        let dt = scalar[0].recommended_time_step();
        let n = laned.voxel_count();
        let mut errors: Vec<Option<Physics3dError>> = vec![None; LANES];
        let mut started = [0usize; LANES];
        let (mut restarts, mut touches) = (0, 0);
        for step in 0..3000 {
            let t = step as f64 * dt;
            for (lane, w) in scalar.iter_mut().enumerate() {
                let own = step - started[lane];
                for v in 0..n {
                    let runaway = lane == 2 && v == 3 && own >= 100;
                    let temperature = match runaway {
                        true => 1e3 * own as f64,
                        false => 1.5 * gait(v, lane, t) + 10.0 * lane as f64,
                    };
                    laned.set_temperature(VoxelId(v), lane, temperature);
                    w.set_temperature(VoxelId(v), temperature);
                }
                errors[lane] = w.step(dt).err();
            }
            laned.step(dt).unwrap();
            for (lane, w) in scalar.iter().enumerate() {
                let what = format!("step {step}, lane {lane}");
                assert_eq!(laned.diverged(lane), errors[lane], "{what}");
                if errors[lane].is_some() {
                    continue;
                }
                let contacts: Vec<_> = laned.contacts(lane).collect();
                assert_eq!(contacts, w.contacts().collect::<Vec<_>>(), "{what}");
                touches += contacts.len();
                for v in 0..n {
                    assert_eq!(
                        laned.touches_voxel(VoxelId(v), lane),
                        w.touches_voxel(VoxelId(v)),
                        "{what}"
                    );
                    assert_eq!(
                        laned.position(VoxelId(v), lane).to_array().map(f64::to_bits),
                        w.position(VoxelId(v)).to_array().map(f64::to_bits),
                        "{what}, voxel {v}"
                    );
                    assert_eq!(
                        laned.orientation(VoxelId(v), lane).to_array().map(f64::to_bits),
                        w.orientation(VoxelId(v)).to_array().map(f64::to_bits),
                        "{what}, voxel {v}"
                    );
                }
            }
            for lane in [1, 2] {
                if errors[lane].is_some() || (lane == 1 && step == 1500) {
                    laned.restart(lane);
                    scalar[lane] = block_and_falling_voxel();
                    started[lane] = step + 1;
                    restarts += 1;
                }
            }
        }
        // lane 2 diverged and restarted again and again; lanes touched
        assert!(
            restarts >= 3 && touches > 100,
            "{restarts} restarts, {touches} contacts"
        );
    }

    /// Property: random connected bodies (2³ to 5³ boxes, 60 % filled, collisions on), each lane
    /// with its own random temperatures redrawn every 0.01 s: no lane diverges, every lane's state
    /// stays finite, and one lane ends on a scalar world's bits.
    #[test]
    fn random_bodies_under_random_actuation_stay_finite_in_every_lane() {
        in_every_form(random_bodies_under_random_actuation_stay_finite_in_every_lane_in);
    }

    fn random_bodies_under_random_actuation_stay_finite_in_every_lane_in(make: Make) {
        let mut next = crate::validation::uniform(0x1A2E);
        for side in 2..6 {
            let cells = crate::validation::random_piece(&mut next, side, 0.6);
            let mut w = World::new(crate::world::WorldSettings::default()).unwrap();
            let m = w.add_material(crate::Material::affordance()).unwrap();
            let ids: Vec<VoxelId> = cells.iter().map(|&c| w.add_voxel(m, c).unwrap()).collect();
            let mut laned = make(&w).unwrap();
            let dt = 0.95 * w.recommended_time_step();
            let per_draw = (0.01 / dt) as usize;
            for step in 0..(0.1 / dt) as usize {
                if step % per_draw == 0 {
                    for &v in &ids {
                        let temperatures: [f64; LANES] = std::array::from_fn(|_| 14.4714 * (2.0 * next() - 1.0));
                        laned.set_temperatures(v, temperatures);
                        w.set_temperature(v, temperatures[LANES - 1]);
                    }
                }
                laned.step(dt).unwrap();
                w.step(dt).unwrap();
            }
            for lane in 0..LANES {
                assert_eq!(laned.diverged(lane), None, "{side}³ body, lane {lane}");
                for &v in &ids {
                    let (p, q) = (laned.position(v, lane), laned.orientation(v, lane));
                    assert!(p.is_finite() && q.is_finite() && laned.velocity(v, lane).is_finite());
                }
            }
            for &v in &ids {
                assert_eq!(laned.position(v, LANES - 1), w.position(v), "{side}³ body");
            }
        }
    }

    /// The block with collisions on and a loose voxel above it that falls onto it; each lane
    /// heats the voxels its own way, so contacts (the falling voxel, diagonal neighbours grown by
    /// heat) start and end at different steps in different lanes.
    fn block_and_falling_voxel() -> World {
        let mut w = block_with(true);
        w.add_voxel(0, [1, 0, 3]).unwrap();
        w
    }

    #[test]
    fn every_lane_of_a_laned_world_with_collisions_gives_a_scalar_worlds_bits() {
        in_every_form(every_lane_of_a_laned_world_with_collisions_gives_a_scalar_worlds_bits_in);
    }

    fn every_lane_of_a_laned_world_with_collisions_gives_a_scalar_worlds_bits_in(make: Make) {
        let mut scalar: Vec<World> = (0..LANES).map(|_| block_and_falling_voxel()).collect();
        let mut laned = make(&scalar[0]).unwrap();
        let dt = scalar[0].recommended_time_step();
        let n = laned.voxel_count();
        let (mut touches, mut split) = (0, 0);
        for step in 0..6000 {
            let t = step as f64 * dt;
            for (lane, w) in scalar.iter_mut().enumerate() {
                for v in 0..n {
                    let temperature = 1.5 * gait(v, lane, t) + 10.0 * lane as f64;
                    w.set_temperature(VoxelId(v), temperature);
                    laned.set_temperature(VoxelId(v), lane, temperature);
                }
                w.step(dt).unwrap();
            }
            laned.step(dt).unwrap();
            for v in 0..n {
                let lanes: Vec<bool> = (0..LANES).map(|l| laned.touches_voxel(VoxelId(v), l)).collect();
                touches += lanes.iter().filter(|&&t| t).count();
                split += usize::from(lanes.iter().any(|&t| t) && !lanes.iter().all(|&t| t));
                for (lane, w) in scalar.iter().enumerate() {
                    let what = format!("step {step}, lane {lane}, voxel {v}");
                    assert_eq!(lanes[lane], w.touches_voxel(VoxelId(v)), "{what}");
                    if v == 0 {
                        let contacts: Vec<_> = laned.contacts(lane).collect();
                        assert_eq!(contacts, w.contacts().collect::<Vec<_>>(), "{what}");
                    }
                    assert_eq!(
                        laned.position(VoxelId(v), lane).to_array().map(f64::to_bits),
                        w.position(VoxelId(v)).to_array().map(f64::to_bits),
                        "{what}"
                    );
                    assert_eq!(
                        laned.orientation(VoxelId(v), lane).to_array().map(f64::to_bits),
                        w.orientation(VoxelId(v)).to_array().map(f64::to_bits),
                        "{what}"
                    );
                }
            }
        }
        // contacts happened, and lanes disagreed on them (masked contact forces were exercised)
        assert!(touches > 100 && split > 100, "{touches} {split}");
    }
}
