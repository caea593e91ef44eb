//! Worlds of EvoGym objects, and the worlds of the tasks this module implements, transcribed
//! from EvoGym's world files (commit `f63c649`, `evogym/envs/sim_files/`). Every object of those
//! four files is fully connected (each cell to every adjacent cell of the same object), so each
//! is given here as its text rows (top row first) and the position of its bottom-left cell.

use super::grid::MaterialGrid;
use std::collections::BTreeSet;
use vsrlab_field::FieldError;

/// A named object placed with its bottom-left cell at `origin` (cells, x right, y up).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WorldObject {
    /// Name (EvoGym's tasks look objects up by name: `robot`, `beam`, `terrain`).
    pub name: String,
    /// Column and row (from the bottom) of the bottom-left cell of its grid.
    pub origin: (usize, usize),
    /// Its cells.
    pub grid: MaterialGrid,
}

impl WorldObject {
    /// An object named `name` at `origin`.
    pub fn new(name: &str, origin: (usize, usize), grid: MaterialGrid) -> WorldObject {
        WorldObject {
            name: name.to_string(),
            origin,
            grid,
        }
    }

    /// The world cells (column, row from the bottom) its present cells occupy.
    pub fn world_cells(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let h = self.grid.height();
        self.grid
            .present()
            .map(move |(x, y, _)| (self.origin.0 + x, self.origin.1 + h - 1 - y))
    }
}

/// Objects in name order, none overlapping another.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct World {
    objects: Vec<WorldObject>,
}

impl World {
    /// An empty world.
    pub fn new() -> World {
        World::default()
    }

    /// The objects, in name order.
    pub fn objects(&self) -> &[WorldObject] {
        &self.objects
    }

    /// The object named `name`.
    pub fn object(&self, name: &str) -> Option<&WorldObject> {
        self.objects.iter().find(|o| o.name == name)
    }

    /// Adds an object; refuses a duplicate name or a cell already taken (as
    /// `EvoWorld.add_object`, `evogym/world.py:95-137`).
    pub fn add(&mut self, object: WorldObject) -> Result<(), FieldError> {
        if self.object(&object.name).is_some() {
            return Err(FieldError::message(format!("a second object named '{}'", object.name)));
        }
        let taken: BTreeSet<(usize, usize)> = self.objects.iter().flat_map(|o| o.world_cells()).collect();
        if let Some(cell) = object.world_cells().find(|c| taken.contains(c)) {
            return Err(FieldError::message(format!(
                "'{}' overlaps another object at cell {cell:?}",
                object.name
            )));
        }
        let at = self.objects.partition_point(|o| o.name < object.name);
        self.objects.insert(at, object);
        Ok(())
    }
}

/// A world of fully connected objects given as `(name, origin, rows)`.
fn transcribed(objects: &[(&str, (usize, usize), &[&str])]) -> World {
    let mut world = World::new();
    for (name, origin, rows) in objects {
        let grid = MaterialGrid::from_rows(&rows.join("/")).expect("a transcribed object reads");
        world
            .add(WorldObject::new(name, *origin, grid))
            .expect("transcribed objects do not overlap");
    }
    world
}

/// Walker-v0's world (`Walker-v0.json`): `ground`, a row of 100 fixed cells at (0, 0).
pub fn walker_v0() -> World {
    transcribed(&[("ground", (0, 0), &[&"5".repeat(100)])])
}

/// BridgeWalker-v0's world (`BridgeWalker-v0.json`): one object, 60 × 5 cells at (0, 0): a fixed
/// floor row, fixed pillars two cells high, and a soft bridge two cells thick on top whose
/// sections are anchored to fixed cells above each pillar.
pub fn bridge_walker_v0() -> World {
    const ROWS: &[&str] = &[
        "522225222252222222522222222225222222222222222252222222222255",
        "522225222252222222522222222225222222222222222252222222222255",
        "5....5....5.......5..........5................5...........55",
        "5....5....5.......5..........5................5...........55",
        "555555555555555555555555555555555555555555555555555555555555",
    ];
    transcribed(&[("new_object_2", (0, 0), ROWS)])
}

