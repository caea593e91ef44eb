//! A voxel of N episodes at once (issue 52, population lanes): the same voxel of one body shape
//! in every lane, each lane with its own state, integrated by the semi-implicit Euler step of
//! `World::step_voxel` (floor, Coulomb friction with its static state, fixed degrees of freedom)
//! lane by lane. Where the lanes' branches differ (touching the floor or not, static or sliding,
//! the rotation series), both ways are computed and each lane keeps its own. A test holds every
//! lane to the scalar world's bits.

use crate::lanes::{Q, V3};
use crate::material::{Material, VoxelConstants};
use crate::voxel::DofMask;
use glam::{DQuat, DVec3};
use vsrlab_lanes::{and, any, not, or, LaneMask, Lanes};

/// What every lane's copy of a voxel shares: its material, constants, fixed degrees of freedom
/// and lattice position, and the world's settings that the step reads.
#[derive(Debug, Clone)]
pub(crate) struct VoxelShared {
    pub material: Material,
    pub constants: VoxelConstants,
    pub fixed: DofMask,
    /// The lattice position (where fixed translations hold it).
    pub home: DVec3,
    pub lattice: f64,
    pub floor: bool,
    pub gravity: f64,
}

/// Each lane's state of one voxel.
#[derive(Debug, Clone)]
pub(crate) struct VoxelLanes<L: Lanes> {
    pub pos: V3<L>,
    pub orient: Q<L>,
    pub momentum: V3<L>,
    pub angular_momentum: V3<L>,
    pub is_static: L::Mask,
    pub dt_prev: L,
    /// Rest edge in each lane (its temperature's).
    pub size: L,
}

impl<L: Lanes> VoxelLanes<L> {
    /// The voxel at rest at `home`, static, in every lane.
    pub fn at_rest(home: DVec3, size: f64) -> Self {
        VoxelLanes {
            pos: V3::splat(home),
            orient: Q::splat(DQuat::IDENTITY),
            momentum: V3::splat(DVec3::ZERO),
            angular_momentum: V3::splat(DVec3::ZERO),
            is_static: L::Mask::splat(true),
            dt_prev: L::splat(0.0),
            size: L::splat(size),
        }
    }

    /// Sets lane `lane` to the state of a voxel of the scalar world.
    #[inline(always)]
    pub fn set_lane(&mut self, lane: usize, v: &crate::voxel::Voxel) {
        self.pos.set_lane(lane, v.pos);
        self.orient.set_lane(lane, v.orient);
        self.momentum.set_lane(lane, v.momentum);
        self.angular_momentum.set_lane(lane, v.angular_momentum);
        self.is_static.set(lane, v.is_static);
        self.dt_prev.set(lane, v.dt_prev);
        self.size.set(lane, v.size);
    }

    /// Sets lane `lane` to `from`'s lane `lane` (a lane restarted from the world's first state).
    pub fn copy_lane(&mut self, lane: usize, from: &Self) {
        self.pos.set_lane(lane, from.pos.lane(lane));
        self.orient.set_lane(lane, from.orient.lane(lane));
        self.momentum.set_lane(lane, from.momentum.lane(lane));
        self.angular_momentum.set_lane(lane, from.angular_momentum.lane(lane));
        self.is_static.set(lane, from.is_static.get(lane));
        self.dt_prev.set(lane, from.dt_prev.get(lane));
        self.size.set(lane, from.size.get(lane));
    }

    /// Writes lane `lane`'s state back to a voxel of the scalar world.
    #[inline(always)]
    pub fn write_lane(&self, lane: usize, v: &mut crate::voxel::Voxel) {
        v.pos = self.pos.lane(lane);
        v.orient = self.orient.lane(lane);
        v.momentum = self.momentum.lane(lane);
        v.angular_momentum = self.angular_momentum.lane(lane);
        v.is_static = self.is_static.get(lane);
        v.dt_prev = self.dt_prev.get(lane);
    }

