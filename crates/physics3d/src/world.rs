//! The world: materials, voxels on a cubic lattice with links between face neighbours, and the
//! step (all links from the state at the start of the step, then every voxel by semi-implicit
//! Euler; `docs/voxelyze-model.md` §6).

use crate::axis::Axis;
use crate::collision::{Collider, Collisions};
use crate::floor::floor_force;
use crate::lanes::V3;
use crate::link::{End, Link};
use crate::link_batches::{lanes_available, LinkBatches};
use crate::material::{LinkConstants, Material, VoxelConstants};
use crate::quat::{from_rotation_vector, rotate, to_rotation_vector};
use crate::voxel::{nominal, Voxel};
use crate::voxel_batches::{VoxelBatches, BATCH as VOXEL_BATCH};
use crate::voxel_lanes::{VoxelLanes, VoxelShared};
use crate::Physics3dError;
use glam::{DQuat, DVec3};
use std::collections::HashMap;
use vsrlab_lanes::Lanes;

/// Standard gravity (m/s²), as Voxelyze scales its gravity.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// A link stretched beyond this strain has diverged (Voxelyze's guard).
pub(crate) const DIVERGED_STRAIN: f64 = 100.0;

/// World-wide settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSettings {
    /// Lattice size: every voxel's nominal edge (m).
    pub voxel_size: f64,
    /// Downward gravitational acceleration (m/s²); Voxelyze's default is 0.
    pub gravity: f64,
    /// Whether the floor z = −voxel_size/2 holds voxels up.
    pub floor: bool,
    /// Whether voxels that are not linked collide (voxcraft-sim's default; Voxelyze's is off).
    pub collisions: bool,
}

impl Default for WorldSettings {
    fn default() -> Self {
        WorldSettings {
            voxel_size: 0.01,
            gravity: STANDARD_GRAVITY,
            floor: true,
            collisions: true,
        }
    }
}

/// A voxel's handle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct VoxelId(pub(crate) usize);

impl VoxelId {
    /// Its index, as voxels were added.
    pub fn index(self) -> usize {
        self.0
    }
}

/// A degree of freedom a voxel can have fixed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dof {
    /// Translation along x, y, z.
    Tx,
    Ty,
    Tz,
    /// Rotation about x, y, z.
    Rx,
    Ry,
    Rz,
}

impl Dof {
    /// Every degree of freedom, translations first.
    pub const ALL: [Dof; 6] = [Dof::Tx, Dof::Ty, Dof::Tz, Dof::Rx, Dof::Ry, Dof::Rz];

    fn index(self) -> usize {
        self as usize
    }
}

/// A 3D soft-voxel world. Stepping allocates nothing and is deterministic.
#[derive(Debug, Clone)]
pub struct World {
    settings: WorldSettings,
    pub(crate) materials: Vec<Material>,
    constants: Vec<VoxelConstants>,
    voxels: Vec<Voxel>,
    /// Each voxel's piece: voxels are linked within a piece only.
    pieces: Vec<u32>,
    links: Vec<Link>,
    /// Which links update together in lanes (planned again when links are added).
    link_batches: LinkBatches,
    batches_stale: bool,
    /// Which voxels step together in lanes (planned again when voxels or fixed DOFs change).
    voxel_batches: VoxelBatches,
    voxel_batches_stale: bool,
    lattice: HashMap<[i32; 3], usize>,
    link_constants: HashMap<(usize, usize), LinkConstants>,
    steps: u64,
    time: f64,
    ends: Vec<End>,
    collisions: Collisions,
    /// Whether the voxels or their fixed DOFs changed since the collision surface was taken.
    surface_stale: bool,
    /// Whether a temperature changed since the links' rest lengths were last computed.
    rests_stale: bool,
    colliders: Vec<Collider>,
    contact_forces: Vec<DVec3>,
}

