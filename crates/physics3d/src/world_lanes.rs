//! A world of N episodes at once (issue 52, population lanes): the same body shape in every lane,
//! each lane with its own temperatures and so its own motion, stepped as `World::step` does, lane
//! by lane: every link from the state at the start of the step, then every voxel. Voxel–voxel
//! collisions are not laned yet, so a world with them is refused. A test holds every lane to a
//! scalar world's bits.

use crate::lanes::{F64s, Q, V3};
use crate::link_lanes::{EndLanes, LinkLanes};
use crate::voxel::rest_edge;
use crate::voxel_lanes::{VoxelLanes, VoxelShared};
use crate::world::{World, DIVERGED_STRAIN};
use crate::Physics3dError;
use glam::DVec3;

/// One voxel's parts: what the lanes share, and each lane's state.
#[derive(Debug, Clone)]
struct Voxel<const N: usize> {
    shared: VoxelShared,
    lanes: VoxelLanes<N>,
    /// Its links (link index, whether it is the negative end), in the order forces are summed.
    links: Vec<(usize, bool)>,
    external_force: DVec3,
    external_moment: DVec3,
}

/// N episodes of one body, stepped together.
#[derive(Debug, Clone)]
pub struct WorldLanes<const N: usize> {
    voxels: Vec<Voxel<N>>,
    links: Vec<LinkLanes<N>>,
    /// Each link's negative and positive voxel.
    ends_of: Vec<(usize, usize)>,
    ends: Vec<EndLanes<N>>,
    lattice: f64,
    rests_stale: bool,
    steps: u64,
}

impl<const N: usize> WorldLanes<N> {
    /// N copies of `world` as it is now: its voxels at rest at their lattice positions (a world
    /// that has not stepped), its links, loads and settings. Refuses a world with voxel–voxel
    /// collisions (not laned yet) or one that has stepped.
    pub fn of(world: &World) -> Result<WorldLanes<N>, Physics3dError> {
        let (voxels, links, settings) = world.parts();
        if settings.collisions {
            return Err(Physics3dError::Invalid(
                "collisions: voxel-voxel collisions do not run in lanes yet; turn them off".into(),
            ));
        }
        if world.steps() > 0 {
            return Err(Physics3dError::Invalid(
                "a laned copy starts from a world that has not stepped".into(),
            ));
        }
        let voxels: Vec<Voxel<N>> = voxels
            .into_iter()
            .map(|(shared, size, links, external_force, external_moment)| Voxel {
                lanes: VoxelLanes::at_rest(shared.home, size),
                shared,
                links,
                external_force,
                external_moment,
            })
            .collect();
        let ends_of = links.iter().map(|l| (l.0, l.1)).collect();
        let links = links
            .into_iter()
            .map(|(neg, pos, axis, k, area)| {
                let rest = 0.5 * (voxels[neg].lanes.size + voxels[pos].lanes.size);
                LinkLanes::new(axis, k, area, rest)
            })
            .collect();
        let ends = voxels
            .iter()
            .map(|v| EndLanes {
                pos: v.lanes.pos,
                orient: v.lanes.orient,
                damping: F64s::splat(0.0),
            })
            .collect();
        Ok(WorldLanes {
            voxels,
            links,
            ends_of,
            ends,
            lattice: settings.voxel_size,
            rests_stale: false,
            steps: 0,
        })
    }

    /// Sets voxel `v`'s temperature in lane `lane` (its rest edge, and its links' rest lengths
    /// at the next step), as `World::set_temperature`.
    pub fn set_temperature(&mut self, v: usize, lane: usize, temperature: f64) {
        let voxel = &mut self.voxels[v];
        voxel.lanes.size.0[lane] = rest_edge(self.lattice, voxel.shared.material.cte, temperature);
        self.rests_stale |= !voxel.links.is_empty();
    }

