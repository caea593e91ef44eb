//! A material grid as points, springs, quads, tight limits and actuators, built the way EvoGym's
//! `ObjectCreator::read_object_from_array` builds an object (`ObjectCreator.cpp:193-641`, commit
//! `f63c649`), then added to a [`MassSpringBuilder`].
//!
//! - Cells are visited row-major from the top row. A cell's corner is taken from an already built
//!   connected neighbour (above, left, then the diagonal one reached through two connections; the
//!   last found wins), or created (order: top-left, top-right, bottom-left, bottom-right) at
//!   `x = x0 + i·0.1`, `y = y_max − j·0.1` (`:333-393`).
//! - Sides: the top is shared with a connected cell above, the left with a connected cell on the
//!   left; the bottom and right sides are always created (the cells that share them come later)
//!   (`:395-423`). All sides are created with the rigid constant and rest length 0.1.
//! - Then, cell by cell: soft and actuator cells overwrite the stiffness of their four sides (so a
//!   side between a rigid and a soft cell is soft, between two non-rigid cells it is the later
//!   one's), and every cell adds its two diagonals (top-right–bottom-left, then
//!   top-left–bottom-right) of rest length √(0.1² + 0.1²) (`:432-494`).
//! - Fixed cells fix their four corners (`:496-510`).
//! - Tight limits (±3 %): the four sides of each rigid cell in the order top, right, bottom, left
//!   (`Boxel.cpp:25`, `PhysicsEngine.cpp:675-710`).
//! - Actuators, one per actuator cell in cell order: a horizontal one drives the top and bottom
//!   sides, a vertical one the left and right sides (`PhysicsEngine.cpp:38-97`, `Robot.cpp:9-22`).
//! - Boundary sides: the sides of a cell facing no connected neighbour (`SimObject.cpp:235-283`).

use super::grid::MaterialGrid;
use super::materials::{Material, RIGID_SIDE};
use vsrlab_physics::mass_spring::{BodyDesc, BodyId, MassSpringBuilder, PointDesc, QuadDesc, SpringDesc, SpringId};

/// Side of a cell in metres of the simulator (`ObjectCreator.h:36`).
pub const CELL: f64 = 0.1;
/// Tight band of rigid cells' sides (`PhysicsEngine.cpp:611`).
pub const RIGID_BAND: f64 = 0.03;

/// A point of a planned object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedPoint {
    /// Position (x, y), y up.
    pub position: (f64, f64),
    /// Part of a fixed cell.
    pub fixed: bool,
}

/// A spring of a planned object, between points of the same object.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedSpring {
    /// First end (index into the plan's points).
    pub a: usize,
    /// Second end.
    pub b: usize,
    /// Stiffness.
    pub stiffness: f64,
    /// Rest length (0.1 for sides, √(0.1² + 0.1²) for diagonals).
    pub rest: f64,
}

/// A cell as a quad in EvoGym's order: corners top-left, top-right, bottom-right, bottom-left
/// (clockwise), side `i` from corner `i` to `i + 1` (top, right, bottom, left). That order is
/// EvoGym's in three places where exact touches are decided: which of two equally near edges a
/// point is pushed through (the first of top, right, bottom, left), the diagonal top-left –
/// bottom-right of the point-in-cell test, and the direction of outline edges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlannedQuad {
    /// Corner point indices.
    pub corners: [usize; 4],
    /// Which sides face no connected neighbour.
    pub boundary: [bool; 4],
    /// Sides EvoGym walks against the corner order: inner bottom and left edges, which keep the
    /// left-to-right and top-to-bottom direction they were made with (`ObjectCreator.cpp:398-422`;
    /// outline edges are turned to face out, `:603-632`).
    pub reversed: [bool; 4],
}

/// Everything an object adds to a world, with indices local to the object.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ObjectPlan {
    /// Points in EvoGym's order of creation.
    pub points: Vec<PlannedPoint>,
    /// Springs in EvoGym's order: sides as created, then diagonals.
    pub springs: Vec<PlannedSpring>,
    /// One quad per present cell, in cell order.
    pub quads: Vec<PlannedQuad>,
    /// Springs held within ±3 %, in EvoGym's order (a side of two rigid cells twice).
    pub limits: Vec<usize>,
    /// For each actuator cell in cell order, the two sides it drives.
    pub actuators: Vec<[usize; 2]>,
}

/// Corner and side indices of one cell while planning.
#[derive(Debug, Clone, Copy, Default)]
struct CellParts {
    /// Top-left, top-right, bottom-left, bottom-right.
    corners: [Option<usize>; 4],
    /// Top, bottom, left, right.
    sides: [Option<usize>; 4],
}