impl World {
    /// An empty world; refuses a voxel size that is not finite and positive or a non-finite gravity.
    pub fn new(settings: WorldSettings) -> Result<World, Physics3dError> {
        if !(settings.voxel_size.is_finite() && settings.voxel_size > 0.0) {
            return Err(Physics3dError::Invalid(format!(
                "voxel_size: must be a finite number > 0, got {}",
                settings.voxel_size
            )));
        }
        if !settings.gravity.is_finite() {
            return Err(Physics3dError::Invalid(format!(
                "gravity: must be finite, got {}",
                settings.gravity
            )));
        }
        Ok(World {
            settings,
            materials: Vec::new(),
            constants: Vec::new(),
            voxels: Vec::new(),
            pieces: Vec::new(),
            links: Vec::new(),
            link_batches: LinkBatches::default(),
            batches_stale: false,
            voxel_batches: VoxelBatches::default(),
            voxel_batches_stale: false,
            lattice: HashMap::new(),
            link_constants: HashMap::new(),
            steps: 0,
            time: 0.0,
            ends: Vec::new(),
            collisions: Collisions::default(),
            surface_stale: true,
            rests_stale: false,
            colliders: Vec::new(),
            contact_forces: Vec::new(),
        })
    }

    /// Adds a material; returns its index.
    pub fn add_material(&mut self, material: Material) -> Result<usize, Physics3dError> {
        material.validate().map_err(Physics3dError::Material)?;
        self.materials.push(material);
        self.constants
            .push(VoxelConstants::new(&material, self.settings.voxel_size));
        Ok(self.materials.len() - 1)
    }

    /// Adds a voxel of `material` at lattice index `index`, linked to every face neighbour
    /// already there of piece 0. Refuses an occupied index or an unknown material.
    pub fn add_voxel(&mut self, material: usize, index: [i32; 3]) -> Result<VoxelId, Physics3dError> {
        self.add_voxel_to_piece(material, index, 0)
    }

    /// Adds a voxel to a piece: it is linked to its face neighbours of the same piece only, so
    /// that separate bodies (a robot and a wall) can touch without being joined.
    pub fn add_voxel_to_piece(
        &mut self,
        material: usize,
        index: [i32; 3],
        piece: u32,
    ) -> Result<VoxelId, Physics3dError> {
        if material >= self.materials.len() {
            return Err(Physics3dError::Invalid(format!("material {material} does not exist")));
        }
        if self.lattice.contains_key(&index) {
            return Err(Physics3dError::Invalid(format!("voxel index {index:?} is taken")));
        }
        let id = self.voxels.len();
        self.voxels.push(Voxel::new(material, index, self.settings.voxel_size));
        self.voxels[id].size = self.size_at(material, 0.0);
        self.pieces.push(piece);
        self.lattice.insert(index, id);
        for (axis, k) in [(Axis::X, 0), (Axis::Y, 1), (Axis::Z, 2)] {
            for step in [-1, 1] {
                let mut other = index;
                other[k] += step;
                if let Some(&j) = self.lattice.get(&other).filter(|&&j| self.pieces[j] == piece) {
                    let (neg, pos) = if step > 0 { (id, j) } else { (j, id) };
                    self.link(neg, pos, axis);
                }
            }
        }
        self.ends.push(End {
            pos: DVec3::ZERO,
            orient: DQuat::IDENTITY,
            damping: 0.0,
        });
        self.surface_stale = true;
        self.voxel_batches_stale = true;
        Ok(VoxelId(id))
    }

    fn link(&mut self, neg: usize, pos: usize, axis: Axis) {
        let (ma, mb) = (self.voxels[neg].material, self.voxels[pos].material);
        let key = (ma.min(mb), ma.max(mb));
        let s = self.settings.voxel_size;
        let (ea, eb) = (self.materials[ma].youngs_modulus, self.materials[mb].youngs_modulus);
        let k = *self
            .link_constants
            .entry(key)
            .or_insert_with(|| LinkConstants::new(ea, eb, s));
        let l = self.links.len();
        let rest = 0.5 * (self.rest_size(neg) + self.rest_size(pos));
        self.links.push(Link::new(neg, pos, axis, k, s * s, rest));
        self.batches_stale = true;
        self.voxels[neg].links.push((l, true));
        self.voxels[pos].links.push((l, false));
    }

    /// A voxel's rest edge: `s (1 + cte T)`.
    fn rest_size(&self, v: usize) -> f64 {
        self.voxels[v].size
    }

    /// The rest edge of a voxel of `material` at `temperature`.
    fn size_at(&self, material: usize, temperature: f64) -> f64 {
        crate::voxel::rest_edge(self.settings.voxel_size, self.materials[material].cte, temperature)
    }

    /// Fixes or frees degrees of freedom of a voxel (fixed: held at its lattice position and
    /// unrotated).
    pub fn set_fixed(&mut self, v: VoxelId, dofs: &[Dof], fixed: bool) {
        for d in dofs {
            self.voxels[v.0].fixed[d.index()] = fixed;
        }
        self.surface_stale = true;
        self.voxel_batches_stale = true;
    }

