//! Building a world: parts, welds, springs, ropes and static geometry.
//!
//! Parts joined by welds are merged into one rigid body when the world is built: the weld is then
//! exactly rigid and costs nothing per step. Handles to the original parts stay valid.

use super::pressure::EdgeLength;
use super::settings::{Dyn4jVersion, SpringMassModel, WorldSettings};
use super::world::{PartHandle, RingHandle, RopeHandle, SpringHandle, World};
use crate::geometry::shape::Polygon;
use crate::math::Vec2;
use crate::PhysicsError;

/// Description of one rigid part: a convex polygon with uniform density.
#[derive(Debug, Clone, PartialEq)]
pub struct PartDesc {
    /// World position of the part's frame origin.
    pub position: Vec2,
    /// Polygon in the part's own frame.
    pub shape: Polygon,
    /// Mass per unit area.
    pub density: f64,
    /// Coulomb friction coefficient (mixed with the other's as √(μ₁μ₂)).
    pub friction: f64,
    /// Restitution (mixed with the other's as max(e₁, e₂)).
    pub restitution: f64,
    /// Linear velocity damping, 1/s.
    pub linear_damping: f64,
    /// Angular velocity damping, 1/s.
    pub angular_damping: f64,
    /// Collision group: contacts with other groups (or static geometry) count as "touching".
    pub group: u32,
    /// Whether the part may collide with other parts of its own group.
    pub collide_within_group: bool,
    /// Whether the part never rotates (infinite inertia; a body with one such part keeps its angle).
    pub fixed_rotation: bool,
}

impl PartDesc {
    /// A part at `position` with the given shape, density 1, no friction, damping or restitution.
    pub fn new(position: Vec2, shape: Polygon) -> PartDesc {
        PartDesc {
            position,
            shape,
            density: 1.0,
            friction: 0.0,
            restitution: 0.0,
            linear_damping: 0.0,
            angular_damping: 0.0,
            group: 0,
            collide_within_group: true,
            fixed_rotation: false,
        }
    }
    /// Sets the density.
    pub fn density(mut self, d: f64) -> Self {
        self.density = d;
        self
    }
    /// Sets the friction coefficient.
    pub fn friction(mut self, f: f64) -> Self {
        self.friction = f;
        self
    }
    /// Sets the restitution.
    pub fn restitution(mut self, r: f64) -> Self {
        self.restitution = r;
        self
    }
    /// Sets linear and angular damping.
    pub fn damping(mut self, linear: f64, angular: f64) -> Self {
        self.linear_damping = linear;
        self.angular_damping = angular;
        self
    }
    /// Keeps the part from rotating.
    pub fn fixed_rotation(mut self) -> Self {
        self.fixed_rotation = true;
        self
    }
    /// Sets the collision group and whether parts of that group collide with each other.
    pub fn group(mut self, group: u32, collide_within_group: bool) -> Self {
        self.group = group;
        self.collide_within_group = collide_within_group;
        self
    }
}

/// A soft distance constraint between two anchors, defined by natural frequency and damping ratio.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringDesc {
    /// First part and anchor (in that part's frame).
    pub part_a: PartHandle,
    /// Anchor on the first part.
    pub anchor_a: Vec2,
    /// Second part.
    pub part_b: PartHandle,
    /// Anchor on the second part.
    pub anchor_b: Vec2,
    /// Initial rest length (changeable every step).
    pub rest_length: f64,
    /// Natural frequency, Hz.
    pub frequency: f64,
    /// Damping ratio (1 = critical).
    pub damping_ratio: f64,
    /// Which mass turns (frequency, damping ratio) into (stiffness, damping).
    pub mass_model: SpringMassModel,
    /// Whether the two parts may still collide with each other.
    pub collide_connected: bool,
}

/// A rope: the two anchors may not come closer than `min_length` (no upper limit).
#[derive(Debug, Clone, PartialEq)]
pub struct RopeDesc {
    /// First part.
    pub part_a: PartHandle,
    /// Anchor on the first part.
    pub anchor_a: Vec2,
    /// Second part.
    pub part_b: PartHandle,
    /// Anchor on the second part.
    pub anchor_b: Vec2,
    /// Smallest allowed distance between the anchors.
    pub min_length: f64,
    /// Whether the two parts may still collide with each other.
    pub collide_connected: bool,
}

