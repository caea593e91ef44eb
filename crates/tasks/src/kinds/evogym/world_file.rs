//! EvoGym's world files (`evogym/envs/sim_files/*.json`, written by its design tool) and robots
//! saved in the same format (one object), read into [`World`]s and [`MaterialGrid`]s.
//!
//! The format, as `EvoWorld.add_from_json` and `WorldObject.load_from_parsed_json` read it
//! (`evogym/world.py:39-72`, `:367-433`, commit `f63c649`):
//! `{"grid_width": W, "grid_height": H, "objects": {NAME: {"indices": [..], "types": [..],
//! "neighbors": {"INDEX": [..], ..}}, ..}}`. A cell index `i` is the cell at column `i % W`, row
//! `i / W` counted from the bottom; `types` holds each listed cell's material code; `neighbors`
//! lists, for each index (as a string key), the indices it is connected to. An object sits at the
//! bottom-left corner of its cells' bounding box. Objects are taken in name order, as EvoGym
//! sorts them (`evogym/sim.py:49-59`).

use super::grid::{MaterialGrid, MAX_SIDE};
use super::materials::Material;
use super::worlds::{World, WorldObject};
use serde_json::{Map, Value};
use vsrlab_field::FieldError;

/// Reads a world file. Errors name the field (`objects.ground.types[3]`, `grid_width`).
pub fn world_from_json(text: &str) -> Result<World, FieldError> {
    let value: Value = serde_json::from_str(text).map_err(|e| FieldError::message(format!("not JSON: {e}")))?;
    let width = size(&value, "grid_width")?;
    let height = size(&value, "grid_height")?;
    let objects = value
        .get("objects")
        .and_then(Value::as_object)
        .ok_or_else(|| FieldError::new("objects", "missing: expected a table of objects"))?;
    let mut world = World::new();
    for (name, object) in objects {
        let (grid, origin) = read_object(object, width, height).map_err(|e| e.at(name).at("objects"))?;
        world
            .add(WorldObject::new(name, origin, grid))
            .map_err(|e| e.at(name).at("objects"))?;
    }
    Ok(world)
}

/// Reads a robot saved as a world file of exactly one object, and checks it is a valid robot.
pub fn robot_from_json(text: &str) -> Result<MaterialGrid, FieldError> {
    let world = world_from_json(text)?;
    let [object] = world.objects() else {
        return Err(FieldError::new(
            "objects",
            format!("{} objects: a robot file holds exactly one", world.objects().len()),
        ));
    };
    object
        .grid
        .validate_robot()
        .map_err(|e| e.at(&object.name).at("objects"))?;
    Ok(object.grid.clone())
}

/// Writes a robot as EvoGym saves one: a world file of one object `robot` in a grid its own size
/// (cells numbered from the bottom row, ascending; each cell's connected neighbours listed).
pub fn robot_to_json(grid: &MaterialGrid) -> String {
    let (w, h) = (grid.width(), grid.height());
    // file index of grid cell (x, y), y counted from the top
    let index = |x: usize, y: usize| (h - 1 - y) * w + x;
    let mut cells: Vec<(usize, usize, usize)> = grid.present().map(|(x, y, _)| (index(x, y), x, y)).collect();
    cells.sort_unstable();
    let mut neighbours = Map::new();
    for &(i, x, y) in &cells {
        let mut list = Vec::new();
        if grid.connected_up(x, y) {
            list.push(index(x, y - 1));
        }
        if grid.connected_down(x, y) {
            list.push(index(x, y + 1));
        }
        if grid.connected_left(x, y) {
            list.push(index(x - 1, y));
        }
        if grid.connected_right(x, y) {
            list.push(index(x + 1, y));
        }
        list.sort_unstable();
        neighbours.insert(i.to_string(), Value::from(list));
    }
    let robot = serde_json::json!({
        "indices": cells.iter().map(|c| c.0).collect::<Vec<_>>(),
        "types": cells.iter().map(|&(_, x, y)| grid.at(x, y).code()).collect::<Vec<_>>(),
        "neighbors": neighbours,
    });
    let file = serde_json::json!({"grid_width": w, "grid_height": h, "objects": {"robot": robot}});
    serde_json::to_string_pretty(&file).expect("a robot always serialises")
}