/// BeamToppler-v0's world (`BeamToppler-v0.json`): `ground` (70 fixed cells at (0, 0)), pegs
/// `peg1` and `peg2` (5 fixed cells each at (27, 4) and (36, 4)) and `beam`, 10 × 2 rigid cells
/// at (29, 5) resting on both pegs.
pub fn beam_toppler_v0() -> World {
    transcribed(&[
        ("beam", (29, 5), &["1111111111", "1111111111"]),
        ("peg1", (27, 4), &["55555"]),
        ("peg2", (36, 4), &["55555"]),
        ("ground", (0, 0), &[&"5".repeat(70)]),
    ])
}

/// CaveCrawler-v0's world (`CaveCrawler-v0.json`): `terrain`, one object of 70 × 14 cells at
/// (0, 0): a fixed floor with a soft bump, a fixed ceiling from which soft masses hang, walls.
pub fn cave_crawler_v0() -> World {
    const ROWS: &[&str] = &[
        "....................5.................................................",
        "....................5.................................................",
        "....................5.................................................",
        "....................5.................................................",
        "....................5................................................5",
        "....................5................................................5",
        "....................55............555555555555555555555555555555555555",
        ".....................22222222222222....222222222222222....555........5",
        ".......................2222222222.........2222222222.......55........5",
        ".........................222222............................5.........5",
        ".....................................................................5",
        ".....................................................................5",
        "..............................................22222..................5",
        "5555555555555555555555555555555555555555555555555555555555555555555555",
    ];
    transcribed(&[("terrain", (0, 0), ROWS)])
}

/// A run of rows from the bottom (first, last) and their cells ([`laid_out_object`]).
type Rows<'a> = (usize, usize, &'a str);

/// One object given as EvoGym's task sheet writes layouts (docs/evogym-tasks-reference.md §5):
/// for each run of rows from the bottom (`first`, `last`), its cells as comma-separated columns
/// or column runs `a-b`, each fixed unless followed by `[2]` (soft) or `[1]` (rigid); placed with
/// the bottom-left corner of its cells' bounding box as its origin.
fn laid_out_object(name: &str, rows: &[Rows]) -> WorldObject {
    let mut cells: Vec<(usize, usize, char)> = Vec::new();
    for &(first, last, spec) in rows {
        for run in spec.split(',').map(str::trim) {
            let (run, code) = match run.split_once('[') {
                Some((run, material)) => (run, material.chars().next().expect("a material code")),
                None => (run, '5'),
            };
            let (a, b) = match run.split_once('-') {
                Some((a, b)) => (a.parse::<usize>(), b.parse::<usize>()),
                None => (run.parse(), run.parse()),
            };
            let (a, b) = (a.expect("a column"), b.expect("a column"));
            for row in first..=last {
                cells.extend((a..=b).map(|column| (column, row, code)));
            }
        }
    }
    let left = cells.iter().map(|c| c.0).min().expect("cells");
    let bottom = cells.iter().map(|c| c.1).min().expect("cells");
    let width = cells.iter().map(|c| c.0).max().expect("cells") + 1 - left;
    let height = cells.iter().map(|c| c.1).max().expect("cells") + 1 - bottom;
    let mut grid = vec![vec!['.'; width]; height];
    for (column, row, code) in cells {
        grid[height - 1 - (row - bottom)][column - left] = code;
    }
    let rows: Vec<String> = grid.into_iter().map(|r| r.into_iter().collect()).collect();
    let grid = MaterialGrid::from_rows(&rows.join("/")).expect("a layout reads");
    WorldObject::new(name, (left, bottom), grid)
}

