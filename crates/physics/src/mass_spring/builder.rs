//! Building a mass-spring world: add points, springs, bodies of quads, length limits and
//! actuators, then [`MassSpringBuilder::build`] checks everything and preallocates.

use super::actuators::Actuators;
use super::bodies::Bodies;
use super::handles::{ActuatorId, BodyId, PointId, QuadId, SpringId};
use super::integrator::Rk4;
use super::points::Points;
use super::projection::Projection;
use super::quad_geometry::{twice_signed_area, Aabb};
use super::runs::Runs;
use super::springs::{length, Springs};
use super::stage_points::{hops_from_free, HOPS};
use super::validate;
use super::world::MassSpringWorld;
use super::{MassSpringError, MassSpringSettings};

/// Tolerance within which boundary quads' boxes at build time make them neighbours.
const NEIGHBOUR_TOLERANCE: f64 = 1e-9;

/// A point mass to add.
#[derive(Debug, Clone, PartialEq)]
pub struct PointDesc {
    /// Position.
    pub position: (f64, f64),
    /// Initial velocity.
    pub velocity: (f64, f64),
    /// Mass (EvoGym: 1 per point).
    pub mass: f64,
    /// A fixed point never moves (EvoGym's terrain is made of fixed points).
    pub fixed: bool,
}

impl PointDesc {
    /// A free point of mass 1 at rest at `(x, y)`.
    pub fn at(x: f64, y: f64) -> Self {
        Self {
            position: (x, y),
            velocity: (0.0, 0.0),
            mass: 1.0,
            fixed: false,
        }
    }

    /// With mass `m`.
    pub fn mass(mut self, m: f64) -> Self {
        self.mass = m;
        self
    }

    /// Fixed in place.
    pub fn fixed(mut self) -> Self {
        self.fixed = true;
        self
    }

    /// Moving at `(vx, vy)` at the start.
    pub fn velocity(mut self, vx: f64, vy: f64) -> Self {
        self.velocity = (vx, vy);
        self
    }
}

/// A spring to add.
#[derive(Debug, Clone, PartialEq)]
pub struct SpringDesc {
    /// First end.
    pub a: PointId,
    /// Second end.
    pub b: PointId,
    /// Force per unit stretch.
    pub stiffness: f64,
    /// Initial rest length; `None`: the distance between the ends at build time.
    pub rest_length: Option<f64>,
    /// Loose band: after each substep the length is pushed back toward
    /// `rest × [1 - band, 1 + band]` (EvoGym: 0.25 for every spring).
    pub band: f64,
}

impl SpringDesc {
    /// A spring between `a` and `b` with rest length their current distance and band 0.25.
    pub fn between(a: PointId, b: PointId, stiffness: f64) -> Self {
        Self {
            a,
            b,
            stiffness,
            rest_length: None,
            band: 0.25,
        }
    }

    /// With initial rest length `l`.
    pub fn rest_length(mut self, l: f64) -> Self {
        self.rest_length = Some(l);
        self
    }

    /// With loose band `band`.
    pub fn band(mut self, band: f64) -> Self {
        self.band = band;
        self
    }
}

/// A body to add: a group of quads that collide as one object.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BodyDesc {
    /// Check the body for self-overlap after every substep (EvoGym: only robots).
    pub watch_self_overlap: bool,
}

impl BodyDesc {
    /// A body not checked for self-overlap.
    pub fn new() -> Self {
        Self::default()
    }

    /// Checked for self-overlap: [`step`](MassSpringWorld::step) fails with
    /// [`MassSpringError::SelfOverlap`] when it folds into itself.
    pub fn watch_self_overlap(mut self) -> Self {
        self.watch_self_overlap = true;
        self
    }
}

/// A quadrilateral of a body: corners in cyclic order (either orientation). Side `i` joins
/// corners `i` and `i + 1`; boundary sides are those on the body's outline, the ones other bodies'
/// points are pushed out through.
#[derive(Debug, Clone, PartialEq)]
pub struct QuadDesc {
    /// The body it belongs to.
    pub body: BodyId,
    /// Corners in cyclic order.
    pub corners: [PointId; 4],
    /// Which sides are on the body's outline.
    pub boundary: [bool; 4],
    /// Sides walked from corner `i + 1` back to corner `i` when a corner's own sides are tested
    /// for crossing another quad's outline. Only an exact touch at an end point depends on it (by
    /// rounding); EvoGym keeps the direction each edge was made with, and this lets a mapper say so.
    pub reversed: [bool; 4],
}

impl QuadDesc {
    /// A quad of `body` with no boundary side.
    pub fn new(body: BodyId, corners: [PointId; 4]) -> Self {
        Self {
            body,
            corners,
            boundary: [false; 4],
            reversed: [false; 4],
        }
    }