const TL: usize = 0;
const TR: usize = 1;
const BL: usize = 2;
const BR: usize = 3;
const TOP: usize = 0;
const BOT: usize = 1;
const LEFT: usize = 2;
const RIGHT: usize = 3;

/// Plans `grid` with its bottom-left cell at cell `origin` (x right, y up), as EvoGym places an
/// object at `pos` (`ObjectCreator.cpp:197-201`).
pub fn plan_object(grid: &MaterialGrid, origin: (usize, usize)) -> ObjectPlan {
    let (w, h) = (grid.width(), grid.height());
    let x0 = origin.0 as f64 * CELL;
    let y_max = origin.1 as f64 * CELL + h as f64 * CELL;
    let mut plan = ObjectPlan::default();
    let mut parts = vec![CellParts::default(); w * h];
    for (x, y, _) in grid.present() {
        let corners = cell_corners(grid, &parts, x, y).map(|c| c.unwrap_or(usize::MAX));
        let mut cell = CellParts::default();
        for (k, (dx, dy)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
            cell.corners[k] = Some(if corners[k] == usize::MAX {
                let position = (x0 + (x + dx) as f64 * CELL, y_max - (y + dy) as f64 * CELL);
                plan.points.push(PlannedPoint { position, fixed: false });
                plan.points.len() - 1
            } else {
                corners[k]
            });
        }
        parts[y * w + x] = cell;
        make_sides(grid, &mut parts, &mut plan, x, y);
    }
    customise(grid, &parts, &mut plan);
    plan
}

/// The corners a cell inherits from built connected neighbours (`None`: create it).
fn cell_corners(grid: &MaterialGrid, parts: &[CellParts], x: usize, y: usize) -> [Option<usize>; 4] {
    let w = grid.width();
    let get = |cx: usize, cy: usize, corner: usize| parts[cy * w + cx].corners[corner];
    let (up, down) = (grid.connected_up(x, y), grid.connected_down(x, y));
    let (left, right) = (grid.connected_left(x, y), grid.connected_right(x, y));
    let top_left = (up && grid.connected_left(x, y - 1)) || (left && grid.connected_up(x - 1, y));
    let top_right = (up && grid.connected_right(x, y - 1)) || (right && grid.connected_up(x + 1, y));
    let bot_left = (down && grid.connected_left(x, y + 1)) || (left && grid.connected_down(x - 1, y));
    let bot_right = (down && grid.connected_right(x, y + 1)) || (right && grid.connected_down(x + 1, y));
    // Candidates in EvoGym's order; the last one that exists wins.
    let pick = |candidates: [(bool, usize, usize, usize); 3]| {
        candidates
            .iter()
            .rev()
            .filter(|c| c.0)
            .find_map(|&(_, cx, cy, corner)| get(cx, cy, corner))
    };
    let (xl, xr, ya, yb) = (x.wrapping_sub(1), x + 1, y.wrapping_sub(1), y + 1);
    [
        pick([(up, x, ya, BL), (left, xl, y, TR), (top_left, xl, ya, BR)]),
        pick([(up, x, ya, BR), (right, xr, y, TL), (top_right, xr, ya, BL)]),
        pick([(down, x, yb, TL), (left, xl, y, BR), (bot_left, xl, yb, TR)]),
        pick([(down, x, yb, TR), (right, xr, y, BL), (bot_right, xr, yb, TL)]),
    ]
}

/// The cell's four sides: top and left shared with built connected neighbours, the rest new.
fn make_sides(grid: &MaterialGrid, parts: &mut [CellParts], plan: &mut ObjectPlan, x: usize, y: usize) {
    let w = grid.width();
    let c = parts[y * w + x].corners.map(|p| p.unwrap_or_default());
    let shared_top = grid
        .connected_up(x, y)
        .then(|| parts[(y - 1) * w + x].sides[BOT])
        .flatten();
    let shared_left = grid
        .connected_left(x, y)
        .then(|| parts[y * w + x - 1].sides[RIGHT])
        .flatten();
    let mut side = |shared: Option<usize>, a: usize, b: usize| {
        shared.unwrap_or_else(|| {
            plan.springs.push(PlannedSpring {
                a,
                b,
                stiffness: RIGID_SIDE,
                rest: CELL,
            });
            plan.springs.len() - 1
        })
    };
    let top = side(shared_top, c[TL], c[TR]);
    // EvoGym's test for a shared bottom looks at the cell below, not yet built: always new.
    let bot = side(None, c[BL], c[BR]);
    let left = side(shared_left, c[TL], c[BL]);
    let right = side(None, c[TR], c[BR]);
    parts[y * w + x].sides = [Some(top), Some(bot), Some(left), Some(right)];
}