/// A world of objects given by [`laid_out_object`], `(name, rows)` each.
fn laid_out_objects(objects: &[(&str, &[Rows])]) -> World {
    let mut world = World::new();
    for (name, rows) in objects {
        world
            .add(laid_out_object(name, rows))
            .expect("laid-out objects do not overlap");
    }
    world
}

/// A world of one object given by [`laid_out_object`].
fn laid_out(name: &str, rows: &[Rows]) -> World {
    laid_out_objects(&[(name, rows)])
}

/// Jumper-v0's world (`Jumper-v0.json`, 60 × 8): `ground`, a floor with a wall at each end.
pub fn jumper_v0() -> World {
    laid_out("ground", &[(0, 0, "0-59"), (1, 7, "0, 59")])
}

/// Balancer-v0's world (`Balancer-v0.json`, 30 × 5): `ground`, a floor, walls at the ends and a
/// pole two cells high in column 17.
pub fn balancer_v0() -> World {
    laid_out("ground", &[(0, 0, "0-29"), (1, 2, "0, 17, 29"), (3, 4, "0, 29")])
}

/// Balancer-v1's world (`Balancer-v1.json`): as Balancer-v0's, the pole three cells high.
pub fn balancer_v1() -> World {
    laid_out("ground", &[(0, 0, "0-29"), (1, 3, "0, 17, 29"), (4, 4, "0, 29")])
}

/// Climber-v0's world (`Climber-v0.json`, 7 × 90): `pipe`, fixed walls in columns 0 and 6, a
/// floor and a cap.
pub fn climber_v0() -> World {
    laid_out("pipe", &[(0, 0, "0-6"), (1, 88, "0, 6"), (89, 89, "0-6")])
}

/// Climber-v1's world (`Climber-v1.json`, 7 × 70): `pipe`, as Climber-v0's with the cap in row 69
/// and 42 soft wall cells in stretches on either side.
pub fn climber_v1() -> World {
    laid_out(
        "pipe",
        &[
            (0, 0, "0-6"),
            (1, 7, "0, 6"),
            (8, 8, "0, 6[2]"),
            (9, 10, "0, 6"),
            (11, 12, "0[2], 6"),
            (13, 14, "0, 6"),
            (15, 17, "0, 6[2]"),
            (18, 20, "0, 6"),
            (21, 22, "0[2], 6"),
            (23, 24, "0, 6[2]"),
            (25, 26, "0, 6"),
            (27, 27, "0[2], 6"),
            (28, 28, "0[2], 6[2]"),
            (29, 29, "0, 6[2]"),
            (30, 30, "0, 6"),
            (31, 32, "0[2], 6"),
            (33, 34, "0, 6"),
            (35, 35, "0[2], 6[2]"),
            (36, 37, "0, 6[2]"),
            (38, 38, "0, 6"),
            (39, 41, "0[2], 6"),
            (42, 44, "0, 6"),
            (45, 46, "0[2], 6[2]"),
            (47, 50, "0, 6"),
            (51, 53, "0[2], 6[2]"),
            (54, 55, "0, 6"),
            (56, 59, "0, 6[2]"),
            (60, 64, "0[2], 6"),
            (65, 68, "0, 6"),
            (69, 69, "0-6"),
        ],
    )
}

/// Climber-v2's world (`Climber-v2.json`, 27 × 42): `pipe`, fixed, rising straight, then stepping
/// right cell by cell, then turning right into a tunnel that ends at column 26.
pub fn climber_v2() -> World {
    laid_out(
        "pipe",
        &[
            (0, 0, "0-6"),
            (1, 18, "0, 6"),
            (19, 19, "0, 6-7"),
            (20, 22, "0, 7"),
            (23, 23, "0-1, 7"),
            (24, 26, "1, 7"),
            (27, 27, "1, 7-8"),
            (28, 29, "1, 8"),
            (30, 30, "1-2, 8"),
            (31, 31, "2, 8"),
            (32, 32, "2, 8-9"),
            (33, 33, "2, 9-10"),
            (34, 34, "2-3, 10-11"),
            (35, 35, "3, 11-26"),
            (36, 36, "3, 26"),
            (37, 37, "3-4, 26"),
            (38, 38, "4-5, 26"),
            (39, 39, "5-6, 26"),
            (40, 40, "6-7, 26"),
            (41, 41, "7-26"),
        ],
    )
}