    /// One step of `dt` seconds in every lane; an error names the lane that diverged.
    pub fn step(&mut self, dt: f64) -> Result<(), Physics3dError> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Physics3dError::Invalid(format!(
                "dt: must be a finite number > 0, got {dt}"
            )));
        }
        if self.rests_stale {
            for (link, &(neg, pos)) in self.links.iter_mut().zip(&self.ends_of) {
                link.rest = 0.5 * (self.voxels[neg].lanes.size + self.voxels[pos].lanes.size);
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
                damping: F64s::select(dt_prev.gt(F64s::splat(0.0)), factor / dt_prev, F64s::splat(0.0)),
            };
        }
        for (l, (link, &(neg, pos))) in self.links.iter_mut().zip(&self.ends_of).enumerate() {
            link.update(&self.ends[neg], &self.ends[pos]);
            if let Some(lane) = (0..N).find(|&i| link.strain.0[i].is_nan() || link.strain.0[i].abs() > DIVERGED_STRAIN)
            {
                return Err(Physics3dError::Invalid(format!(
                    "lane {lane} diverged at step {} (link {l})",
                    self.steps
                )));
            }
        }
        let zero = V3::splat(DVec3::ZERO);
        for v in &mut self.voxels {
            let (mut force, mut moment) = (zero, zero);
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
            v.lanes
                .step(&v.shared, force, moment, zero, external_force, external_moment, dt);
        }
        self.steps += 1;
        Ok(())
    }

    /// Voxel `v`'s centre in lane `lane` (m).
    pub fn position(&self, v: usize, lane: usize) -> DVec3 {
        let p = &self.voxels[v].lanes.pos;
        DVec3::new(p.x.0[lane], p.y.0[lane], p.z.0[lane])
    }

    /// Voxel `v`'s orientation in lane `lane`.
    pub fn orientation(&self, v: usize, lane: usize) -> glam::DQuat {
        let q: &Q<N> = &self.voxels[v].lanes.orient;
        glam::DQuat::from_xyzw(q.x.0[lane], q.y.0[lane], q.z.0[lane], q.w.0[lane])
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.voxels.len()
    }
}

/// A 3 × 2 × 2 block less one voxel on the floor, the affordance study's material, collisions
/// off: the body of the test and of [`benchmark`].
fn block() -> World {
    let settings = crate::world::WorldSettings {
        collisions: false,
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

/// The temperature of voxel `v` in lane `lane` at time `t`: a gait of its own per lane.
fn gait(v: usize, lane: usize, t: f64) -> f64 {
    let phase = v as f64 * 0.7 + lane as f64 * 1.3;
    14.0 * (2.0 * std::f64::consts::PI * (5.0 + lane as f64) * t + phase).sin()
}

/// Times `steps` steps of the block (`--example lanes3d`): nanoseconds per voxel·step and episode
/// for N scalar worlds one after the other and for one laned world of N episodes, N = 4 and 8.
/// Returns `(scalar, 4 lanes, 8 lanes)`.
pub fn benchmark(steps: usize) -> (f64, f64, f64) {
    (time_scalar(steps), time_lanes::<4>(steps), time_lanes::<8>(steps))
}

fn time_scalar(steps: usize) -> f64 {
    let mut w = block();
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

fn time_lanes<const N: usize>(steps: usize) -> f64 {
    let w = block();
    let (n, dt) = (w.voxel_count(), w.recommended_time_step());
    let mut laned = WorldLanes::<N>::of(&w).expect("no collisions");
    let start = std::time::Instant::now();
    step_all(&mut laned, steps, dt);
    std::hint::black_box(laned.position(0, 0));
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
            for lane in 0..N {
                laned.set_temperature(v, lane, gait(v, lane, step as f64 * dt));
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::{VoxelId, WorldSettings};

    const LANES: usize = 4;

    #[test]
    fn every_lane_of_a_laned_world_gives_a_scalar_worlds_bits() {
        let mut scalar: Vec<World> = (0..LANES).map(|_| block()).collect();
        let mut laned = WorldLanes::<LANES>::of(&scalar[0]).unwrap();
        let dt = scalar[0].recommended_time_step();
        let n = laned.voxel_count();
        let mut moved = 0.0f64;
        for step in 0..4000 {
            let t = step as f64 * dt;
            for (lane, w) in scalar.iter_mut().enumerate() {
                for v in 0..n {
                    let temperature = gait(v, lane, t);
                    w.set_temperature(VoxelId(v), temperature);
                    laned.set_temperature(v, lane, temperature);
                }
                w.step(dt).unwrap();
            }
            laned.step(dt).unwrap();
            for (lane, w) in scalar.iter().enumerate() {
                for v in 0..n {
                    let what = format!("step {step}, lane {lane}, voxel {v}");
                    let (p, q) = (laned.position(v, lane), laned.orientation(v, lane));
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
            assert_eq!(laned.position(0, lane), w.position(VoxelId(0)));
        }
        // the gaits moved the body (not a world at rest compared with itself)
        assert!(moved > 1e-4, "{moved}");
        // collisions are refused, not ignored
        assert!(WorldLanes::<LANES>::of(&World::new(WorldSettings::default()).unwrap()).is_err());
    }
}