/// A closed ring of parts with gas pressure inside (see [`crate::dynamics::pressure`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PressureRingDesc {
    /// The ring's parts in order (edge i joins part i and part i+1, the last joins the first);
    /// each must be a body of its own (not welded) and appear once.
    pub parts: Vec<PartHandle>,
    /// Which length the force p·L of an edge uses.
    pub length: EdgeLength,
    /// For [`EdgeLength::SpringRest`]: the spring along each edge, in the same order (edge i is
    /// the spring between part i and part i+1); empty otherwise.
    pub springs: Vec<SpringHandle>,
    /// Initial pressure.
    pub pressure: f64,
}

/// A static polygon in world coordinates (terrain, walls).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct StaticDesc {
    pub polygon: Polygon,
    pub friction: f64,
    pub restitution: f64,
}

/// Collects the description of a world, then builds it.
#[derive(Debug, Clone, Default)]
pub struct WorldBuilder {
    pub(crate) settings: WorldSettings,
    pub(crate) parts: Vec<PartDesc>,
    pub(crate) welds: Vec<(PartHandle, PartHandle)>,
    pub(crate) springs: Vec<SpringDesc>,
    pub(crate) ropes: Vec<RopeDesc>,
    pub(crate) statics: Vec<StaticDesc>,
    pub(crate) rings: Vec<PressureRingDesc>,
    pub(crate) excluded: Vec<(PartHandle, PartHandle)>,
    /// Every spring, rope and weld in the order they were added (the sequential-impulse solver
    /// visits joints in this order, as dyn4j visits them in the order they joined its world).
    pub(crate) joint_order: Vec<JointRef>,
}

/// A joint of the builder by kind and index in its kind's list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum JointRef {
    Spring(u32),
    Rope(u32),
    Weld(u32),
}

impl WorldBuilder {
    /// An empty world with the given settings.
    pub fn new(settings: WorldSettings) -> WorldBuilder {
        WorldBuilder {
            settings,
            ..Default::default()
        }
    }
    /// Adds a rigid part.
    pub fn add_part(&mut self, part: PartDesc) -> PartHandle {
        self.parts.push(part);
        PartHandle(self.parts.len() as u32 - 1)
    }
    /// Welds two parts rigidly together (they become one rigid body and never collide).
    pub fn weld(&mut self, a: PartHandle, b: PartHandle) {
        self.joint_order.push(JointRef::Weld(self.welds.len() as u32));
        self.welds.push((a, b));
    }
    /// Adds a soft distance constraint.
    pub fn add_spring(&mut self, spring: SpringDesc) -> SpringHandle {
        self.joint_order.push(JointRef::Spring(self.springs.len() as u32));
        self.springs.push(spring);
        SpringHandle(self.springs.len() as u32 - 1)
    }
    /// Adds a minimum-distance rope.
    pub fn add_rope(&mut self, rope: RopeDesc) -> RopeHandle {
        self.joint_order.push(JointRef::Rope(self.ropes.len() as u32));
        self.ropes.push(rope);
        RopeHandle(self.ropes.len() as u32 - 1)
    }
    /// Adds a pressurised ring of parts.
    pub fn add_pressure_ring(&mut self, ring: PressureRingDesc) -> RingHandle {
        self.rings.push(ring);
        RingHandle(self.rings.len() as u32 - 1)
    }
    /// Adds a static convex polygon (world coordinates; circles are not supported as statics).
    pub fn add_static_polygon(&mut self, polygon: Polygon, friction: f64, restitution: f64) {
        self.statics.push(StaticDesc {
            polygon,
            friction,
            restitution,
        });
    }
    /// Prevents two parts from ever colliding.
    pub fn exclude_collision(&mut self, a: PartHandle, b: PartHandle) {
        self.excluded.push((a, b));
    }
    /// Records which dyn4j the parts being added were made for (a voxel preset's engine); the
    /// sequential-impulse solver follows it unless the settings name a version.
    pub fn made_for(&mut self, version: Dyn4jVersion) {
        if self.settings.dyn4j.is_none() {
            self.settings.dyn4j = Some(version);
        }
    }
    /// The settings the world will run with.
    pub fn settings(&self) -> &WorldSettings {
        &self.settings
    }
    /// Number of parts added so far.
    pub fn part_count(&self) -> usize {
        self.parts.len()
    }