/// Flipper-v0's world (`Flipper-v0.json`): `new_object_1`, a row of 70 fixed cells at (0, 0).
pub fn flipper_v0() -> World {
    laid_out("new_object_1", &[(0, 0, "0-69")])
}

/// The shape tasks' world (`ShapeChange.json`, 20 × 10): `new_object_4`, a floor with walls two
/// cells thick at each end.
pub fn shape_change() -> World {
    laid_out("new_object_4", &[(0, 0, "0-19"), (1, 9, "0-1, 18-19")])
}

/// Carrier-v0's world (`Carrier-v0.json`, 100 × 8): `ground`, a row of 100 fixed cells, and
/// `package`, 3 × 2 soft cells at (3, 6), on top of the robot.
pub fn carrier_v0() -> World {
    laid_out_objects(&[("ground", &[(0, 0, "0-99")]), ("package", &[(6, 7, "3-5[2]")])])
}

/// Carrier-v1's world (`Carrier-v1.json`, 60 × 12): `ground`, a shelf, a step, a lower floor and
/// a table post, and `package`, 3 × 2 rigid cells at (3, 10), above the robot.
pub fn carrier_v1() -> World {
    laid_out_objects(&[
        (
            "ground",
            &[
                (1, 1, "26-59"),
                (2, 2, "23-26, 48-49"),
                (3, 3, "0-23, 48-49"),
                (4, 4, "48-49"),
            ],
        ),
        ("package", &[(10, 11, "3-5[1]")]),
    ])
}

/// Pusher-v0's world (`Pusher-v0.json`, 100 × 3): `ground`, a row of 100 fixed cells, and
/// `package`, 3 × 2 soft cells at (8, 1).
pub fn pusher_v0() -> World {
    laid_out_objects(&[("ground", &[(0, 0, "0-99")]), ("package", &[(1, 2, "8-10[2]")])])
}

/// Pusher-v1's world (`Pusher-v1.json`): as Pusher-v0's, the package rigid.
pub fn pusher_v1() -> World {
    laid_out_objects(&[("ground", &[(0, 0, "0-99")]), ("package", &[(1, 2, "8-10[1]")])])
}

/// Thrower-v0's world (`Thrower-v0.json`, 70 × 10): `ground`, a floor with posts of rising
/// heights and an end wall, and `package`, 3 × 2 soft cells at (3, 7), above the robot.
pub fn thrower_v0() -> World {
    laid_out_objects(&[
        (
            "ground",
            &[
                (0, 0, "0-69"),
                (1, 2, "10, 14, 18, 23, 28, 39, 69"),
                (3, 3, "14, 18, 23, 28, 39, 69"),
                (4, 4, "18, 23, 28, 39, 69"),
                (5, 6, "23, 28, 39, 69"),
                (7, 7, "28, 39, 69"),
                (8, 9, "39, 69"),
            ],
        ),
        ("package", &[(7, 8, "3-5[2]")]),
    ])
}

/// Lifter-v0's world (`Lifter-v0.json`, 11 × 5): `ground`, a pit between two ledges, and
/// `package`, 1 × 2 rigid cells standing in the pit at (5, 1).
pub fn lifter_v0() -> World {
    laid_out_objects(&[
        (
            "ground",
            &[(0, 0, "3-7"), (1, 1, "3, 7"), (2, 2, "0-3, 7-10"), (3, 4, "0, 10")],
        ),
        ("package", &[(1, 2, "5[1]")]),
    ])
}

