//! Worlds of EvoGym objects, and the worlds of the tasks this module implements, transcribed
//! from EvoGym's world files (commit `f63c649`, `evogym/envs/sim_files/`). Every object of those
//! four files is fully connected (each cell to every adjacent cell of the same object), so each
//! is given here as its text rows (top row first) and the position of its bottom-left cell. The
//! other tasks' worlds live in their own modules (`tasks/`), built with the layout helpers here
//! ([`laid_out`], [`laid_out_objects`]: EvoGym's task sheet's notation of rows and column runs).

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
pub(super) type Rows<'a> = (usize, usize, &'a str);

/// One object given as EvoGym's task sheet writes layouts (docs/evogym-tasks-reference.md §5):
/// for each run of rows from the bottom (`first`, `last`), its cells as comma-separated columns
/// or column runs `a-b`, each fixed unless followed by `[2]` (soft) or `[1]` (rigid); placed with
/// the bottom-left corner of its cells' bounding box as its origin.
pub(super) fn laid_out_object(name: &str, rows: &[Rows]) -> WorldObject {
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
pub(super) fn laid_out_objects(objects: &[(&str, &[Rows])]) -> World {
    let mut world = World::new();
    for (name, rows) in objects {
        world
            .add(laid_out_object(name, rows))
            .expect("laid-out objects do not overlap");
    }
    world
}

/// A world of one object given by [`laid_out_object`].
pub(super) fn laid_out(name: &str, rows: &[Rows]) -> World {
    laid_out_objects(&[(name, rows)])
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