    /// Validates the description and builds the world.
    pub fn build(self) -> Result<World, PhysicsError> {
        self.settings
            .validate()
            .map_err(|e| PhysicsError::Invalid(e.to_string()))?;
        let n = self.parts.len() as u32;
        let check = |h: PartHandle, what: &str| {
            if h.0 < n {
                Ok(())
            } else {
                Err(PhysicsError::Invalid(format!("{what} refers to unknown part {}", h.0)))
            }
        };
        for (i, p) in self.parts.iter().enumerate() {
            let fields = [
                ("density", p.density),
                ("friction", p.friction),
                ("restitution", p.restitution),
                ("linear_damping", p.linear_damping),
                ("angular_damping", p.angular_damping),
            ];
            for (name, v) in fields {
                if !(v.is_finite() && v >= 0.0) {
                    return Err(PhysicsError::Invalid(format!(
                        "part {i}: {name} must be finite and ≥ 0, got {v}"
                    )));
                }
            }
            if p.density <= 0.0 {
                return Err(PhysicsError::Invalid(format!("part {i}: density must be > 0")));
            }
            if !p.position.is_finite() {
                return Err(PhysicsError::Invalid(format!("part {i}: position must be finite")));
            }
        }
        for &(a, b) in self.welds.iter().chain(self.excluded.iter()) {
            check(a, "weld or exclusion")?;
            check(b, "weld or exclusion")?;
        }
        for s in &self.springs {
            check(s.part_a, "spring")?;
            check(s.part_b, "spring")?;
            if !(s.frequency > 0.0 && s.damping_ratio >= 0.0 && s.rest_length >= 0.0) {
                return Err(PhysicsError::Invalid(
                    "spring: frequency must be > 0, damping ratio and rest length ≥ 0".into(),
                ));
            }
        }
        for r in &self.ropes {
            check(r.part_a, "rope")?;
            check(r.part_b, "rope")?;
        }
        for (i, st) in self.statics.iter().enumerate() {
            if st.polygon.count < 3 || st.polygon.verts().iter().any(|v| !v.is_finite()) {
                return Err(PhysicsError::Invalid(format!(
                    "static polygon {i}: must be a finite polygon with at least 3 vertices"
                )));
            }
        }
        self.validate_rings()?;
        Ok(World::from_builder(self))
    }

    fn validate_rings(&self) -> Result<(), PhysicsError> {
        let n = self.parts.len() as u32;
        let welded: std::collections::HashSet<u32> = self.welds.iter().flat_map(|&(a, b)| [a.0, b.0]).collect();
        for (i, r) in self.rings.iter().enumerate() {
            let bad = |why: String| Err(PhysicsError::Invalid(format!("pressure ring {i}: {why}")));
            if r.parts.len() < 3 {
                return bad(format!("needs at least 3 parts, got {}", r.parts.len()));
            }
            let mut seen = std::collections::HashSet::new();
            for p in &r.parts {
                if p.0 >= n {
                    return bad(format!("refers to unknown part {}", p.0));
                }
                if welded.contains(&p.0) {
                    return bad(format!(
                        "part {} is welded; ring parts must be bodies of their own",
                        p.0
                    ));
                }
                if !seen.insert(p.0) {
                    return bad(format!("part {} appears twice", p.0));
                }
            }
            if !r.pressure.is_finite() {
                return bad(format!("pressure must be finite, got {}", r.pressure));
            }
            match r.length {
                EdgeLength::Actual if !r.springs.is_empty() => {
                    return bad("springs are only used with EdgeLength::SpringRest".into())
                }
                EdgeLength::SpringRest if r.springs.len() != r.parts.len() => {
                    return bad(format!(
                        "needs one spring per edge ({}), got {}",
                        r.parts.len(),
                        r.springs.len()
                    ))
                }
                _ => {}
            }
            if let Some(s) = r.springs.iter().find(|s| s.0 as usize >= self.springs.len()) {
                return bad(format!("refers to unknown spring {}", s.0));
            }
        }
        Ok(())
    }
}