/// BeamSlider-v0's world (`BeamSlider-v0.json`, 70 × 7): `ground`, five fixed pegs in row 4 and
/// `beam`, 10 × 2 rigid cells at (22, 5) on the first peg.
pub fn beam_slider_v0() -> World {
    laid_out_objects(&[
        ("beam", &[(5, 6, "22-31[1]")]),
        ("ground", &[(0, 0, "0-69")]),
        ("peg1", &[(4, 4, "20-24")]),
        ("peg2", &[(4, 4, "29-31")]),
        ("peg3", &[(4, 4, "35-37")]),
        ("peg4", &[(4, 4, "41-43")]),
        ("peg5", &[(4, 4, "49-51")]),
    ])
}

/// Traverser-v0's world (`Traverser-v0.json`, 60 × 9, and `traverse.py:553-580`): `ground`, a
/// left shelf, a pit and a right shelf, and 27 free rigid blocks `block_0` … `block_26` of 3 × 3,
/// 2 × 2 or 1 × 1 cells placed in the pit in three layers, as EvoGym's code places them.
pub fn traverser_v0() -> World {
    let mut world = laid_out(
        "ground",
        &[
            (0, 0, "19-49"),
            (1, 5, "19, 49"),
            (6, 6, "19, 49-59"),
            (7, 7, "19"),
            (8, 8, "0-19"),
        ],
    );
    let mut blocks: Vec<(usize, usize, usize)> = vec![
        (20, 1, 3),
        (24, 1, 3),
        (27, 1, 2),
        (31, 1, 3),
        (34, 1, 3),
        (38, 1, 2),
        (41, 1, 3),
        (45, 1, 3),
        (21, 4, 3),
        (24, 4, 2),
        (26, 4, 1),
        (29, 4, 2),
        (31, 4, 3),
        (34, 4, 2),
        (36, 4, 2),
        (40, 4, 3),
        (43, 4, 2),
        (46, 4, 3),
    ];
    blocks.extend((20..45).step_by(3).map(|x| (x, 7, 2)));
    for (k, &(x, y, side)) in blocks.iter().enumerate() {
        let rows = vec!["1".repeat(side); side].join("/");
        let grid = MaterialGrid::from_rows(&rows).expect("a rigid block");
        world
            .add(WorldObject::new(&format!("block_{k}"), (x, y), grid))
            .expect("the blocks do not overlap");
    }
    world
}

/// BidirectionalWalker-v0's world (`BidirectionalWalker-v0.json`): `new_object_1`, a row of 70
/// fixed cells at (0, 0).
pub fn bidirectional_walker_v0() -> World {
    laid_out("new_object_1", &[(0, 0, "0-69")])
}

/// UpStepper-v0's world (`UpStepper-v0.json`, 70 × 9): `ground`, a staircase up from row 0 to
/// row 8, one cell per step.
pub fn up_stepper_v0() -> World {
    laid_out(
        "ground",
        &[
            (0, 0, "0-20"),
            (1, 1, "20-29"),
            (2, 2, "29-36"),
            (3, 3, "36-42"),
            (4, 4, "42-47"),
            (5, 5, "47-51"),
            (6, 6, "51-55"),
            (7, 7, "55-61"),
            (8, 8, "61-69"),
        ],
    )
}

/// DownStepper-v0's world (`DownStepper-v0.json`, 75 × 10): `ground`, a staircase down from row 9
/// to row 0.
pub fn down_stepper_v0() -> World {
    laid_out(
        "ground",
        &[
            (9, 9, "0-20"),
            (8, 8, "20-28"),
            (7, 7, "28-35"),
            (6, 6, "35-41"),
            (5, 5, "41-47"),
            (4, 4, "47-52"),
            (3, 3, "52-57"),
            (2, 2, "57-61"),
            (1, 1, "61-65"),
            (0, 0, "65-74"),
        ],
    )
}

