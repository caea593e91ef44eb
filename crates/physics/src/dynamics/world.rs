//! The world: simulated state, the step pipeline and queries.

use super::broad_phase::{ExcludedPairs, StaticIndex, SweepAndPrune};
use super::builder::{JointRef, WorldBuilder};
use super::colour::colour_order;
use super::contact::{apply_restitution, ContactConstraint, ContactPass, ContactSchedule};
use super::contact_batch::ContactBatches;
use super::dyn4j_contacts::Dyn4jContacts;
use super::pressure::PressureRing;
use super::rope::{rope_batches, solve_ropes, Rope, RopeBatch};
use super::sequential::{self, Joint, Rope as SequentialRope, SequentialSolver, Spring as SequentialSpring, Weld};
use super::settings::{ContactModel, Dyn4jVersion, Solver, WorldSettings};
use super::soft::Softness;
use super::spring::{Spring, SpringModel, SpringSet};
use crate::geometry::aabb::Aabb;
use crate::geometry::collide::{collide_polygons, collide_polygons_dyn4j, Manifold};
use crate::geometry::raycast::ray_cast_polygon;
use crate::geometry::shape::Polygon;
use crate::math::{Rot, Vec2};
use crate::PhysicsError;

/// Handle to a part added with [`WorldBuilder::add_part`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct PartHandle(pub u32);
/// Handle to a spring added with [`WorldBuilder::add_spring`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct SpringHandle(pub u32);
/// Handle to a pressure ring added with [`WorldBuilder::add_pressure_ring`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RingHandle(pub u32);
/// Handle to a rope added with [`WorldBuilder::add_rope`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct RopeHandle(pub u32);

const NONE: u32 = u32::MAX;

/// Position, velocity and inverse mass of one body: everything the solver touches, together.
/// The layout is fixed (`repr(C)`: position, rotation, velocity, angular velocity, inverse mass,
/// inverse inertia) because the vectorised spring solver loads it in pairs of f64.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub(crate) struct BodyState {
    pub pos: Vec2,
    pub rot: Rot,
    pub vel: Vec2,
    pub omega: f64,
    pub inv_mass: f64,
    pub inv_inertia: f64,
}

/// Simulated rigid bodies. Body 0 is the static world (infinite mass, never moves).
#[derive(Debug, Clone, Default)]
pub(crate) struct Bodies {
    pub state: Vec<BodyState>,
    pub mass: Vec<f64>,
    pub lin_damp: Vec<f64>,
    pub ang_damp: Vec<f64>,
    pub force: Vec<Vec2>,
    pub torque: Vec<f64>,
}

impl Bodies {
    fn push(&mut self, pos: Vec2, mass: f64, inertia: f64, lin_damp: f64, ang_damp: f64) {
        self.state.push(BodyState {
            pos,
            rot: Rot::IDENTITY,
            vel: Vec2::ZERO,
            omega: 0.0,
            inv_mass: if mass > 0.0 { 1.0 / mass } else { 0.0 },
            inv_inertia: if inertia > 0.0 { 1.0 / inertia } else { 0.0 },
        });
        self.mass.push(mass);
        self.lin_damp.push(lin_damp);
        self.ang_damp.push(ang_damp);
        self.force.push(Vec2::ZERO);
        self.torque.push(0.0);
    }

    /// Number of bodies, the static world included.
    #[inline]
    pub fn len(&self) -> usize {
        self.state.len()
    }

    /// Applies impulse `p` at arm `rb` of body b and −p at arm `ra` of body a.
    #[inline(always)]
    pub fn apply_impulse_pair(&mut self, a: usize, b: usize, ra: Vec2, rb: Vec2, p: Vec2) {
        let sa = &mut self.state[a];
        sa.vel -= p * sa.inv_mass;
        sa.omega -= sa.inv_inertia * ra.cross(p);
        let sb = &mut self.state[b];
        sb.vel += p * sb.inv_mass;
        sb.omega += sb.inv_inertia * rb.cross(p);
    }
}

/// A simulated part: which body it belongs to and where it sits in that body.
#[derive(Debug, Clone, Copy)]
struct Part {
    body: u32,
    /// Part frame origin relative to the body's centre of mass, in body frame.
    local: Vec2,
    touching: bool,
}

/// A dynamic collision shape (one per part).
#[derive(Debug, Clone, Copy)]
struct Shape {
    part: u32,
    body: u32,
    /// Polygon relative to the body's centre of mass, in body frame.
    local: Polygon,
    /// Largest distance of a vertex from the body's centre of mass.
    radius: f64,
    friction: f64,
    restitution: f64,
    group: u32,
    collide_within_group: bool,
}

/// What the broad phase checks of a shape before the narrow phase, kept compact.
#[derive(Debug, Clone, Copy)]
struct ShapeFilter {
    part: u32,
    group: u32,
    collide_within_group: bool,
}

#[derive(Debug, Clone, Copy)]
struct StaticShape {
    polygon: Polygon,
    aabb: Aabb,
    friction: f64,
    restitution: f64,
}

/// A 2D world of rigid bodies, springs, ropes, contacts and static geometry.
#[derive(Debug, Clone)]
pub struct World {
    settings: WorldSettings,
    pub(crate) bodies: Bodies,
    parts: Vec<Part>,
    shapes: Vec<Shape>,
    /// Per shape (same order): its broad-phase filter.
    filters: Vec<ShapeFilter>,
    statics: Vec<StaticShape>,
    static_index: StaticIndex,
    springs: SpringSet,
    spring_slot: Vec<u32>,
    ropes: Vec<Rope>,
    /// The ropes by colour, for the slack test of the first sub-step.
    rope_batches: Vec<RopeBatch>,
    rope_slot: Vec<u32>,
    rings: Vec<PressureRing>,
    /// Part pairs that never collide.
    excluded: ExcludedPairs,
    contacts: Vec<ContactConstraint>,
    contact_schedule: ContactSchedule,
    contact_batches: ContactBatches,
    world_polys: Vec<Polygon>,
    aabbs: Vec<Aabb>,
    /// Speculative margin of each shape this step.
    margins: Vec<f64>,
    /// Bounding box of each dynamic body (index = body − 1).
    body_aabbs: Vec<Aabb>,
    /// Range of `shapes` owned by each body (shapes are sorted by body).
    body_shapes: Vec<(u32, u32)>,
    sap: SweepAndPrune,
    step_count: u64,
    time: f64,
    /// The joints and contacts of the sequential-impulse solver, when the world uses it.
    sequential: Option<SequentialSolver>,
    /// The soft solver's contacts when they follow dyn4j (`contact_model = "dyn4j"`).
    dyn4j_contacts: Option<Dyn4jContacts>,
    /// Whether `contacts` hold the present positions' contacts (the sequential-impulse solver
    /// detects them at the end of each step, for the next one).
    contacts_fresh: bool,
}