/// A positive size field no larger than [`MAX_SIDE`].
fn size(value: &Value, field: &str) -> Result<usize, FieldError> {
    value
        .get(field)
        .and_then(Value::as_u64)
        .filter(|&n| n > 0 && n as usize <= MAX_SIDE)
        .map(|n| n as usize)
        .ok_or_else(|| FieldError::sentence(field, format!("must be an integer between 1 and {MAX_SIDE}")))
}

/// One object: its grid and the position of its bottom-left cell.
fn read_object(object: &Value, width: usize, height: usize) -> Result<(MaterialGrid, (usize, usize)), FieldError> {
    let indices = index_list(object.get("indices"), "indices", width * height)?;
    let types = object
        .get("types")
        .and_then(Value::as_array)
        .ok_or_else(|| FieldError::new("types", "missing: expected a list of material codes"))?;
    if types.len() != indices.len() {
        return Err(FieldError::new(
            "types",
            format!("{} types for {} indices", types.len(), indices.len()),
        ));
    }
    if indices.is_empty() {
        return Err(FieldError::new("indices", "no cell: an object needs at least one"));
    }
    let cell = |i: usize| (i % width, i / width);
    let x0 = indices.iter().map(|&i| cell(i).0).min().unwrap_or(0);
    let y0 = indices.iter().map(|&i| cell(i).1).min().unwrap_or(0);
    let w = indices.iter().map(|&i| cell(i).0).max().unwrap_or(0) - x0 + 1;
    let h = indices.iter().map(|&i| cell(i).1).max().unwrap_or(0) - y0 + 1;
    // Grid rows run from the top: file row y is grid row h - 1 - (y - y0).
    let local = |i: usize| (cell(i).0 - x0, h - 1 - (cell(i).1 - y0));
    let mut cells = vec![Material::Empty; w * h];
    for (k, (&i, t)) in indices.iter().zip(types).enumerate() {
        let m = t
            .as_u64()
            .and_then(Material::from_code)
            .filter(|m| m.is_present())
            .ok_or_else(|| FieldError::new(format!("types[{k}]"), format!("{t} is no material code 1-5")))?;
        let (x, y) = local(i);
        if cells[y * w + x].is_present() {
            return Err(FieldError::new(
                format!("indices[{k}]"),
                format!("cell {i} listed twice"),
            ));
        }
        cells[y * w + x] = m;
    }
    let mut grid = MaterialGrid::unconnected(w, h, cells);
    connect(&mut grid, object.get("neighbors"), &indices, width * height, &local)?;
    grid.validate_object()?;
    Ok((grid, (x0, y0)))
}

/// A list of cell indices below `limit`.
fn index_list(value: Option<&Value>, field: &str, limit: usize) -> Result<Vec<usize>, FieldError> {
    let list = value
        .and_then(Value::as_array)
        .ok_or_else(|| FieldError::new(field, "missing: expected a list of cell indices"))?;
    list.iter()
        .enumerate()
        .map(|(k, v)| {
            v.as_u64()
                .map(|i| i as usize)
                .filter(|&i| i < limit)
                .ok_or_else(|| FieldError::new(format!("{field}[{k}]"), format!("{v} is no cell index below {limit}")))
        })
        .collect()
}