/// ObstacleTraverser-v0's world (`ObstacleTraverser-v0.json`, 80 × 3): `ground`, a floor with
/// bumps one or two cells high.
pub fn obstacle_traverser_v0() -> World {
    laid_out(
        "ground",
        &[
            (0, 0, "0-79"),
            (
                1,
                1,
                "22, 28, 33-34, 39, 42-43, 45, 47, 50-51, 54-57, 59-60, 62-65, 67-68, 72",
            ),
            (2, 2, "55, 60, 64"),
        ],
    )
}

/// ObstacleTraverser-v1's world (`ObstacleTraverser-v1.json`, 60 × 10): `ground`, rugged ground
/// two to four rows thick with a wall at the end.
pub fn obstacle_traverser_v1() -> World {
    laid_out(
        "ground",
        &[
            (0, 0, "0-59"),
            (1, 1, "0-15, 17-59"),
            (
                2,
                2,
                "0-7, 9, 12-13, 17-19, 21-24, 26, 28-29, 31-33, 35-40, 42-50, 53-55, 57-59",
            ),
            (3, 3, "2, 4, 18, 23, 32-33, 36, 38-40, 43-45, 47, 49, 54, 58-59"),
            (4, 4, "44, 58-59"),
            (5, 9, "58-59"),
        ],
    )
}

/// Hurdler-v0's world (`Hurdler-v0.json`, 70 × 6): `ground`, a floor with hurdles one or two cells
/// high and a wall at the end.
pub fn hurdler_v0() -> World {
    laid_out(
        "ground",
        &[
            (0, 0, "0-69"),
            (1, 1, "12, 20, 28, 36-37, 45, 52, 58, 69"),
            (2, 2, "20, 36-37, 52, 58, 69"),
            (3, 5, "69"),
        ],
    )
}

/// A world of one-row fixed platforms, each `(name, origin, length)`.
fn platforms(list: &[(&str, (usize, usize), usize)]) -> World {
    let mut world = World::new();
    for &(name, origin, length) in list {
        let grid = MaterialGrid::from_rows(&"5".repeat(length)).expect("a row of fixed cells");
        world
            .add(WorldObject::new(name, origin, grid))
            .expect("platforms apart");
    }
    world
}

/// GapJumper-v0's world (`GapJumper-v0.json`, 80 × 6): five platforms in row 5 with gaps of five
/// cells, and no ground.
pub fn gap_jumper_v0() -> World {
    platforms(&[
        ("platform_1", (0, 5), 20),
        ("platform_2", (25, 5), 10),
        ("platform_3", (40, 5), 10),
        ("platform_4", (55, 5), 10),
        ("platform_5", (70, 5), 10),
    ])
}