/// Rewrites handle → slot maps after constraints were permuted by `order` (new → old).
fn remap_slots(slots: &mut [u32], order: &[usize]) {
    let mut new_of_old = vec![0u32; order.len()];
    for (new, &old) in order.iter().enumerate() {
        new_of_old[old] = new as u32;
    }
    for s in slots.iter_mut().filter(|s| **s != NONE) {
        *s = new_of_old[*s as usize];
    }
}

/// What joining parts needs: the builder, each part's body and mass properties, the bodies.
struct Joining<'a> {
    b: &'a WorldBuilder,
    part_body: &'a [u32],
    props: &'a [(f64, Vec2, f64)],
    bodies: &'a Bodies,
}

impl Joining<'_> {
    /// A world point relative to a body's centre of mass (bodies start unrotated).
    fn local(&self, world: Vec2, body: u32) -> Vec2 {
        world - self.bodies.state[body as usize].pos
    }

    /// The builder's springs: the soft solver's (with their mass models) or, with the
    /// sequential-impulse solver, its own; each builder spring's slot (`NONE` within a body).
    /// Parts joined by a spring that does not collide are added to `excluded`.
    fn springs(
        &self,
        sequential: &mut Option<SequentialSolver>,
        excluded: &mut Vec<(u32, u32)>,
    ) -> (Vec<Spring>, Vec<SpringModel>, Vec<u32>) {
        let mut springs = Vec::new();
        let mut spring_models = Vec::new();
        let mut spring_slot = Vec::new();
        for s in &self.b.springs {
            if !s.collide_connected {
                excluded.push((s.part_a.0, s.part_b.0));
            }
            let (pa, pb) = (s.part_a.0 as usize, s.part_b.0 as usize);
            let (ba, bb) = (self.part_body[pa], self.part_body[pb]);
            if ba == bb {
                spring_slot.push(NONE);
                continue;
            }
            let (ma, mb) = (self.props[pa].0, self.props[pb].0);
            let world_a = self.b.parts[pa].position + s.anchor_a;
            let world_b = self.b.parts[pb].position + s.anchor_b;
            if let Some(si) = sequential {
                spring_slot.push(si.joints.springs.len() as u32);
                si.joints.springs.push(SequentialSpring::new(
                    ba,
                    bb,
                    self.local(world_a, ba),
                    self.local(world_b, bb),
                    s.rest_length,
                    s.frequency,
                    s.damping_ratio,
                    s.mass_model,
                ));
                continue;
            }
            spring_slot.push(springs.len() as u32);
            springs.push(Spring {
                a: ba,
                b: bb,
                local_a: self.local(world_a, ba),
                local_b: self.local(world_b, bb),
                rest: s.rest_length,
            });
            let part_inv_inertia = |k: usize| {
                if self.b.parts[k].fixed_rotation {
                    0.0
                } else {
                    1.0 / self.props[k].2
                }
            };
            spring_models.push(SpringModel {
                arm_a: world_a - self.props[pa].1,
                arm_b: world_b - self.props[pb].1,
                part_inv_mass_a: 1.0 / ma,
                part_inv_inertia_a: part_inv_inertia(pa),
                part_inv_mass_b: 1.0 / mb,
                part_inv_inertia_b: part_inv_inertia(pb),
                omega: 2.0 * std::f64::consts::PI * s.frequency,
                zeta: s.damping_ratio,
                model: s.mass_model,
                reduced_mass: ma * mb / (ma + mb),
            });
        }
        (springs, spring_models, spring_slot)
    }

    /// The builder's ropes, as [`Joining::springs`] does springs.
    fn ropes(
        &self,
        sequential: &mut Option<SequentialSolver>,
        excluded: &mut Vec<(u32, u32)>,
    ) -> (Vec<Rope>, Vec<u32>) {
        let mut ropes = Vec::new();
        let mut rope_slot = Vec::new();
        for r in &self.b.ropes {
            if !r.collide_connected {
                excluded.push((r.part_a.0, r.part_b.0));
            }
            let (pa, pb) = (r.part_a.0 as usize, r.part_b.0 as usize);
            let (ba, bb) = (self.part_body[pa], self.part_body[pb]);
            if ba == bb {
                rope_slot.push(NONE);
                continue;
            }
            let world_a = self.b.parts[pa].position + r.anchor_a;
            let world_b = self.b.parts[pb].position + r.anchor_b;
            if let Some(si) = sequential {
                rope_slot.push(si.joints.ropes.len() as u32);
                si.joints.ropes.push(SequentialRope::new(
                    ba,
                    bb,
                    self.local(world_a, ba),
                    self.local(world_b, bb),
                    r.min_length,
                ));
                continue;
            }
            rope_slot.push(ropes.len() as u32);
            ropes.push(Rope {
                a: ba,
                b: bb,
                local_a: self.local(world_a, ba),
                local_b: self.local(world_b, bb),
                min_length: r.min_length,
                impulse: 0.0,
                active: true,
            });
        }
        (ropes, rope_slot)
    }

    /// The sequential-impulse solver's weld joints: welded parts never collide; the weld's anchor
    /// is the first part's centre of mass (2D-VSR-Sim's, vsr-model.md §1.8).
    /// Each builder weld's slot (`NONE` where `merge_welds` made its parts one body).
    fn welds(&self, si: &mut SequentialSolver, excluded: &mut Vec<(u32, u32)>) -> Vec<u32> {
        let mut slots = Vec::with_capacity(self.b.welds.len());
        for &(x, y) in &self.b.welds {
            excluded.push((x.0, y.0));
            let (ba, bb) = (self.part_body[x.0 as usize], self.part_body[y.0 as usize]);
            if ba == bb {
                slots.push(NONE);
                continue;
            }
            slots.push(si.joints.welds.len() as u32);
            let anchor = self.bodies.state[ba as usize].pos;
            si.joints
                .welds
                .push(Weld::new(ba, bb, Vec2::ZERO, self.local(anchor, bb), 0.0));
        }
        slots
    }
}