    /// One step of `dt` with the summed link forces and moments (in the voxel's frame), the
    /// contact forces and the external loads of each lane, as `World::step_voxel`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn step(
        &mut self,
        v: &VoxelShared,
        link_force: V3<L>,
        link_moment: V3<L>,
        contact: V3<L>,
        external_force: V3<L>,
        external_moment: V3<L>,
        dt: f64,
    ) {
        let (m, c) = (&v.material, &v.constants);
        self.dt_prev = L::splat(dt);
        if v.fixed.iter().all(|&f| f) {
            self.pos = V3::splat(v.home);
            self.orient = Q::splat(DQuat::IDENTITY);
            self.momentum = V3::splat(DVec3::ZERO);
            self.angular_momentum = V3::splat(DVec3::ZERO);
            return;
        }
        let mass = L::splat(c.mass);
        let velocity = V3 {
            x: self.momentum.x / mass,
            y: self.momentum.y / mass,
            z: self.momentum.z / mass,
        };
        let inertia = L::splat(c.inertia);
        let omega = V3 {
            x: self.angular_momentum.x / inertia,
            y: self.angular_momentum.y / inertia,
            z: self.angular_momentum.z / inertia,
        };
        let gravity = V3::splat(DVec3::new(0.0, 0.0, -c.mass * v.gravity));
        let linear = L::splat(m.global_damping * c.linear_damping);
        let mut force = rotate(self.orient, link_force)
            .add(external_force)
            .sub(velocity.scale(linear))
            .add(gravity)
            .add(contact);
        let angular = L::splat(m.global_damping * c.angular_damping);
        let moment = rotate(self.orient, link_moment)
            .add(external_moment)
            .sub(omega.scale(angular));
        let zero = V3::splat(DVec3::ZERO);
        let (touching, friction) = match v.floor {
            true => self.floor(v, &mut force, velocity),
            false => (L::Mask::splat(false), zero),
        };
        self.momentum = self.momentum.add(force.scale(L::splat(dt)));
        let mut translation = V3 {
            x: self.momentum.x * dt / mass,
            y: self.momentum.y * dt / mass,
            z: self.momentum.z * dt / mass,
        };
        if any(touching) {
            let work = friction.x * translation.x + friction.y * translation.y;
            let kinetic = (self.momentum.x * self.momentum.x + self.momentum.y * self.momentum.y) / (2.0 * c.mass);
            let stops = and(touching, (kinetic + work).le(L::splat(0.0)));
            self.is_static = or(self.is_static, stops);
            let held = and(touching, self.is_static);
            let zero = L::splat(0.0);
            self.momentum.x = L::select(held, zero, self.momentum.x);
            self.momentum.y = L::select(held, zero, self.momentum.y);
            translation.x = L::select(held, zero, translation.x);
            translation.y = L::select(held, zero, translation.y);
        }
        self.pos = self.pos.add(translation);
        self.angular_momentum = self.angular_momentum.add(moment.scale(L::splat(dt)));
        let turn = V3 {
            x: self.angular_momentum.x * dt / inertia,
            y: self.angular_momentum.y * dt / inertia,
            z: self.angular_momentum.z * dt / inertia,
        };
        self.orient = from_rotation_vector(turn).mul(self.orient);
        self.hold_fixed(v);
    }

    /// The floor's force added to `force`, as `floor::floor_force` lane by lane: whether each
    /// lane touches, and the friction each lane got.
    #[inline(always)]
    fn floor(&mut self, v: &VoxelShared, force: &mut V3<L>, velocity: V3<L>) -> (L::Mask, V3<L>) {
        let (m, c) = (&v.material, &v.constants);
        let zero = L::splat(0.0);
        let penetration = self.size / 2.0 - v.lattice / 2.0 - self.pos.z;
        let touching = not(penetration.lt(zero));
        let was_static = self.is_static;
        let normal = L::splat(c.floor_stiffness) * penetration;
        let damping = m.collision_damping * c.linear_damping;
        force.z = L::select(touching, force.z + (normal - L::splat(damping) * velocity.z), force.z);
        // static lanes: the friction holds until the horizontal force exceeds μs N
        let limit = L::splat(m.static_friction) * normal;
        let breaks = (force.x * force.x + force.y * force.y).gt(limit * limit);
        // sliding lanes: kinetic friction against the horizontal velocity
        let speed = (velocity.x * velocity.x + velocity.y * velocity.y + zero * zero).sqrt();
        let slides = and(and(touching, not(was_static)), speed.gt(zero));
        let mut friction = V3 {
            x: zero,
            y: zero,
            z: zero,
        };
        if any(slides) {
            let pull = L::splat(-m.kinetic_friction) * normal;
            let kinetic = V3 {
                x: pull * velocity.x / speed,
                y: pull * velocity.y / speed,
                z: pull * zero / speed,
            };
            friction = V3::select(slides, kinetic, friction);
            *force = V3::select(slides, force.add(kinetic), *force);
        }
        self.is_static = and(touching, and(was_static, not(breaks)));
        (touching, friction)
    }

    /// Fixed translations back at the lattice position and fixed rotations undone, as the end
    /// of `World::step_voxel` (the same degrees of freedom in every lane).
    #[inline(always)]
    fn hold_fixed(&mut self, v: &VoxelShared) {
        let zero = L::splat(0.0);
        let pos = [&mut self.pos.x, &mut self.pos.y, &mut self.pos.z];
        let momentum = [&mut self.momentum.x, &mut self.momentum.y, &mut self.momentum.z];
        for (k, (p, m)) in pos.into_iter().zip(momentum).enumerate() {
            if v.fixed[k] {
                *p = L::splat(v.home[k]);
                *m = zero;
            }
        }
        let (rx, ry, rz) = (v.fixed[3], v.fixed[4], v.fixed[5]);
        if rx && ry && rz {
            self.orient = Q::splat(DQuat::IDENTITY);
            self.angular_momentum = V3::splat(DVec3::ZERO);
        } else if rx || ry || rz {
            let mut r = to_rotation_vector(self.orient);
            let rotation = [&mut r.x, &mut r.y, &mut r.z];
            let angular = [
                &mut self.angular_momentum.x,
                &mut self.angular_momentum.y,
                &mut self.angular_momentum.z,
            ];
            for (fixed, (r, a)) in [rx, ry, rz].into_iter().zip(rotation.into_iter().zip(angular)) {
                if fixed {
                    *r = zero;
                    *a = zero;
                }
            }
            self.orient = from_rotation_vector(r);
        }
    }
}