/// PlatformJumper-v0's world (`PlatformJumper-v0.json`, 91 × 9): seven platforms at different
/// heights, and no ground.
pub fn platform_jumper_v0() -> World {
    platforms(&[
        ("platform_1", (0, 5), 20),
        ("platform_2", (21, 7), 10),
        ("platform_3", (33, 8), 10),
        ("platform_4", (46, 6), 10),
        ("platform_5", (57, 5), 10),
        ("platform_6", (70, 6), 10),
        ("platform_7", (81, 3), 10),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinds::evogym::materials::Material;

    /// Cell counts and material counts as in the files (Walker: 100 fixed; BridgeWalker: 104
    /// soft, 92 fixed; BeamToppler: beam 20 rigid, pegs 5 and 5, ground 70; CaveCrawler: 128
    /// fixed, 60 soft).
    #[test]
    fn transcribed_worlds_have_the_files_cells() {
        let count =
            |w: &World, name: &str, m: Material| w.object(name).unwrap().grid.present().filter(|c| c.2 == m).count();
        assert_eq!(count(&walker_v0(), "ground", Material::Fixed), 100);
        let b = bridge_walker_v0();
        assert_eq!(count(&b, "new_object_2", Material::Soft), 104);
        assert_eq!(count(&b, "new_object_2", Material::Fixed), 92);
        let t = beam_toppler_v0();
        assert_eq!(count(&t, "beam", Material::Rigid), 20);
        assert_eq!(
            count(&t, "peg1", Material::Fixed) + count(&t, "peg2", Material::Fixed),
            10
        );
        assert_eq!(count(&t, "ground", Material::Fixed), 70);
        let names: Vec<&str> = t.objects().iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names, ["beam", "ground", "peg1", "peg2"]);
        let c = cave_crawler_v0();
        assert_eq!(count(&c, "terrain", Material::Fixed), 128);
        assert_eq!(count(&c, "terrain", Material::Soft), 60);
        assert!(c.objects().iter().all(|o| o.grid.is_connected()));
    }

    /// The laid-out worlds have the files' cell counts (docs/evogym-tasks-reference.md §3, §5):
    /// Jumper 60 + 2 × 7 = 74 fixed; Balancer-v0 30 + 3 × 2 + 2 × 2 = 40, v1 41; Climber-v0
    /// 7 + 2 × 88 + 7 = 190; Climber-v1 42 soft and 108 fixed.
    #[test]
    fn laid_out_worlds_have_the_files_cells() {
        let count =
            |w: &World, name: &str, m: Material| w.object(name).unwrap().grid.present().filter(|c| c.2 == m).count();
        assert_eq!(count(&jumper_v0(), "ground", Material::Fixed), 74);
        assert_eq!(count(&balancer_v0(), "ground", Material::Fixed), 40);
        assert_eq!(count(&balancer_v1(), "ground", Material::Fixed), 41);
        assert_eq!(count(&climber_v0(), "pipe", Material::Fixed), 190);
        let c = climber_v1();
        assert_eq!(
            (count(&c, "pipe", Material::Soft), count(&c, "pipe", Material::Fixed)),
            (42, 108)
        );
        let pole: BTreeSet<_> = balancer_v1().object("ground").unwrap().world_cells().collect();
        assert!(pole.contains(&(17, 3)) && !pole.contains(&(17, 4)) && pole.contains(&(29, 4)));
        // ObstacleTraverser-v1's ground has 195 cells (reference sheet §3.5)
        assert_eq!(count(&obstacle_traverser_v1(), "ground", Material::Fixed), 195);
        let names = |w: &World| w.objects().iter().map(|o| o.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&gap_jumper_v0()).len(), 5);
        assert_eq!(names(&platform_jumper_v0())[6], "platform_7");
        let every = [
            jumper_v0(),
            balancer_v0(),
            balancer_v1(),
            climber_v0(),
            c,
            climber_v2(),
            up_stepper_v0(),
            down_stepper_v0(),
            obstacle_traverser_v0(),
            obstacle_traverser_v1(),
            hurdler_v0(),
            gap_jumper_v0(),
            platform_jumper_v0(),
        ];
        for w in every {
            assert!(w.objects().iter().all(|o| o.grid.is_connected()), "{:?}", names(&w));
        }
    }

    #[test]
    fn world_cells_count_rows_from_the_bottom() {
        let t = beam_toppler_v0();
        let beam: BTreeSet<_> = t.object("beam").unwrap().world_cells().collect();
        assert!(beam.contains(&(29, 5)) && beam.contains(&(38, 6)) && !beam.contains(&(29, 7)));
    }

    #[test]
    fn duplicates_and_overlaps_are_refused() {
        let mut w = walker_v0();
        let g = MaterialGrid::from_rows("3").unwrap();
        assert!(w.add(WorldObject::new("ground", (0, 5), g.clone())).is_err());
        let e = w.add(WorldObject::new("robot", (3, 0), g.clone())).unwrap_err();
        assert!(e.message.contains("(3, 0)"), "{e}");
        assert!(w.add(WorldObject::new("robot", (3, 1), g)).is_ok());
    }
}