    /// Moves a voxel (its links take the new position as a deformation).
    pub fn set_position(&mut self, v: VoxelId, position: DVec3) {
        self.voxels[v.0].pos = position;
    }

    /// Sets the constant external force (N) and moment (N·m) on a voxel, in world axes.
    pub fn set_external(&mut self, v: VoxelId, force: DVec3, moment: DVec3) {
        self.voxels[v.0].external_force = force;
        self.voxels[v.0].external_moment = moment;
    }

    /// Sets a voxel's temperature, and with it its rest edge and the rest length of its links
    /// (thermal actuation). The links' rest lengths are computed once at the next step, from
    /// every temperature set before it: the values of computing them at each call.
    pub fn set_temperature(&mut self, v: VoxelId, temperature: f64) {
        let size = self.size_at(self.voxels[v.0].material, temperature);
        let voxel = &mut self.voxels[v.0];
        voxel.temperature = temperature;
        voxel.size = size;
        self.rests_stale |= !voxel.links.is_empty();
    }

    /// Every link's rest length from its voxels' rest edges, if a temperature changed.
    fn update_rest_lengths(&mut self) {
        if !self.rests_stale {
            return;
        }
        for l in &mut self.links {
            l.rest = 0.5 * (self.voxels[l.neg].size + self.voxels[l.pos].size);
        }
        self.rests_stale = false;
    }

    /// Voxelyze's recommended time step: one radian of the fastest axial link oscillation,
    /// `1 / (2π √max(a1 / min(m_neg, m_pos)))` (with no links, of `E s / m` per voxel).
    pub fn recommended_time_step(&self) -> f64 {
        let mass = |v: usize| self.constants[self.voxels[v].material].mass;
        let mut omega2: f64 = 0.0;
        for l in &self.links {
            omega2 = omega2.max(l.k.a1 / mass(l.neg).min(mass(l.pos)));
        }
        if self.links.is_empty() {
            for v in &self.voxels {
                let m = &self.materials[v.material];
                omega2 = omega2.max(m.youngs_modulus * self.settings.voxel_size / self.constants[v.material].mass);
            }
        }
        if omega2 == 0.0 {
            return 0.0;
        }
        1.0 / (2.0 * std::f64::consts::PI * omega2.sqrt())
    }

    /// Puts every voxel back at its lattice position, at rest, static, and time to 0 (links lose
    /// their damping history, as Voxelyze's `resetTime`).
    pub fn reset(&mut self) {
        let s = self.settings.voxel_size;
        for v in &mut self.voxels {
            v.pos = nominal(v.index, s);
            v.orient = DQuat::IDENTITY;
            v.momentum = DVec3::ZERO;
            v.angular_momentum = DVec3::ZERO;
            v.is_static = true;
            v.dt_prev = 0.0;
        }
        for l in &mut self.links {
            l.reset();
        }
        self.steps = 0;
        self.time = 0.0;
    }

    /// One step of `dt` seconds: every link from the state at the start of the step, then every
    /// voxel. A diverged step is an error: a link strained 100-fold (found before any voxel
    /// moves) or a non-finite voxel state (after the step; the world is then not to be stepped on).
    pub fn step(&mut self, dt: f64) -> Result<(), Physics3dError> {
        if !(dt.is_finite() && dt >= 0.0) {
            return Err(Physics3dError::Invalid(format!(
                "dt: must be a finite number ≥ 0, got {dt}"
            )));
        }
        if dt == 0.0 {
            return Ok(());
        }
        self.update_rest_lengths();
        for (end, v) in self.ends.iter_mut().zip(&self.voxels) {
            let c = &self.constants[v.material];
            let zeta = self.materials[v.material].internal_damping;
            *end = End {
                pos: v.pos,
                orient: v.orient,
                damping: if v.dt_prev > 0.0 {
                    2.0 * c.sqrt_mass * zeta / v.dt_prev
                } else {
                    0.0
                },
            };
        }
        if self.batches_stale {
            self.link_batches = LinkBatches::plan(&self.links, lanes_available());
            self.batches_stale = false;
        }
        self.link_batches.update(&mut self.links, &self.ends);
        for l in &self.links {
            if l.strain.is_nan() || l.strain.abs() > DIVERGED_STRAIN {
                return Err(Physics3dError::Diverged {
                    step: self.steps,
                    voxel: l.neg,
                });
            }
        }
        self.collide();
        self.step_voxels(dt);
        if let Some(bad) = self.voxels.iter().position(|v| {
            !(v.pos.is_finite() && v.momentum.is_finite() && v.angular_momentum.is_finite() && v.orient.is_finite())
        }) {
            return Err(Physics3dError::Diverged {
                step: self.steps,
                voxel: bad,
            });
        }
        self.steps += 1;
        self.time += dt;
        Ok(())
    }