/// `quat::rotate` in every lane.
#[inline(always)]
fn rotate<L: Lanes>(q: Q<L>, v: V3<L>) -> V3<L> {
    crate::link_lanes::sandwich(q, v, q.conjugate())
}

/// `quat::from_rotation_vector` in every lane: the series near zero, sine and cosine beyond.
#[inline(always)]
fn from_rotation_vector<L: Lanes>(r: V3<L>) -> Q<L> {
    let h = V3 {
        x: r.x * 0.5,
        y: r.y * 0.5,
        z: r.z * 0.5,
    };
    let h2 = h.x * h.x + h.y * h.y + h.z * h.z;
    let series = (h2 * h2).lt(L::splat(5.328e-15));
    let one = L::splat(1.0);
    let (mut w, mut scale) = (one - h2 / 2.0, one - h2 / 6.0);
    if any(not(series)) {
        let a = h2.sqrt();
        let (sin, cos) = a.sin_cos();
        w = L::select(series, w, cos);
        scale = L::select(series, scale, sin / a);
    }
    Q {
        x: h.x * scale,
        y: h.y * scale,
        z: h.z * scale,
        w,
    }
}

/// `quat::to_rotation_vector` in every lane.
#[inline(always)]
fn to_rotation_vector<L: Lanes>(q: Q<L>) -> V3<L> {
    crate::link_lanes::to_rotation_vector(q)
}

/// Voxelyze's material with friction, thermal expansion and damping, so that every branch of
/// the floor is met (sticking, breaking free, sliding, stopping, leaving the floor).
#[cfg(any(test, feature = "bench"))]
fn bench_material() -> Material {
    Material {
        cte: 0.01,
        static_friction: 1.0,
        kinetic_friction: 0.5,
        global_damping: 0.01,
        collision_damping: 0.8,
        ..Material::voxelyze(1e6, 1000.0)
    }
}

#[cfg(feature = "bench")]
pub use bench::benchmark;

/// The timings of `--example lanes3d` (feature `bench`: the 8-lane and AVX-512 forms are
/// compiled only for it).
#[cfg(feature = "bench")]
mod bench {
    use super::*;

    /// Times voxel updates (`--example lanes3d`): nanoseconds per voxel update and episode for a
    /// one-voxel world of the scalar engine (its whole step) and for laned voxels of 1, 4 and 8
    /// episodes, each under sideways, lifting and twisting loads that make it slide, stick and hop.
    /// Returns `(scalar world, 1 lane, 4 lanes, 8 lanes)`.
    pub fn benchmark(steps: usize) -> (f64, f64, f64, f64) {
        let (world, one) = (time_world(steps), time_lanes::<vsrlab_lanes::F64s<1>>(steps));
        #[cfg(target_arch = "x86_64")]
        if vsrlab_lanes::avx::available() {
            let four = time_lanes::<vsrlab_lanes::avx::Avx<4>>(steps);
            return (world, one, four, time_lanes::<vsrlab_lanes::avx::Avx<8>>(steps));
        }
        let four = time_lanes::<vsrlab_lanes::F64s<4>>(steps);
        (world, one, four, time_lanes::<vsrlab_lanes::F64s<8>>(steps))
    }