/// Stiffness overrides, diagonals, fixed corners, quads, tight limits and actuators.
fn customise(grid: &MaterialGrid, parts: &[CellParts], plan: &mut ObjectPlan) {
    let w = grid.width();
    let diagonal = (2.0 * CELL * CELL).sqrt();
    for (x, y, m) in grid.present() {
        let cell = parts[y * w + x];
        let c = cell.corners.map(|p| p.unwrap_or_default());
        let s = cell.sides.map(|p| p.unwrap_or_default());
        if let Some(k) = m.side_override() {
            s.iter().for_each(|&i| plan.springs[i].stiffness = k);
        }
        for (a, b) in [(c[TR], c[BL]), (c[TL], c[BR])] {
            let stiffness = m.diagonal_stiffness();
            plan.springs.push(PlannedSpring {
                a,
                b,
                stiffness,
                rest: diagonal,
            });
        }
        if m == Material::Fixed {
            c.iter().for_each(|&p| plan.points[p].fixed = true);
        }
        if m.has_tight_limits() {
            plan.limits.extend([s[TOP], s[RIGHT], s[BOT], s[LEFT]]);
        }
        match m {
            Material::HorizontalActuator => plan.actuators.push([s[TOP], s[BOT]]),
            Material::VerticalActuator => plan.actuators.push([s[LEFT], s[RIGHT]]),
            _ => {}
        }
        let boundary = [
            !grid.connected_up(x, y),
            !grid.connected_right(x, y),
            !grid.connected_down(x, y),
            !grid.connected_left(x, y),
        ];
        plan.quads.push(PlannedQuad {
            corners: [c[TL], c[TR], c[BR], c[BL]],
            boundary,
            reversed: [false, false, !boundary[2], !boundary[3]],
        });
    }
}

/// Where a planned object landed in a world.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedObject {
    /// Its body.
    pub body: BodyId,
    /// Index of its first point in the world; its points are contiguous.
    pub first_point: usize,
    /// Number of points.
    pub point_count: usize,
    /// Its springs, in the plan's order.
    pub springs: Vec<SpringId>,
}

impl PlacedObject {
    /// The world indices of its points.
    pub fn points(&self) -> std::ops::Range<usize> {
        self.first_point..self.first_point + self.point_count
    }
}