/// Union–find root with path halving.
fn find(parent: &mut [usize], mut i: usize) -> usize {
    while parent[i] != i {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    i
}

/// Groups of parts joined by welds (the soft solver merges each into one rigid body): each part's
/// group root, the lowest part index of its group. Without merging, every part is its own group.
fn weld_groups(b: &WorldBuilder, merge_welds: bool) -> Vec<usize> {
    let n = b.parts.len();
    let mut parent: Vec<usize> = (0..n).collect();
    for &(x, y) in b.welds.iter().filter(|_| merge_welds) {
        let (rx, ry) = (find(&mut parent, x.0 as usize), find(&mut parent, y.0 as usize));
        if rx != ry {
            parent[rx.max(ry)] = rx.min(ry);
        }
    }
    (0..n).map(|i| find(&mut parent, i)).collect()
}

/// Each part's mass, centre of mass and inertia about it, in the world frame (all parts start
/// unrotated).
fn part_mass_properties(b: &WorldBuilder) -> Vec<(f64, Vec2, f64)> {
    b.parts
        .iter()
        .map(|p| {
            let (area, c, i) = p.shape.mass_properties();
            (area * p.density, p.position + c, i * p.density)
        })
        .collect()
}

/// One body per weld group, in order of first part, after body 0 (the static world); and each
/// part's body.
fn bodies_of_groups(b: &WorldBuilder, roots: &[usize], props: &[(f64, Vec2, f64)]) -> (Bodies, Vec<u32>) {
    let n = b.parts.len();
    let mut bodies = Bodies::default();
    bodies.push(Vec2::ZERO, 0.0, 0.0, 0.0, 0.0); // body 0: the static world
    let mut body_of_root = vec![NONE; n];
    let mut part_body = vec![0u32; n];
    for i in 0..n {
        let r = roots[i];
        if body_of_root[r] == NONE {
            let members: Vec<usize> = (0..n).filter(|&j| roots[j] == r).collect();
            let mass: f64 = members.iter().map(|&j| props[j].0).sum();
            let com = members.iter().fold(Vec2::ZERO, |acc, &j| acc + props[j].1 * props[j].0) / mass;
            let inertia: f64 = if members.iter().any(|&j| b.parts[j].fixed_rotation) {
                0.0 // never rotates: zero inverse inertia
            } else {
                members
                    .iter()
                    .map(|&j| props[j].2 + props[j].0 * (props[j].1 - com).length_squared())
                    .sum()
            };
            let lin = members
                .iter()
                .map(|&j| b.parts[j].linear_damping * props[j].0)
                .sum::<f64>()
                / mass;
            let ang = members
                .iter()
                .map(|&j| b.parts[j].angular_damping * props[j].0)
                .sum::<f64>()
                / mass;
            body_of_root[r] = bodies.len() as u32;
            bodies.push(com, mass, inertia, lin, ang);
        }
        part_body[i] = body_of_root[r];
    }
    (bodies, part_body)
}

/// Each part as a body sees it, and its collision shape in its body's frame.
fn parts_and_shapes(b: &WorldBuilder, bodies: &Bodies, part_body: &[u32]) -> (Vec<Part>, Vec<Shape>) {
    let n = b.parts.len();
    let parts: Vec<Part> = (0..n)
        .map(|i| Part {
            body: part_body[i],
            local: b.parts[i].position - bodies.state[part_body[i] as usize].pos,
            touching: false,
        })
        .collect();
    let shapes: Vec<Shape> = (0..n)
        .map(|i| {
            let p = &b.parts[i];
            Shape {
                part: i as u32,
                body: part_body[i],
                local: p.shape.transformed(Rot::IDENTITY, parts[i].local),
                radius: p
                    .shape
                    .verts()
                    .iter()
                    .map(|v| (*v + parts[i].local).length())
                    .fold(0.0, f64::max)
                    + p.shape.radius,
                friction: p.friction,
                restitution: p.restitution,
                group: p.group,
                collide_within_group: p.collide_within_group,
            }
        })
        .collect();
    (parts, shapes)
}

/// The static shapes (ground, obstacles), sorted by the left edge of their boxes.
fn static_shapes(b: &WorldBuilder) -> Vec<StaticShape> {
    let mut statics: Vec<StaticShape> = b
        .statics
        .iter()
        .map(|s| StaticShape {
            polygon: s.polygon,
            aabb: Aabb::of_points(s.polygon.verts()),
            friction: s.friction,
            restitution: s.restitution,
        })
        .collect();
    statics.sort_by(|x, y| x.aabb.min.x.total_cmp(&y.aabb.min.x));
    statics
}

impl World {
    pub(crate) fn from_builder(b: WorldBuilder) -> World {
        let n = b.parts.len();
        // the sequential-impulse solver keeps every part a body of its own, joined by weld joints
        // (unless told to merge them, a fidelity candidate)
        let soft = b.settings.solver == Solver::SoftSubsteps;
        let merge_welds = soft || b.settings.merge_welds;
        let mut sequential = (!soft).then(SequentialSolver::default);
        let roots = weld_groups(&b, merge_welds);
        let props = part_mass_properties(&b);
        let (bodies, part_body) = bodies_of_groups(&b, &roots, &props);
        let (parts, shapes) = parts_and_shapes(&b, &bodies, &part_body);
        let statics = static_shapes(&b);

        let static_aabbs: Vec<Aabb> = statics.iter().map(|s| s.aabb).collect();
        let mut excluded: Vec<(u32, u32)> = b.excluded.iter().map(|&(x, y)| (x.0, y.0)).collect();
        let joining = Joining {
            b: &b,
            part_body: &part_body,
            props: &props,
            bodies: &bodies,
        };
        let (springs, spring_models, mut spring_slot) = joining.springs(&mut sequential, &mut excluded);
        let (ropes, mut rope_slot) = joining.ropes(&mut sequential, &mut excluded);
        let weld_slot = match &mut sequential {
            Some(si) => joining.welds(si, &mut excluded),
            None => Vec::new(),
        };
        let excluded = ExcludedPairs::new(n, excluded);
        // order constraints so that neighbours in the solver loop touch different bodies: the
        // result is the same Gauss–Seidel sweep, but the CPU can overlap independent constraints
        let (order, ranges) = colour_order(&springs.iter().map(|s| (s.a, s.b)).collect::<Vec<_>>());
        let springs: Vec<Spring> = order.iter().map(|&i| springs[i]).collect();
        let spring_models: Vec<SpringModel> = order.iter().map(|&i| spring_models[i]).collect();
        let (springs, batch_slot) = SpringSet::new(&springs, &spring_models, &ranges, &bodies);
        // (the sequential-impulse solver's slots index its own lists, which keep their order)
        if sequential.is_none() {
            remap_slots(&mut spring_slot, &order);
            for s in spring_slot.iter_mut().filter(|s| **s != NONE) {
                *s = batch_slot[*s as usize];
            }
        }
        let (order, rope_ranges) = colour_order(&ropes.iter().map(|r| (r.a, r.b)).collect::<Vec<_>>());
        let ropes: Vec<Rope> = order.iter().map(|&i| ropes[i].clone()).collect();
        if sequential.is_none() {
            remap_slots(&mut rope_slot, &order);
        }
        let mut shapes = shapes;
        shapes.sort_by_key(|s| s.body);
        let mut body_shapes = vec![(0u32, 0u32); bodies.len()];
        for (k, sh) in shapes.iter().enumerate() {
            let r = &mut body_shapes[sh.body as usize];
            if r.1 == 0 {
                r.0 = k as u32;
            }
            r.1 = k as u32 + 1;
        }
        let rings = b
            .rings
            .iter()
            .map(|r| PressureRing {
                bodies: r.parts.iter().map(|p| part_body[p.0 as usize]).collect(),
                spring_slots: r.springs.iter().map(|h| spring_slot[h.0 as usize]).collect(),
                length: r.length,
                pressure: r.pressure,
            })
            .collect();
        let n_bodies = bodies.len();
        let ccd = || {
            let polygons: Vec<Polygon> = statics.iter().map(|s| s.polygon).collect();
            let locals: Vec<(u32, Polygon)> = shapes.iter().map(|s| (s.body, s.local)).collect();
            sequential::Ccd::new(&polygons, &locals, n_bodies)
        };
        let dyn4j_contacts = (sequential.is_none() && b.settings.contact_model == ContactModel::Dyn4j)
            .then(|| Dyn4jContacts::new(ccd()));
        if let Some(si) = &mut sequential {
            let joints: Vec<(Joint, u32, u32)> = b
                .joint_order
                .iter()
                .filter_map(|j| {
                    let (joint, a, c) = match *j {
                        JointRef::Spring(i) => {
                            let slot = spring_slot[i as usize];
                            let s = si.joints.springs.get(slot as usize)?;
                            (Joint::Spring(slot), s.a, s.b)
                        }
                        JointRef::Rope(i) => {
                            let slot = rope_slot[i as usize];
                            let r = si.joints.ropes.get(slot as usize)?;
                            (Joint::Rope(slot), r.a, r.b)
                        }
                        JointRef::Weld(i) => {
                            let slot = weld_slot[i as usize];
                            let w = si.joints.welds.get(slot as usize)?;
                            (Joint::Weld(slot), w.a, w.b)
                        }
                    };
                    Some((joint, a, c))
                })
                .collect();
            let counts = [si.joints.springs.len(), si.joints.ropes.len(), si.joints.welds.len()];
            si.island = sequential::Island::new(n_bodies, &joints, counts);
            si.rest = sequential::Rest::new(n_bodies);
            si.ccd = ccd();
        }
        World {
            settings: b.settings,
            bodies,
            world_polys: shapes.iter().map(|s| s.local).collect(),
            aabbs: vec![
                Aabb {
                    min: Vec2::ZERO,
                    max: Vec2::ZERO
                };
                shapes.len()
            ],
            margins: vec![0.0; shapes.len()],
            sap: SweepAndPrune::new(n_bodies - 1),
            body_aabbs: vec![
                Aabb {
                    min: Vec2::ZERO,
                    max: Vec2::ZERO
                };
                n_bodies - 1
            ],
            body_shapes,
            parts,
            filters: shapes
                .iter()
                .map(|s| ShapeFilter {
                    part: s.part,
                    group: s.group,
                    collide_within_group: s.collide_within_group,
                })
                .collect(),
            shapes,
            static_index: StaticIndex::new(&static_aabbs),
            statics,
            springs,
            spring_slot,
            rope_batches: rope_batches(&ropes, &rope_ranges),
            ropes,
            rope_slot,
            rings,
            excluded,
            contacts: Vec::new(),
            contact_schedule: ContactSchedule::default(),
            contact_batches: ContactBatches::default(),
            step_count: 0,
            time: 0.0,
            sequential,
            dyn4j_contacts,
            contacts_fresh: false,
        }
    }

    /// The settings this world runs with.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }
    /// Simulated time so far, in seconds.
    pub fn time(&self) -> f64 {
        self.time
    }
    /// Number of steps taken so far.
    pub fn step_count(&self) -> u64 {
        self.step_count
    }
    /// Number of simulated rigid bodies (welded parts count once; the static world is excluded).
    pub fn body_count(&self) -> usize {
        self.bodies.len() - 1
    }
    /// Number of active springs (those joining two different bodies).
    pub fn spring_count(&self) -> usize {
        self.springs.len()
    }
    /// Number of contact manifolds found in the last step.
    pub fn contact_count(&self) -> usize {
        self.contacts.len()
    }

    /// Advances the world by one time step `dt`.
    pub fn step(&mut self) -> Result<(), PhysicsError> {
        if self.sequential.is_some() {
            return self.step_sequential();
        }
        if self.dyn4j_contacts.is_some() {
            return self.step_soft_dyn4j_contacts();
        }
        self.apply_pressure();
        self.integrate_velocities(self.settings.dt, true);
        self.detect_contacts();
        self.contact_schedule.build(&self.contacts, self.bodies.len());
        self.contact_batches
            .build(&self.contacts, &self.contact_schedule, &self.bodies);
        self.solve_substeps();
        self.contact_batches.write_back(&mut self.contacts);
        apply_restitution(
            &mut self.contacts,
            &mut self.bodies,
            self.settings.restitution_threshold,
        );
        self.end_step()
    }

    /// One step of the sequential-impulse solver (dyn4j's order, see [`sequential`]): one whole
    /// pipeline of `dt`, or `sequential_substeps` of them of `dt / sequential_substeps` each.
    fn step_sequential(&mut self) -> Result<(), PhysicsError> {
        let params = sequential::Params::of(&self.settings);
        let n = self.settings.sequential_substeps;
        // pressure is a force of the step's start positions, held (like external forces) over
        // every sub-step
        self.apply_pressure();
        for sub in 0..n {
            if !self.contacts_fresh {
                self.detect_sequential_contacts();
            }
            if let Some(si) = &mut self.sequential {
                si.ccd.remember_start(&self.bodies);
            }
            // external forces act on every sub-step and are cleared after the last
            self.integrate_velocities(params.dt, sub + 1 == n);
            if let Some(si) = &mut self.sequential {
                si.rest.hold(&mut self.bodies);
                si.solve(&mut self.bodies, &self.contacts, static_of_key, &params);
            }
            self.detect_sequential_contacts();
        }
        self.end_step()
    }

    /// One step of the soft solver with dyn4j's contacts ([`Dyn4jContacts`]): the contacts
    /// detected at the end of the last step are warm started, swept with the springs in every
    /// sub-step, then pushed apart by the position pass; continuous collision last.
    fn step_soft_dyn4j_contacts(&mut self) -> Result<(), PhysicsError> {
        let params = sequential::Params::of(&self.settings);
        self.apply_pressure();
        if !self.contacts_fresh {
            self.detect_dyn4j_contacts(&params);
        }
        let n = self.substep_count();
        // taken out for the step (the springs and bodies are borrowed beside it), put back below
        let Some(mut dc) = self.dyn4j_contacts.take() else {
            unreachable!("called only with dyn4j contacts")
        };
        dc.remember_start(&self.bodies);
        self.integrate_velocities(self.settings.dt, true);
        dc.initialize(&mut self.bodies, &params);
        let s = &self.settings;
        let h = s.dt / n as f64;
        let soft = Softness::new(s.contact_hertz.min(0.25 / h), s.contact_damping_ratio, h);
        let (max_v, max_w) = (s.max_translation / s.dt, s.max_rotation / s.dt);
        for sub in 0..n {
            self.springs.prepare(&self.bodies, h, sub == 0);
            for _ in 0..s.iterations {
                self.springs.solve(&mut self.bodies);
            }
            let (ropes, batches) = (&mut self.ropes, &self.rope_batches);
            solve_ropes(
                ropes,
                batches,
                &mut self.bodies,
                soft,
                h,
                s.dt,
                s.contact_push_max,
                true,
                sub == 0,
            );
            for _ in 0..s.iterations {
                dc.solve_velocities(&mut self.bodies);
            }
            integrate_positions(&mut self.bodies, h, max_v, max_w);
        }
        dc.finish(&mut self.bodies, &self.contacts, static_of_key, &params);
        self.dyn4j_contacts = Some(dc);
        self.detect_dyn4j_contacts(&params);
        self.end_step()
    }

    /// Detects the contacts of the present positions and hands them to [`Dyn4jContacts`].
    fn detect_dyn4j_contacts(&mut self, params: &sequential::Params) {
        self.detect_contacts();
        if let Some(dc) = &mut self.dyn4j_contacts {
            dc.collect(&self.contacts, &self.bodies, params);
        }
        self.contacts_fresh = true;
    }

    /// Detects the contacts of the present positions and hands them to the sequential solver.
    fn detect_sequential_contacts(&mut self) {
        self.detect_contacts();
        if let Some(si) = &mut self.sequential {
            let oldest_first = self.settings.dyn4j_version() == Dyn4jVersion::V4_2_1;
            si.contacts
                .collect(&self.contacts, &self.bodies, self.settings.warm_starting, oldest_first);
        }
        self.contacts_fresh = true;
    }

    /// Adds every pressure ring's forces, from the positions at the start of the step.
    fn apply_pressure(&mut self) {
        let (springs, sequential) = (&self.springs, &self.sequential);
        for ring in &self.rings {
            ring.apply(&mut self.bodies, |slot| match sequential {
                Some(si) => si.joints.springs[slot as usize].rest,
                None => springs.rest(slot),
            });
        }
    }

    /// Gravity, external forces and damping over `dt` (semi-implicit Euler); `clear` resets the
    /// external forces afterwards.
    #[inline(never)]
    fn integrate_velocities(&mut self, dt: f64, clear: bool) {
        let g = self.settings.gravity;
        let b = &mut self.bodies;
        for i in 1..b.len() {
            let lin = (1.0 - dt * b.lin_damp[i]).clamp(0.0, 1.0);
            let ang = (1.0 - dt * b.ang_damp[i]).clamp(0.0, 1.0);
            b.state[i].vel = (b.state[i].vel + (g + b.force[i] * b.state[i].inv_mass) * dt) * lin;
            b.state[i].omega = (b.state[i].omega + b.torque[i] * b.state[i].inv_inertia * dt) * ang;
            if clear {
                b.force[i] = Vec2::ZERO;
                b.torque[i] = 0.0;
            }
        }
    }

    /// Finds touching (or nearly touching) shape pairs and turns them into contact constraints.
    #[inline(never)]
    fn detect_contacts(&mut self) {
        self.contacts.clear();
        // speculative margin of each shape: the base gap plus how far its body may travel this
        // step, so fast bodies meet contacts before they overlap (no tunnelling or deep overlaps)
        // the sequential-impulse solver (like dyn4j) only knows shapes that overlap
        let speculative = self.settings.solver == Solver::SoftSubsteps && self.dyn4j_contacts.is_none();
        let collide = if speculative {
            collide_polygons
        } else {
            collide_polygons_dyn4j
        };
        let base = if speculative {
            self.settings.speculative_distance
        } else {
            0.0
        };
        let dt = self.settings.dt;
        for (k, s) in self.shapes.iter().enumerate() {
            let st = &self.bodies.state[s.body as usize];
            let poly = &mut self.world_polys[k];
            poly.set_transformed(&s.local, st.rot, st.pos);
            let reach = s.radius * st.omega.abs() + st.vel.length();
            self.margins[k] = if speculative { 0.5 * base + reach * dt } else { 0.0 };
            self.aabbs[k] = Aabb::of_points(poly.verts()).inflated(self.margins[k] + poly.radius);
        }
        for (b, &(lo, hi)) in self.body_shapes.iter().enumerate().skip(1) {
            let boxes = &self.aabbs[lo as usize..hi as usize];
            self.body_aabbs[b - 1] = boxes.iter().skip(1).fold(boxes[0], |acc, x| Aabb {
                min: acc.min.min(x.min),
                max: acc.max.max(x.max),
            });
        }
        let Self {
            shapes,
            filters,
            statics,
            static_index,
            world_polys,
            aabbs,
            body_aabbs,
            body_shapes,
            contacts,
            bodies,
            sap,
            excluded,
            margins,
            ..
        } = self;
        for (b, &(lo, hi)) in body_shapes.iter().enumerate().skip(1) {
            // a body whose box misses every static polygon has no shape that touches one (its
            // box is the union of its shapes' boxes)
            let body_box = body_aabbs[b - 1].inflated(0.5 * base);
            let near = &statics[static_index.candidates(body_box.min.x, body_box.max.x)];
            if !near.iter().any(|st| body_box.overlaps(&st.aabb)) {
                continue;
            }
            for k in lo as usize..hi as usize {
                let s = &shapes[k];
                let bb = aabbs[k].inflated(0.5 * base);
                let range = static_index.candidates(bb.min.x, bb.max.x);
                for (static_id, st) in range.clone().zip(&statics[range]) {
                    if !bb.overlaps(&st.aabb) {
                        continue;
                    }
                    // static is A so that the normal points from the ground into the body
                    let m = collide(&st.polygon, &world_polys[k], 0.5 * base + margins[k]);
                    if m.count > 0 && (speculative || overlapping(&m)) {
                        let friction = (st.friction * s.friction).sqrt();
                        let restitution = st.restitution.max(s.restitution);
                        let mut c =
                            ContactConstraint::new(bodies, &m, NONE, k as u32, 0, s.body, friction, restitution);
                        c.key = static_contact_key(static_id, k);
                        contacts.push(c);
                    }
                }
            }
        }
        sap.for_each_pair(
            body_aabbs,
            |k| k as u32,
            |ba, bb| {
                let (ra, rb) = (body_shapes[ba as usize + 1], body_shapes[bb as usize + 1]);
                let (ra, rb) = (ra.0 as usize..ra.1 as usize, rb.0 as usize..rb.1 as usize);
                // a shape can only touch a shape of the other body if it reaches that body's box
                // (the union of its shapes' boxes): filtering both sides first keeps the pairs, and
                // their order, and skips most of the pairwise tests
                let (box_a, box_b) = (&body_aabbs[ba as usize], &body_aabbs[bb as usize]);
                let near_b = ShapeSubset::reaching(&aabbs[rb.clone()], box_a);
                for i in ra {
                    let (bi, fi) = (&aabbs[i], &filters[i]);
                    if !bi.overlaps(box_b) {
                        continue;
                    }
                    for j in near_b.iter().map(|k| rb.start + k) {
                        let (bj, fj) = (&aabbs[j], &filters[j]);
                        if !bi.overlaps(bj) {
                            continue;
                        }
                        if fi.group == fj.group && !(fi.collide_within_group && fj.collide_within_group) {
                            continue;
                        }
                        if excluded.contains(fi.part, fj.part) {
                            continue;
                        }
                        let (si, sj) = (&shapes[i], &shapes[j]);
                        let margin = margins[i] + margins[j];
                        let m = collide(&world_polys[i], &world_polys[j], margin);
                        if m.count > 0 && (speculative || overlapping(&m)) {
                            let friction = (si.friction * sj.friction).sqrt();
                            let restitution = si.restitution.max(sj.restitution);
                            let mut c = ContactConstraint::new(
                                bodies,
                                &m,
                                i as u32,
                                j as u32,
                                si.body,
                                sj.body,
                                friction,
                                restitution,
                            );
                            c.key = ((i as u64) << 32) | j as u64;
                            contacts.push(c);
                        }
                    }
                }
            },
        );
    }

    /// Sub-steps: solve springs, ropes and contacts, integrate positions, relax contacts.
    #[inline(never)]
    fn solve_substeps(&mut self) {
        let s = &self.settings;
        let n = self.substep_count();
        let h = s.dt / n as f64;
        let hertz = s.contact_hertz.min(0.25 / h);
        let soft = Softness::new(hertz, s.contact_damping_ratio, h);
        let static_soft = Softness::new((2.0 * hertz).min(0.25 / h), s.contact_damping_ratio, h);
        let mut pass = ContactPass {
            soft,
            static_soft,
            inv_h: 1.0 / h,
            push_max: s.contact_push_max,
            use_bias: true,
        };
        let (max_v, max_w) = (s.max_translation / s.dt, s.max_rotation / s.dt);
        for sub in 0..n {
            self.springs.prepare(&self.bodies, h, sub == 0);
            for _ in 0..s.iterations {
                self.springs.solve(&mut self.bodies);
            }
            solve_ropes(
                &mut self.ropes,
                &self.rope_batches,
                &mut self.bodies,
                soft,
                h,
                s.dt,
                pass.push_max,
                true,
                sub == 0,
            );
            pass.use_bias = true;
            self.contact_batches.solve(&mut self.bodies, &pass);
            integrate_positions(&mut self.bodies, h, max_v, max_w);
            pass.use_bias = false;
            self.contact_batches.solve(&mut self.bodies, &pass);
        }
    }

    /// Sub-steps for this step: the configured number, or more when the fastest body would travel
    /// farther than `substep_travel` in one sub-step (capped at four times the configured number).
    fn substep_count(&self) -> u32 {
        let s = &self.settings;
        if s.substep_travel <= 0.0 {
            return s.substeps;
        }
        let fastest = self.bodies.state[1..]
            .iter()
            .map(|b| b.vel.length_squared())
            .fold(0.0, f64::max)
            .sqrt();
        let wanted = (fastest * s.dt / s.substep_travel).ceil();
        if wanted.is_finite() {
            (wanted as u32).clamp(s.substeps, 4 * s.substeps)
        } else {
            s.substeps
        }
    }

    /// Marks parts that touch static geometry or a part of another group.
    #[inline(never)]
    fn update_touching(&mut self) {
        for p in &mut self.parts {
            p.touching = false;
        }
        let tol = self.settings.touch_tolerance;
        for c in &self.contacts {
            let touching = c.points[..c.count].iter().any(|p| c.separation(&self.bodies, p) <= tol);
            if !touching {
                continue;
            }
            let sb = &self.shapes[c.shape_b as usize];
            if c.shape_a == NONE {
                self.parts[sb.part as usize].touching = true;
            } else {
                let sa = &self.shapes[c.shape_a as usize];
                if sa.group != sb.group {
                    self.parts[sa.part as usize].touching = true;
                    self.parts[sb.part as usize].touching = true;
                }
            }
        }
    }

    /// What every solver's step ends with: touching flags, the clock, the check for non-finite
    /// state.
    fn end_step(&mut self) -> Result<(), PhysicsError> {
        self.update_touching();
        self.step_count += 1;
        self.time += self.settings.dt;
        self.check_finite()
    }

    #[inline(never)]
    fn check_finite(&self) -> Result<(), PhysicsError> {
        let b = &self.bodies;
        for i in 1..b.len() {
            if !(b.state[i].pos.is_finite()
                && b.state[i].vel.is_finite()
                && b.state[i].omega.is_finite()
                && b.state[i].rot.c.is_finite())
            {
                return Err(PhysicsError::NonFinite {
                    step: self.step_count,
                    body: i - 1,
                });
            }
        }
        Ok(())
    }

    // ---- queries and control -------------------------------------------------------------

    fn part(&self, h: PartHandle) -> &Part {
        &self.parts[h.0 as usize]
    }
    /// World position of a part's frame origin.
    pub fn part_position(&self, h: PartHandle) -> Vec2 {
        let p = self.part(h);
        let b = p.body as usize;
        self.bodies.state[b].pos + self.bodies.state[b].rot.apply(p.local)
    }
    /// World angle of a part (radians, counter-clockwise).
    pub fn part_angle(&self, h: PartHandle) -> f64 {
        let r = self.bodies.state[self.part(h).body as usize].rot;
        r.s.atan2(r.c)
    }
    /// World position of a point given in the part's frame.
    pub fn part_point(&self, h: PartHandle, local: Vec2) -> Vec2 {
        let p = self.part(h);
        let b = p.body as usize;
        self.bodies.state[b].pos + self.bodies.state[b].rot.apply(p.local + local)
    }
    /// Linear velocity of a part's frame origin.
    pub fn part_velocity(&self, h: PartHandle) -> Vec2 {
        let p = self.part(h);
        let b = p.body as usize;
        let r = self.bodies.state[b].rot.apply(p.local);
        self.bodies.state[b].vel + Vec2::cross_scalar_left(self.bodies.state[b].omega, r)
    }
    /// Angular velocity of a part.
    pub fn part_angular_velocity(&self, h: PartHandle) -> f64 {
        self.bodies.state[self.part(h).body as usize].omega
    }
    /// Whether the part touched static geometry or another group's part in the last step.
    pub fn part_touching(&self, h: PartHandle) -> bool {
        self.part(h).touching
    }
    /// Whether two parts were welded into the same rigid body.
    pub fn same_body(&self, a: PartHandle, b: PartHandle) -> bool {
        self.part(a).body == self.part(b).body
    }
    /// Adds a force (applied at the part's frame origin) for the next step only.
    pub fn apply_force(&mut self, h: PartHandle, force: Vec2) {
        let p = *self.part(h);
        let b = p.body as usize;
        let r = self.bodies.state[b].rot.apply(p.local);
        self.bodies.force[b] += force;
        self.bodies.torque[b] += r.cross(force);
    }
    /// Moves every body rigidly by `delta` (used to place things before simulating).
    pub fn translate_all(&mut self, delta: Vec2) {
        for s in &mut self.bodies.state[1..] {
            s.pos += delta;
        }
        self.contacts_fresh = false;
    }
    /// Sets a spring's rest length (takes effect at the next step).
    #[inline]
    pub fn set_spring_rest_length(&mut self, h: SpringHandle, rest: f64) {
        let slot = self.spring_slot[h.0 as usize];
        if slot == NONE {
            return;
        }
        let wakes = self.settings.dyn4j_version() == Dyn4jVersion::V4_2_1;
        match &mut self.sequential {
            Some(si) => {
                let spring = &mut si.joints.springs[slot as usize];
                // dyn4j 4.2.1's setRestDistance wakes both bodies on a new value only
                if wakes && spring.rest != rest {
                    let (a, b) = (spring.a as usize, spring.b as usize);
                    si.rest.wake(a);
                    si.rest.wake(b);
                }
                spring.rest = rest;
            }
            None => self.springs.set_rest(slot, rest),
        }
    }
    /// A spring's current rest length (`None` when its two parts were welded together).
    pub fn spring_rest_length(&self, h: SpringHandle) -> Option<f64> {
        let slot = self.spring_slot[h.0 as usize];
        (slot != NONE).then(|| match &self.sequential {
            Some(si) => si.joints.springs[slot as usize].rest,
            None => self.springs.rest(slot),
        })
    }
    /// Sets a pressure ring's pressure (acts from the next step on).
    pub fn set_ring_pressure(&mut self, h: RingHandle, pressure: f64) {
        self.rings[h.0 as usize].pressure = pressure;
    }
    /// A pressure ring's current pressure.
    pub fn ring_pressure(&self, h: RingHandle) -> f64 {
        self.rings[h.0 as usize].pressure
    }
    /// Area enclosed by a ring's part centres now (shoelace formula; positive whichever way the
    /// ring was listed, as long as it does not fold over itself).
    pub fn ring_area(&self, h: RingHandle) -> f64 {
        self.rings[h.0 as usize].signed_area(&self.bodies).abs()
    }
    /// Whether a rope is simulated (false when its two parts were welded together).
    pub fn rope_active(&self, h: RopeHandle) -> bool {
        self.rope_slot[h.0 as usize] != NONE
    }
    /// Distance from `origin` along unit `dir` to the first static polygon, within `max_distance`.
    pub fn ray_cast_static(&self, origin: Vec2, dir: Vec2, max_distance: f64) -> Option<f64> {
        let end = origin + dir * max_distance;
        let (x0, x1) = (origin.x.min(end.x), origin.x.max(end.x));
        let mut best: Option<f64> = None;
        for st in &self.statics[self.static_index.candidates(x0, x1)] {
            if let Some(t) = ray_cast_polygon(&st.polygon, origin, dir, max_distance) {
                if best.is_none_or(|b| t < b) {
                    best = Some(t);
                }
            }
        }
        best
    }
    /// The static polygons, in x order (for drawing).
    pub fn static_polygons(&self) -> impl Iterator<Item = &Polygon> {
        self.statics.iter().map(|s| &s.polygon)
    }
    /// Total kinetic energy (translational plus rotational).
    pub fn kinetic_energy(&self) -> f64 {
        let b = &self.bodies;
        (1..b.len())
            .map(|i| {
                0.5 * b.mass[i] * b.state[i].vel.length_squared()
                    + 0.5 * b.state[i].omega * b.state[i].omega / b.state[i].inv_inertia.max(1e-300)
            })
            .sum()
    }
    /// Total mass of the dynamic bodies.
    pub fn total_mass(&self) -> f64 {
        self.bodies.mass[1..].iter().sum()
    }
}

/// Overlap below which shapes only touch, for the sequential-impulse solver: dyn4j makes no
/// contact of shapes that touch (depth 0), and its intersection test cannot tell an overlap of a
/// few rounding errors (coordinates up to ~10³, so ~10⁻¹³) from touching.
const TOUCHING_OVERLAP: f64 = 1e-12;

/// Whether a manifold has a point of actual overlap (see [`TOUCHING_OVERLAP`]).
fn overlapping(m: &Manifold) -> bool {
    m.points[..m.count].iter().any(|p| p.separation < -TOUCHING_OVERLAP)
}

/// The key of a contact between static polygon `static_id` and dynamic shape `shape`: distinct
/// from every shape–shape key (whose high half is a shape index, far below 2³¹).
fn static_contact_key(static_id: usize, shape: usize) -> u64 {
    (1 << 63) | ((static_id as u64) << 32) | shape as u64
}

/// The static polygon of a key made by [`static_contact_key`].
fn static_of_key(key: u64) -> u32 {
    ((key >> 32) & 0x7fff_ffff) as u32
}

/// The shapes of one body (by index within the body) whose boxes reach a given box, in order.
#[derive(Debug, Clone, Copy)]
enum ShapeSubset {
    /// Bit k set: shape k reaches the box (bodies of at most 64 shapes).
    Mask(u64),
    /// Every shape (larger bodies are not filtered).
    All(usize),
}

impl ShapeSubset {
    /// The shapes among `boxes` that overlap `target`.
    #[inline]
    fn reaching(boxes: &[Aabb], target: &Aabb) -> ShapeSubset {
        if boxes.len() > 64 {
            return ShapeSubset::All(boxes.len());
        }
        let mask = boxes
            .iter()
            .enumerate()
            .fold(0u64, |m, (k, b)| m | (u64::from(b.overlaps(target)) << k));
        ShapeSubset::Mask(mask)
    }

    /// Indices of the shapes in the subset, in increasing order.
    #[inline]
    fn iter(self) -> impl Iterator<Item = usize> {
        let (mut mask, all) = match self {
            ShapeSubset::Mask(m) => (m, 0..0),
            ShapeSubset::All(n) => (0, 0..n),
        };
        let bits = std::iter::from_fn(move || {
            (mask != 0).then(|| {
                let k = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                k
            })
        });
        bits.chain(all)
    }
}

/// x += v·h and θ += ω·h, after clamping speeds to the per-step limits.
#[inline(never)]
fn integrate_positions(b: &mut Bodies, h: f64, max_v: f64, max_w: f64) {
    for s in &mut b.state[1..] {
        let v2 = s.vel.length_squared();
        if v2 > max_v * max_v {
            s.vel *= max_v / v2.sqrt();
        }
        if s.omega.abs() > max_w {
            s.omega = max_w * s.omega.signum();
        }
        s.pos += s.vel * h;
        // rotate the rotation by ω·h without trigonometry, then renormalise
        let q = s.rot;
        let w = s.omega * h;
        let (c, sn) = (q.c - w * q.s, q.s + w * q.c);
        let inv = 1.0 / (c * c + sn * sn).sqrt();
        s.rot = Rot {
            c: c * inv,
            s: sn * inv,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn boxes(n: std::ops::Range<usize>) -> impl Strategy<Value = Vec<Aabb>> {
        prop::collection::vec((-5.0..5.0f64, -5.0..5.0f64, 0.0..3.0f64, 0.0..3.0f64), n).prop_map(|v| {
            v.into_iter()
                .map(|(x, y, w, h)| Aabb {
                    min: Vec2::new(x, y),
                    max: Vec2::new(x + w, y + h),
                })
                .collect()
        })
    }

    fn union(b: &[Aabb]) -> Aabb {
        b.iter().skip(1).fold(b[0], |acc, x| Aabb {
            min: acc.min.min(x.min),
            max: acc.max.max(x.max),
        })
    }

    proptest! {
        /// Filtering both bodies' shapes by the other body's box finds exactly the overlapping
        /// shape pairs of the full double loop, in the same order.
        #[test]
        fn body_box_filter_keeps_every_overlapping_pair_in_order(a in boxes(1..6), b in boxes(1..70)) {
            let (box_a, box_b) = (union(&a), union(&b));
            let all: Vec<(usize, usize)> = (0..a.len())
                .flat_map(|i| (0..b.len()).map(move |j| (i, j)))
                .filter(|&(i, j)| a[i].overlaps(&b[j]))
                .collect();
            let near_b = ShapeSubset::reaching(&b, &box_a);
            let filtered: Vec<(usize, usize)> = (0..a.len())
                .filter(|&i| a[i].overlaps(&box_b))
                .flat_map(|i| near_b.iter().map(move |j| (i, j)))
                .filter(|&(i, j)| a[i].overlaps(&b[j]))
                .collect();
            prop_assert_eq!(filtered, all);
        }
    }

    #[test]
    fn shape_subset_lists_reaching_shapes_in_order_and_all_of_a_large_body() {
        let unit = |x: f64| Aabb {
            min: Vec2::new(x, 0.0),
            max: Vec2::new(x + 1.0, 1.0),
        };
        let target = Aabb {
            min: Vec2::new(2.5, 0.5),
            max: Vec2::new(6.0, 0.6),
        };
        let row: Vec<Aabb> = (0..10).map(|k| unit(k as f64)).collect();
        // boxes [k, k+1] that reach [2.5, 6]: k = 2 … 6
        assert_eq!(
            ShapeSubset::reaching(&row, &target).iter().collect::<Vec<_>>(),
            vec![2, 3, 4, 5, 6]
        );
        let long: Vec<Aabb> = (0..65).map(|k| unit(k as f64)).collect();
        assert_eq!(ShapeSubset::reaching(&long, &target).iter().count(), 65);
    }
}