    /// The contact forces of this step between voxels (`collision.rs`), from the state at its
    /// start.
    fn collide(&mut self) {
        if !self.settings.collisions {
            return;
        }
        if self.surface_stale {
            let surface: Vec<usize> = (0..self.voxels.len())
                .filter(|&v| self.voxels[v].links.len() < 6)
                .collect();
            let fixed = surface.iter().map(|&v| self.voxels[v].all_fixed()).collect();
            self.collisions.set_surface(surface, fixed, self.voxels.len());
            self.colliders.resize(self.voxels.len(), self.collider(0));
            self.contact_forces.resize(self.voxels.len(), DVec3::ZERO);
            self.surface_stale = false;
        }
        for v in 0..self.voxels.len() {
            self.colliders[v] = self.collider(v);
        }
        self.contact_forces.iter_mut().for_each(|f| *f = DVec3::ZERO);
        let voxels = &self.voxels;
        let linked = |a: usize, b: usize| {
            voxels[a].links.iter().any(|&(l, _)| {
                let link = &self.links[l];
                link.neg == b || link.pos == b
            })
        };
        self.collisions.add_forces(
            &self.colliders,
            self.settings.voxel_size,
            linked,
            &mut self.contact_forces,
        );
    }

    /// Voxel `v` as the collision pass sees it.
    fn collider(&self, v: usize) -> Collider {
        let voxel = &self.voxels[v];
        let c = &self.constants[voxel.material];
        Collider {
            pos: voxel.pos,
            velocity: voxel.momentum / c.mass,
            size: self.rest_size(v),
            stiffness: c.floor_stiffness,
            damping: self.materials[voxel.material].collision_damping * c.linear_damping,
        }
    }

    /// Plans no batches: every link and voxel steps one by one (the tests compare both ways).
    #[cfg(test)]
    pub(crate) fn one_by_one(&mut self) {
        self.link_batches = LinkBatches::plan(&self.links, false);
        self.voxel_batches = VoxelBatches::plan(&self.voxels, false);
        (self.batches_stale, self.voxel_batches_stale) = (false, false);
    }

    /// Every voxel by semi-implicit Euler: the batches of free voxels in AVX2 lanes
    /// (`voxel_batches.rs`), the others one by one, the same bits either way.
    fn step_voxels(&mut self, dt: f64) {
        if self.voxel_batches_stale {
            self.voxel_batches = VoxelBatches::plan(&self.voxels, lanes_available());
            self.voxel_batches_stale = false;
        }
        #[cfg(target_arch = "x86_64")]
        if !self.voxel_batches.batches.is_empty() {
            // SAFETY: batches exist only where `lanes_available` found AVX2
            unsafe { self.step_voxel_batches_avx2(dt) };
        }
        for k in 0..self.voxel_batches.single.len() {
            self.step_voxel(self.voxel_batches.single[k], dt);
        }
    }