    /// With boundary sides `sides` (side `i` joins corners `i` and `i + 1`).
    pub fn boundary(mut self, sides: [bool; 4]) -> Self {
        self.boundary = sides;
        self
    }

    /// With sides `sides` walked backwards in the crossing test (see [`QuadDesc::reversed`]).
    pub fn reversed(mut self, sides: [bool; 4]) -> Self {
        self.reversed = sides;
        self
    }
}

/// Collects the description of a world; [`build`](Self::build) checks it.
#[derive(Debug, Clone, Default)]
pub struct MassSpringBuilder {
    settings: MassSpringSettings,
    points: Vec<PointDesc>,
    springs: Vec<SpringDesc>,
    limits: Vec<(SpringId, f64)>,
    bodies: Vec<BodyDesc>,
    quads: Vec<QuadDesc>,
    actuators: Vec<Vec<SpringId>>,
}

impl MassSpringBuilder {
    /// An empty world with `settings`.
    pub fn new(settings: MassSpringSettings) -> Self {
        Self {
            settings,
            ..Self::default()
        }
    }

    /// Adds a point.
    pub fn add_point(&mut self, p: PointDesc) -> PointId {
        self.points.push(p);
        PointId(self.points.len() as u32 - 1)
    }

    /// Adds a spring.
    pub fn add_spring(&mut self, s: SpringDesc) -> SpringId {
        self.springs.push(s);
        SpringId(self.springs.len() as u32 - 1)
    }

    /// Changes the stiffness of a spring already added (EvoGym gives a side shared by two cells
    /// the stiffness of the cell built last). An unknown spring is left alone.
    pub fn set_stiffness(&mut self, spring: SpringId, stiffness: f64) {
        if let Some(s) = self.springs.get_mut(spring.index()) {
            s.stiffness = stiffness;
        }
    }

    /// Adds a tight limit: after the loose pass, `spring`'s length is pulled back toward
    /// `rest × [1 - band, 1 + band]` (half the excess removed), limits one after another in the
    /// order added (EvoGym: band
    /// 0.03 on the four sides of each rigid cell, a side shared by two rigid cells twice).
    pub fn limit_length(&mut self, spring: SpringId, band: f64) {
        self.limits.push((spring, band));
    }

    /// Adds a body.
    pub fn add_body(&mut self, b: BodyDesc) -> BodyId {
        self.bodies.push(b);
        BodyId(self.bodies.len() as u32 - 1)
    }

    /// Adds a quad to a body.
    pub fn add_quad(&mut self, q: QuadDesc) -> QuadId {
        self.quads.push(q);
        QuadId(self.quads.len() as u32 - 1)
    }

    /// Adds an actuator driving `springs`: each step, a spring's goal length is its initial rest
    /// length times the mean of the (clipped) targets of the actuators that drive it.
    pub fn add_actuator(&mut self, springs: &[SpringId]) -> ActuatorId {
        self.actuators.push(springs.to_vec());
        ActuatorId(self.actuators.len() as u32 - 1)
    }

    /// Checks the description and builds the world with every buffer allocated.
    pub fn build(self) -> Result<MassSpringWorld, MassSpringError> {
        validate::settings(&self.settings)?;
        validate::points(&self.points)?;
        let rests = self.rest_lengths()?;
        validate::limits(&self.limits, self.springs.len())?;
        validate::actuators(&self.actuators, self.springs.len())?;
        let mut points = self.make_points();
        let springs = self.make_springs(rests, &mut points);
        let bodies = self.make_bodies(&points)?;
        let limits: Vec<(u32, f64)> = self.limits.iter().map(|(s, b)| (s.0, *b)).collect();
        let lists: Vec<Vec<u32>> = self.actuators.iter().map(|l| l.iter().map(|s| s.0).collect()).collect();
        let n = points.x.len();
        Ok(MassSpringWorld::assemble(
            self.settings,
            points,
            springs,
            Actuators::new(&lists, self.springs.len()),
            bodies,
            Projection::new(&limits, n),
            Rk4::new(n),
        ))
    }

    fn make_points(&self) -> Points {
        let pos: Vec<_> = self.points.iter().map(|p| p.position).collect();
        let vel: Vec<_> = self.points.iter().map(|p| p.velocity).collect();
        let mass = self.points.iter().map(|p| p.mass).collect();
        let fixed = self.points.iter().map(|p| p.fixed).collect();
        Points::new(&pos, &vel, mass, fixed)
    }