impl ObjectPlan {
    /// Adds the object as one body (checked for self-overlap when `robot`, as EvoGym checks
    /// objects with actuators: `PhysicsEngine.cpp:819-889`).
    pub fn add_to(&self, builder: &mut MassSpringBuilder, robot: bool) -> PlacedObject {
        let body = builder.add_body(if robot {
            BodyDesc::new().watch_self_overlap()
        } else {
            BodyDesc::new()
        });
        let ids: Vec<_> = self
            .points
            .iter()
            .map(|p| {
                let d = PointDesc::at(p.position.0, p.position.1);
                builder.add_point(if p.fixed { d.fixed() } else { d })
            })
            .collect();
        let springs: Vec<SpringId> = self
            .springs
            .iter()
            .map(|s| builder.add_spring(SpringDesc::between(ids[s.a], ids[s.b], s.stiffness).rest_length(s.rest)))
            .collect();
        for q in &self.quads {
            builder.add_quad(
                QuadDesc::new(body, q.corners.map(|i| ids[i]))
                    .boundary(q.boundary)
                    .reversed(q.reversed),
            );
        }
        self.limits
            .iter()
            .for_each(|&s| builder.limit_length(springs[s], RIGID_BAND));
        for a in &self.actuators {
            builder.add_actuator(&[springs[a[0]], springs[a[1]]]);
        }
        PlacedObject {
            body,
            first_point: ids.first().map_or(0, |p| p.index()),
            point_count: ids.len(),
            springs,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinds::evogym::materials::{ACTUATOR_SIDE, SOFT_SIDE};

    fn ends(plan: &ObjectPlan) -> Vec<(usize, usize)> {
        plan.springs.iter().map(|s| (s.a, s.b)).collect()
    }

    /// A rigid cell left of a soft one ("12"), worked out by hand. Points: the rigid cell creates
    /// TL 0, TR 1, BL 2, BR 3; the soft cell inherits its TL = 1 and BL = 3 from the left and
    /// creates TR 4, BR 5. Sides: rigid top 0 (0–1), bottom 1 (2–3), left 2 (0–2), right 3 (1–3);
    /// soft top 4 (1–4), bottom 5 (3–5), its left is side 3, right 6 (4–5). Diagonals: rigid 7
    /// (1–2), 8 (0–3); soft 9 (4–3), 10 (1–5). Soft overwrites sides 4, 5, 3, 6.
    #[test]
    fn a_rigid_and_a_soft_cell_share_a_soft_side() {
        let plan = plan_object(&MaterialGrid::from_rows("12").unwrap(), (0, 0));
        assert_eq!(plan.points.len(), 6);
        let xy: Vec<_> = plan.points.iter().map(|p| p.position).collect();
        assert_eq!(
            xy,
            [(0.0, 0.1), (0.1, 0.1), (0.0, 0.0), (0.1, 0.0), (0.2, 0.1), (0.2, 0.0)]
        );
        assert_eq!(
            ends(&plan),
            [
                (0, 1),
                (2, 3),
                (0, 2),
                (1, 3),
                (1, 4),
                (3, 5),
                (4, 5),
                (1, 2),
                (0, 3),
                (4, 3),
                (1, 5)
            ]
        );
        let k: Vec<f64> = plan.springs.iter().map(|s| s.stiffness).collect();
        let (r, s) = (RIGID_SIDE, SOFT_SIDE);
        assert_eq!(k, [r, r, r, s, s, s, s, r / 2.0, r / 2.0, s / 4.0, s / 4.0]);
        let rest: Vec<f64> = plan.springs.iter().map(|s| s.rest).collect();
        let d = (0.1f64 * 0.1 + 0.1 * 0.1).sqrt();
        assert_eq!(rest, [0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, d, d, d, d]);
        // Rigid cell's sides top, right, bottom, left.
        assert_eq!(plan.limits, [0, 3, 1, 2]);
        assert!(plan.actuators.is_empty());
        assert_eq!(plan.quads[0].corners, [0, 1, 3, 2]);
        assert_eq!(plan.quads[0].boundary, [true, false, true, true]);
        assert_eq!(plan.quads[0].reversed, [false, false, false, false]);
        assert_eq!(plan.quads[1].corners, [1, 4, 5, 3]);
        assert_eq!(plan.quads[1].boundary, [true, true, true, false]);
        assert_eq!(
            plan.quads[1].reversed,
            [false, false, false, true],
            "the shared left edge"
        );
    }

    /// Two stacked actuators "3/4" at cell (1, 1): the horizontal one on top drives its top and
    /// bottom sides (0 and 1), the vertical one below drives its left and right (side 1 is
    /// shared as its top: its own sides are bottom 4, left 5, right 6). The later (vertical)
    /// cell writes the shared side last: actuator constant either way.
    #[test]
    fn actuators_drive_the_sides_evogym_names() {
        let plan = plan_object(&MaterialGrid::from_rows("3/4").unwrap(), (1, 1));
        assert_eq!(plan.points.len(), 6);
        assert_eq!(plan.points[0].position, (0.1, 0.30000000000000004));
        assert!((plan.points[5].position.1 - 0.1).abs() < 1e-15);
        assert_eq!(plan.actuators, [[0, 1], [5, 6]]);
        assert_eq!(plan.springs[1].stiffness, ACTUATOR_SIDE);
        assert_eq!(plan.springs.len(), 7 + 4);
        assert!(plan.limits.is_empty());
    }

    /// A full 5 × 5 body: 36 points, 60 sides + 50 diagonals.
    #[test]
    fn a_full_body_has_shared_corners() {
        let plan = plan_object(
            &MaterialGrid::from_rows("33333/33333/33333/33333/33333").unwrap(),
            (0, 0),
        );
        assert_eq!(plan.points.len(), 36);
        assert_eq!(plan.springs.len(), 60 + 50);
        assert_eq!(plan.actuators.len(), 25);
        let boundary = plan.quads.iter().filter(|q| q.boundary.iter().any(|&b| b)).count();
        assert_eq!(boundary, 16);
    }

    /// Unconnected neighbours share nothing: "11" without its connection has 8 points and each
    /// cell's four sides on the boundary; fixed cells fix their corners.
    #[test]
    fn connections_and_fixed_cells_are_respected() {
        let g = MaterialGrid::unconnected(2, 1, vec![Material::Rigid, Material::Fixed]);
        let plan = plan_object(&g, (0, 0));
        assert_eq!(plan.points.len(), 8);
        assert!(plan.quads.iter().all(|q| q.boundary == [true; 4]));
        let fixed: Vec<bool> = plan.points.iter().map(|p| p.fixed).collect();
        assert_eq!(fixed, [false, false, false, false, true, true, true, true]);
    }

    #[test]
    fn a_plan_goes_into_a_builder_that_builds() {
        let plan = plan_object(&MaterialGrid::from_rows("12/34").unwrap(), (0, 1));
        let mut b = MassSpringBuilder::new(Default::default());
        let placed = plan.add_to(&mut b, true);
        let world = b.build().unwrap();
        assert_eq!(placed.points(), 0..9);
        assert_eq!(world.actuator_count(), 2);
        assert_eq!(world.spring_count(), plan.springs.len());
    }
}