/// Applies the `neighbors` table: every listed cell has an entry, every neighbour is a listed
/// 4-adjacent cell.
fn connect(
    grid: &mut MaterialGrid,
    neighbours: Option<&Value>,
    indices: &[usize],
    limit: usize,
    local: &dyn Fn(usize) -> (usize, usize),
) -> Result<(), FieldError> {
    let table: &Map<String, Value> = neighbours
        .and_then(Value::as_object)
        .ok_or_else(|| FieldError::new("neighbors", "missing: expected a table from cell index to neighbours"))?;
    for &i in indices {
        let key = i.to_string();
        let field = format!("neighbors.{key}");
        let list = index_list(table.get(&key), &field, limit)?;
        for (k, n) in list.into_iter().enumerate() {
            if !indices.contains(&n) {
                return Err(FieldError::new(
                    format!("{field}[{k}]"),
                    format!("{n} is not a cell of this object"),
                ));
            }
            grid.connect(local(i), local(n))
                .map_err(|m| FieldError::new(format!("{field}[{k}]"), m.to_string()))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 2 world: a fixed floor (cells 0, 1, 2 on the bottom row) and a rigid block on cell 4
    /// (column 1, row 1).
    const SMALL: &str = r#"{"grid_width": 3, "grid_height": 2, "objects": {
        "ground": {"indices": [0, 1, 2], "types": [5, 5, 5],
                   "neighbors": {"0": [1], "1": [0, 2], "2": [1]}},
        "block": {"indices": [4], "types": [1], "neighbors": {"4": []}}}}"#;

    #[test]
    fn a_world_file_reads_into_placed_objects() {
        let w = world_from_json(SMALL).unwrap();
        let names: Vec<&str> = w.objects().iter().map(|o| o.name.as_str()).collect();
        assert_eq!(names, ["block", "ground"], "name order");
        assert_eq!(w.objects()[0].origin, (1, 1));
        assert_eq!(w.objects()[0].grid.to_rows(), "1");
        assert_eq!(w.objects()[1].origin, (0, 0));
        assert_eq!(w.objects()[1].grid.to_rows(), "555");
        assert!(w.objects()[1].grid.connected_right(0, 0));
    }

    #[test]
    fn rows_of_a_file_count_from_the_bottom() {
        let text = r#"{"grid_width": 2, "grid_height": 2, "objects": {"r": {
            "indices": [0, 2, 3], "types": [1, 3, 4],
            "neighbors": {"0": [2], "2": [0, 3], "3": [2]}}}}"#;
        let g = robot_from_json(text).unwrap();
        assert_eq!(g.to_rows(), "34/10");
    }

    #[test]
    fn wrong_files_are_refused_naming_the_field() {
        let cases = [
            (SMALL.replace("\"grid_width\": 3", "\"grid_width\": 0"), "grid_width"),
            (SMALL.replace("[5, 5, 5]", "[5, 5, 9]"), "objects.ground.types[2]"),
            (SMALL.replace("[5, 5, 5]", "[5, 5]"), "objects.ground.types"),
            (SMALL.replace("[0, 1, 2]", "[0, 1, 7]"), "objects.ground.indices[2]"),
            (
                SMALL.replace("\"2\": [1]", "\"2\": [0]"),
                "objects.ground.neighbors.2[0]",
            ),
            (SMALL.replace("\"2\": [1]", "\"3\": [1]"), "objects.ground.neighbors.2"),
            (SMALL.replace("\"4\": []", "\"4\": [1]"), "objects.block.neighbors.4[0]"),
            (
                SMALL.replace(
                    "{\"0\": [1], \"1\": [0, 2], \"2\": [1]}",
                    "{\"0\": [], \"1\": [], \"2\": []}",
                ),
                "objects.ground.cells",
            ),
        ];
        for (text, path) in cases {
            let e = world_from_json(&text).unwrap_err();
            assert_eq!(e.path, path, "{e}");
        }
        let e = robot_from_json(SMALL).unwrap_err();
        assert_eq!(e.path, "objects");
        let one = r#"{"grid_width": 1, "grid_height": 1, "objects": {"r": {"indices": [0], "types": [2], "neighbors": {"0": []}}}}"#;
        let e = robot_from_json(one).unwrap_err();
        assert_eq!(e.path, "objects.r.cells");
        assert!(e.message.contains("actuator"), "{e}");
    }

    #[test]
    fn overlapping_objects_are_refused() {
        let text = SMALL
            .replace("\"indices\": [4]", "\"indices\": [1]")
            .replace("{\"4\": []}", "{\"1\": []}");
        let e = world_from_json(&text).unwrap_err();
        assert!(e.message.contains("overlaps"), "{e}");
    }
}