    /// The loads of step `i` in lane `l`.
    fn bench_loads(i: usize, l: usize) -> (DVec3, DVec3) {
        let phase = i as f64 * 0.004 + l as f64;
        let force = DVec3::new(
            0.02 * phase.sin(),
            0.01 * (2.0 * phase).cos(),
            0.015 * (0.5 * phase).sin(),
        );
        let moment = DVec3::new(1e-5 * phase.cos(), -2e-5 * phase.sin(), 1e-5);
        (force, moment)
    }

    fn time_world(steps: usize) -> f64 {
        let settings = crate::world::WorldSettings::default();
        let mut w = crate::world::World::new(settings).expect("valid settings");
        let m = w.add_material(bench_material()).expect("valid material");
        let v = w.add_voxel(m, [0, 0, 0]).expect("free index");
        let dt = w.recommended_time_step();
        let loads: Vec<_> = (0..steps).map(|i| bench_loads(i, 0)).collect();
        let start = std::time::Instant::now();
        for (f, t) in &loads {
            w.set_external(v, *f, *t);
            if w.step(dt).is_err() {
                break;
            }
        }
        std::hint::black_box(w.position(v));
        start.elapsed().as_secs_f64() * 1e9 / steps as f64
    }

    fn time_lanes<L: Lanes>(steps: usize) -> f64 {
        let material = bench_material();
        let settings = crate::world::WorldSettings::default();
        let shared = VoxelShared {
            material,
            constants: VoxelConstants::new(&material, settings.voxel_size),
            fixed: [false; 6],
            home: DVec3::ZERO,
            lattice: settings.voxel_size,
            floor: settings.floor,
            gravity: settings.gravity,
        };
        let dt = {
            let mut w = crate::world::World::new(settings).expect("valid settings");
            let m = w.add_material(material).expect("valid material");
            w.add_voxel(m, [0, 0, 0]).expect("free index");
            w.recommended_time_step()
        };
        let loads: Vec<(V3<L>, V3<L>)> = (0..steps)
            .map(|i| {
                let (mut force, mut moment) = (V3::splat(DVec3::ZERO), V3::splat(DVec3::ZERO));
                for l in 0..L::LANES {
                    let (f, m) = bench_loads(i, l);
                    force.set_lane(l, f);
                    moment.set_lane(l, m);
                }
                (force, moment)
            })
            .collect();
        let mut voxel = VoxelLanes::<L>::at_rest(DVec3::ZERO, settings.voxel_size);
        let start = std::time::Instant::now();
        step_all(&mut voxel, &shared, &loads, dt);
        std::hint::black_box(&voxel.pos);
        start.elapsed().as_secs_f64() * 1e9 / (steps * L::LANES) as f64
    }

    /// The laned steps, compiled for the best vector unit this CPU has (the same bits on each).
    fn step_all<L: Lanes>(voxel: &mut VoxelLanes<L>, shared: &VoxelShared, loads: &[(V3<L>, V3<L>)], dt: f64) {
        #[cfg(target_arch = "x86_64")]
        {
            if is_x86_feature_detected!("avx512f") {
                // SAFETY: the CPU supports AVX-512F.
                return unsafe { step_all_avx512(voxel, shared, loads, dt) };
            }
            if is_x86_feature_detected!("avx2") {
                // SAFETY: the CPU supports AVX2.
                return unsafe { step_all_avx2(voxel, shared, loads, dt) };
            }
        }
        step_all_portable(voxel, shared, loads, dt);
    }