    /// The voxel batches in AVX2 lanes.
    ///
    /// # Safety
    /// The CPU must support AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn step_voxel_batches_avx2(&mut self, dt: f64) {
        for b in 0..self.voxel_batches.batches.len() {
            let (material, batch) = self.voxel_batches.batches[b];
            self.step_voxel_batch::<vsrlab_lanes::avx::Avx<VOXEL_BATCH>>(material, batch, dt);
        }
    }

    /// One batch of free voxels of `material`: gathered into lanes, stepped, written back.
    #[inline(always)]
    fn step_voxel_batch<L: Lanes>(&mut self, material: usize, batch: [usize; VOXEL_BATCH], dt: f64) {
        let shared = VoxelShared {
            material: self.materials[material],
            constants: self.constants[material],
            fixed: [false; 6],
            home: DVec3::ZERO,
            lattice: self.settings.voxel_size,
            floor: self.settings.floor,
            gravity: self.settings.gravity,
        };
        let mut lanes = VoxelLanes::<L>::at_rest(DVec3::ZERO, 0.0);
        let zero = V3::<L>::splat(DVec3::ZERO);
        let (mut link_force, mut link_moment, mut contact) = (zero, zero, zero);
        let (mut external_force, mut external_moment) = (zero, zero);
        for (lane, &i) in batch.iter().enumerate() {
            let (f, m) = self.link_loads(i);
            link_force.set_lane(lane, f);
            link_moment.set_lane(lane, m);
            contact.set_lane(lane, self.contact_forces.get(i).copied().unwrap_or(DVec3::ZERO));
            let v = &self.voxels[i];
            external_force.set_lane(lane, v.external_force);
            external_moment.set_lane(lane, v.external_moment);
            lanes.set_lane(lane, v);
        }
        lanes.step(
            &shared,
            link_force,
            link_moment,
            contact,
            external_force,
            external_moment,
            dt,
        );
        for (lane, &i) in batch.iter().enumerate() {
            lanes.write_lane(lane, &mut self.voxels[i]);
        }
    }

    /// The sum of voxel `i`'s link forces and moments (in its own frame), in its links' order.
    #[inline(always)]
    fn link_loads(&self, i: usize) -> (DVec3, DVec3) {
        let (mut link_force, mut link_moment) = (DVec3::ZERO, DVec3::ZERO);
        for &(l, is_neg) in &self.voxels[i].links {
            let link = &self.links[l];
            if is_neg {
                link_force += link.force_neg;
                link_moment += link.moment_neg;
            } else {
                link_force += link.force_pos;
                link_moment += link.moment_pos;
            }
        }
        (link_force, link_moment)
    }

    /// Semi-implicit Euler for one voxel (`docs/voxelyze-model.md` §6.2).
    fn step_voxel(&mut self, i: usize, dt: f64) {
        let s = self.settings.voxel_size;
        let rest = self.rest_size(i);
        let (floor, gravity) = (self.settings.floor, self.settings.gravity);
        let voxel = &self.voxels[i];
        let m = self.materials[voxel.material];
        let c = self.constants[voxel.material];
        if voxel.all_fixed() {
            let v = &mut self.voxels[i];
            v.dt_prev = dt;
            v.pos = nominal(v.index, s);
            v.orient = DQuat::IDENTITY;
            v.momentum = DVec3::ZERO;
            v.angular_momentum = DVec3::ZERO;
            return;
        }
        let (link_force, link_moment) = self.link_loads(i);
        let velocity = voxel.momentum / c.mass;
        let omega = voxel.angular_momentum / c.inertia;
        let mut force = rotate(voxel.orient, link_force) + voxel.external_force
            - m.global_damping * c.linear_damping * velocity
            + DVec3::new(0.0, 0.0, -c.mass * gravity)
            + self.contact_forces.get(i).copied().unwrap_or(DVec3::ZERO);
        let moment =
            rotate(voxel.orient, link_moment) + voxel.external_moment - m.global_damping * c.angular_damping * omega;
        let v = &mut self.voxels[i];
        v.dt_prev = dt;
        let contact = floor.then(|| {
            floor_force(
                &mut force,
                v.pos.z,
                velocity,
                rest,
                s,
                c.floor_stiffness,
                m.collision_damping * c.linear_damping,
                m.static_friction,
                m.kinetic_friction,
                &mut v.is_static,
            )
        });
        v.momentum += force * dt;
        let mut translation = v.momentum * dt / c.mass;
        if let Some(contact) = contact.filter(|c| c.touching) {
            let work = contact.friction.x * translation.x + contact.friction.y * translation.y;
            let kinetic = (v.momentum.x * v.momentum.x + v.momentum.y * v.momentum.y) / (2.0 * c.mass);
            if kinetic + work <= 0.0 {
                v.is_static = true;
            }
            if v.is_static {
                (v.momentum.x, v.momentum.y) = (0.0, 0.0);
                (translation.x, translation.y) = (0.0, 0.0);
            }
        }
        v.pos += translation;
        v.angular_momentum += moment * dt;
        v.orient = from_rotation_vector(v.angular_momentum * dt / c.inertia) * v.orient;
        let home = nominal(v.index, s);
        for k in 0..3 {
            if v.fixed[k] {
                v.pos[k] = home[k];
                v.momentum[k] = 0.0;
            }
        }
        let (rx, ry, rz) = (v.fixed[3], v.fixed[4], v.fixed[5]);
        if rx && ry && rz {
            v.orient = DQuat::IDENTITY;
            v.angular_momentum = DVec3::ZERO;
        } else if rx || ry || rz {
            let mut r = to_rotation_vector(v.orient);
            for (k, fixed) in [rx, ry, rz].into_iter().enumerate() {
                if fixed {
                    r[k] = 0.0;
                    v.angular_momentum[k] = 0.0;
                }
            }
            v.orient = from_rotation_vector(r);
        }
    }

    /// Whether voxel `v` touched another voxel (not linked to it) in the last step.
    pub fn touches_voxel(&self, v: VoxelId) -> bool {
        self.settings.collisions && self.collisions.touching.get(v.0).copied().unwrap_or(false)
    }

    /// The pairs of voxels that touched in the last step (not linked; the lower index first).
    pub fn contacts(&self) -> impl Iterator<Item = (VoxelId, VoxelId)> + '_ {
        let contacts: &[(usize, usize)] = if self.settings.collisions {
            &self.collisions.contacts
        } else {
            &[]
        };
        contacts.iter().map(|&(a, b)| (VoxelId(a), VoxelId(b)))
    }

    /// The piece a voxel belongs to ([`World::add_voxel_to_piece`]).
    pub fn piece(&self, v: VoxelId) -> u32 {
        self.pieces[v.0]
    }

    /// Whether voxel `v` touches the floor (its bottom at or below the floor).
    pub fn touches_floor(&self, v: VoxelId) -> bool {
        let s = self.settings.voxel_size;
        self.settings.floor && self.rest_size(v.0) / 2.0 - s / 2.0 - self.voxels[v.0].pos.z >= 0.0
    }

    /// Steps taken since the start or the last reset.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Simulated time (s).
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Number of voxels.
    pub fn voxel_count(&self) -> usize {
        self.voxels.len()
    }

    /// Number of links.
    pub fn link_count(&self) -> usize {
        self.links.len()
    }

    /// What a laned copy of this world needs (`world_lanes`): for each voxel its shared part, its
    /// rest edge and its links (link index, whether it is the negative end) in the order its
    /// forces are summed; for each link its ends, axis, constants and area; the settings.
    #[allow(clippy::type_complexity)]
    pub(crate) fn parts(
        &self,
    ) -> (
        Vec<(crate::voxel_lanes::VoxelShared, f64, Vec<(usize, bool)>, DVec3, DVec3)>,
        Vec<(usize, usize, Axis, LinkConstants, f64)>,
        WorldSettings,
    ) {
        let s = self.settings.voxel_size;
        let voxels = self
            .voxels
            .iter()
            .map(|v| {
                let shared = crate::voxel_lanes::VoxelShared {
                    material: self.materials[v.material],
                    constants: self.constants[v.material],
                    fixed: v.fixed,
                    home: nominal(v.index, s),
                    lattice: s,
                    floor: self.settings.floor,
                    gravity: self.settings.gravity,
                };
                (shared, v.size, v.links.clone(), v.external_force, v.external_moment)
            })
            .collect();
        let links = self.links.iter().map(|l| (l.neg, l.pos, l.axis, l.k, l.area)).collect();
        (voxels, links, self.settings)
    }

    /// A voxel's centre (m).
    pub fn position(&self, v: VoxelId) -> DVec3 {
        self.voxels[v.0].pos
    }

    /// A voxel's displacement from its lattice position (m).
    pub fn displacement(&self, v: VoxelId) -> DVec3 {
        self.voxels[v.0].pos - nominal(self.voxels[v.0].index, self.settings.voxel_size)
    }

    /// A voxel's orientation.
    pub fn orientation(&self, v: VoxelId) -> DQuat {
        self.voxels[v.0].orient
    }

    /// A voxel's rotation vector (axis × angle, rad).
    pub fn rotation(&self, v: VoxelId) -> DVec3 {
        to_rotation_vector(self.voxels[v.0].orient)
    }

    /// A voxel's velocity (m/s).
    pub fn velocity(&self, v: VoxelId) -> DVec3 {
        let voxel = &self.voxels[v.0];
        voxel.momentum / self.constants[voxel.material].mass
    }

    /// A voxel's rest edge now (m): the lattice size scaled by its thermal expansion.
    pub fn edge(&self, v: VoxelId) -> f64 {
        self.rest_size(v.0)
    }

    /// A voxel's mass (kg).
    pub fn mass(&self, v: VoxelId) -> f64 {
        self.constants[self.voxels[v.0].material].mass
    }

    /// The settings.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }
}