    /// Each spring's initial rest length, after checking the spring.
    fn rest_lengths(&self) -> Result<Vec<f64>, MassSpringError> {
        let (x, y): (Vec<f64>, Vec<f64>) = self.points.iter().map(|p| p.position).unzip();
        let mut rests = Vec::with_capacity(self.springs.len());
        for (i, s) in self.springs.iter().enumerate() {
            validate::spring(i, s, self.points.len())?;
            let rest = s
                .rest_length
                .unwrap_or_else(|| length(&x, &y, s.a.index(), s.b.index()));
            if !(rest.is_finite() && rest > 0.0) {
                return Err(MassSpringError::Invalid(format!(
                    "spring {i}: rest length {rest} must be positive"
                )));
            }
            rests.push(rest);
        }
        Ok(rests)
    }

    /// The springs, and the points the RK4 stages move; the springs that matter are those with an
    /// end among them.
    fn make_springs(&self, rests: Vec<f64>, points: &mut Points) -> Springs {
        let a: Vec<u32> = self.springs.iter().map(|s| s.a.0).collect();
        let b: Vec<u32> = self.springs.iter().map(|s| s.b.0).collect();
        let hops = hops_from_free(&points.fixed, &a, &b);
        let mut stages = Vec::new();
        for stage in 0..4 {
            let near = |p: u32| hops[p as usize] <= HOPS - stage;
            points.stage[stage as usize] = Runs::where_(hops.len(), |i| near(i as u32));
            stages.push(Runs::where_(a.len(), |s| near(a[s]) || near(b[s])));
        }
        let active = stages[0].clone();
        let count = a.len();
        Springs {
            a,
            b,
            stiffness: self.springs.iter().map(|s| s.stiffness).collect(),
            rest: rests.clone(),
            goal: rests.clone(),
            initial: rests,
            band: self.springs.iter().map(|s| s.band).collect(),
            active,
            stages: stages.try_into().expect("four stages"),
            tracked_length: vec![0.0; count],
        }
    }

    fn make_bodies(&self, points: &Points) -> Result<Bodies, MassSpringError> {
        let n_bodies = self.bodies.len();
        let mut sides = Vec::with_capacity(self.quads.len());
        for (i, q) in self.quads.iter().enumerate() {
            validate::quad(i, q, n_bodies, points.x.len())?;
            sides.push(oriented_sides(i, q, points)?);
        }
        let mut offsets = vec![0u32];
        let mut boundary = Vec::new();
        let mut all_fixed = vec![true; n_bodies];
        for (b, body_fixed) in all_fixed.iter_mut().enumerate() {
            let mine = self.quads.iter().enumerate().filter(|(_, q)| q.body.index() == b);
            let mut any = false;
            for (i, q) in mine {
                any = true;
                *body_fixed &= q.corners.iter().all(|p| points.fixed[p.index()]);
                if q.boundary.iter().any(|&s| s) {
                    boundary.push(i as u32);
                }
            }
            if !any {
                return Err(MassSpringError::Invalid(format!("body {b} has no quads")));
            }
            offsets.push(boundary.len() as u32);
        }
        let mut bodies = Bodies {
            quad_points: self.quads.iter().map(|q| q.corners.map(|p| p.0)).collect(),
            quad_sides: sides,
            walked_sides: self.quads.iter().map(walked_sides).collect(),
            boxes: vec![Aabb::EMPTY; boundary.len()],
            offsets,
            boundary,
            all_fixed,
            watched: self.bodies.iter().map(|b| b.watch_self_overlap).collect(),
            neighbour_offsets: Vec::new(),
            neighbours: Vec::new(),
            body_boxes: vec![Aabb::EMPTY; n_bodies],
            fixed_boxes_version: 0,
        };
        bodies.update_boxes(&points.x, &points.y, true);
        bodies.find_neighbours(NEIGHBOUR_TOLERANCE);
        Ok(bodies)
    }
}

/// Every side of the quad as (from, to) for the crossing test.
fn walked_sides(q: &QuadDesc) -> [(u32, u32); 4] {
    let c = q.corners.map(|p| p.0);
    std::array::from_fn(|i| {
        let (from, to) = (c[i], c[(i + 1) % 4]);
        if q.reversed[i] {
            (to, from)
        } else {
            (from, to)
        }
    })
}

/// The quad's boundary sides as endpoint pairs whose normal `(-dy, dx)` points outward.
fn oriented_sides(i: usize, q: &QuadDesc, points: &Points) -> Result<[Option<(u32, u32)>; 4], MassSpringError> {
    let c = q.corners.map(|p| p.0);
    let area = twice_signed_area(c.map(|p| points.x[p as usize]), c.map(|p| points.y[p as usize]));
    if area == 0.0 || !area.is_finite() {
        return Err(MassSpringError::Invalid(format!("quad {i} has zero area")));
    }
    let mut sides = [None; 4];
    for k in 0..4 {
        if q.boundary[k] {
            let (p, n) = (c[k], c[(k + 1) % 4]);
            sides[k] = Some(if area > 0.0 { (n, p) } else { (p, n) });
        }
    }
    Ok(sides)
}