    #[inline(always)]
    fn step_all_portable<L: Lanes>(voxel: &mut VoxelLanes<L>, shared: &VoxelShared, loads: &[(V3<L>, V3<L>)], dt: f64) {
        let zero = V3::splat(DVec3::ZERO);
        for (force, moment) in loads {
            voxel.step(shared, zero, zero, zero, *force, *moment, dt);
        }
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn step_all_avx2<L: Lanes>(
        voxel: &mut VoxelLanes<L>,
        shared: &VoxelShared,
        loads: &[(V3<L>, V3<L>)],
        dt: f64,
    ) {
        step_all_portable(voxel, shared, loads, dt);
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx512f")]
    unsafe fn step_all_avx512<L: Lanes>(
        voxel: &mut VoxelLanes<L>,
        shared: &VoxelShared,
        loads: &[(V3<L>, V3<L>)],
        dt: f64,
    ) {
        step_all_portable(voxel, shared, loads, dt);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::{Dof, World, WorldSettings};

    const LANES: usize = 4;

    /// [`run_in`] with the portable lanes and, where the CPU has them, AVX2's.
    fn run(fixed: &[Dof], collisions: bool) {
        run_in::<vsrlab_lanes::F64s<LANES>>(fixed, collisions);
        #[cfg(target_arch = "x86_64")]
        if vsrlab_lanes::avx::available() {
            run_in::<vsrlab_lanes::avx::Avx<LANES>>(fixed, collisions);
        }
    }

    /// Each lane's world: one voxel on the floor pushed sideways, lifted and twisted by its own
    /// loads, warmed to its own size; the laned voxel beside them with the same loads.
    fn run_in<L: Lanes>(fixed: &[Dof], collisions: bool) {
        let settings = WorldSettings {
            collisions,
            ..WorldSettings::default()
        };
        let material = bench_material();
        let mut worlds: Vec<(World, crate::world::VoxelId)> = (0..LANES)
            .map(|_| {
                let mut w = World::new(settings).unwrap();
                let m = w.add_material(material).unwrap();
                let v = w.add_voxel(m, [0, 0, 0]).unwrap();
                w.set_fixed(v, fixed, true);
                (w, v)
            })
            .collect();
        let dt = worlds[0].0.recommended_time_step();
        let mut shared_fixed = [false; 6];
        for d in fixed {
            shared_fixed[Dof::ALL.iter().position(|x| x == d).unwrap()] = true;
        }
        let shared = VoxelShared {
            material,
            constants: VoxelConstants::new(&material, settings.voxel_size),
            fixed: shared_fixed,
            home: DVec3::ZERO,
            lattice: settings.voxel_size,
            floor: settings.floor,
            gravity: settings.gravity,
        };
        let mut laned = VoxelLanes::<L>::at_rest(DVec3::ZERO, settings.voxel_size);
        let zero = V3::splat(DVec3::ZERO);
        let mut touched = [0usize; 2];
        for step in 0..3000 {
            let (mut force, mut moment) = (zero, zero);
            for (l, (w, v)) in worlds.iter_mut().enumerate() {
                let phase = step as f64 * 0.004 + l as f64;
                // sideways pushes that stick and slip, a lift now and then, a twist
                let f = DVec3::new(
                    0.02 * phase.sin() * (l + 1) as f64,
                    0.01 * (2.0 * phase).cos(),
                    0.015 * (0.5 * phase).sin(),
                );
                let t = DVec3::new(1e-5 * phase.cos(), -2e-5 * phase.sin(), 1e-5 * (l as f64 - 1.5));
                w.set_external(*v, f, t);
                w.set_temperature(*v, 10.0 * (0.01 * step as f64 + l as f64).sin());
                force.set_lane(l, f);
                moment.set_lane(l, t);
                laned.size.set(l, w.edge(*v));
                w.step(dt).unwrap();
            }
            laned.step(&shared, zero, zero, zero, force, moment, dt);
            for (l, (w, v)) in worlds.iter().enumerate() {
                let what = format!("step {step}, lane {l}, fixed {fixed:?}");
                let (p, q) = (laned.pos.lane(l), laned.orient.lane(l));
                assert_eq!(
                    p.to_array().map(f64::to_bits),
                    w.position(*v).to_array().map(f64::to_bits),
                    "{what}"
                );
                assert_eq!(
                    q.to_array().map(f64::to_bits),
                    w.orientation(*v).to_array().map(f64::to_bits),
                    "{what}"
                );
                let velocity = laned.momentum.lane(l) / shared.constants.mass;
                assert_eq!(
                    velocity.to_array().map(f64::to_bits),
                    w.velocity(*v).to_array().map(f64::to_bits),
                    "{what}"
                );
                touched[usize::from(w.touches_floor(*v))] += 1;
            }
        }
        // the lanes were on and off the floor
        assert!(touched[0] > 0 && touched[1] > 0, "{touched:?}");
    }

    #[test]
    fn every_lane_of_a_laned_voxel_gives_the_scalar_worlds_bits() {
        run(&[], true);
        run(&[], false);
        run(&[Dof::Rx, Dof::Rz], false);
        run(&[Dof::Tx, Dof::Ry], false);
    }
}
