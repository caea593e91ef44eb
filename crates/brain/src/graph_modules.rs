//! Modules of a graph brain (thesis §4.1, thesis-code-facts.md §4.4–4.6): module maps of a body
//! (which grid cells belong together), the per-generation statistics of a graph (size |G|,
//! connection cost, share of within-module edges), module compactness and the automatic
//! discovery of a module.
//!
//! Compactness follows the thesis' formula (4.5): the |w| + |b| mass of the edges inside a
//! candidate module over that of every edge touching it, in [0, 1]. The original code ranks
//! candidates by the inverse ratio (crossing ÷ inside) and divides by zero when a candidate has
//! no inside edge; here a candidate that no edge touches, or whose edges all weigh 0, has
//! compactness 0, so every score is finite and a module is always returned.

use crate::controllers::graph::{GraphSpec, NeuronSpec};
use serde::{Deserialize, Serialize};
use std::collections::BTreeSet;
use vsrlab_body::Morphology;
use vsrlab_field::FieldError;

/// A grid cell (x, y), y = 0 at the bottom.
pub type Cell = (usize, usize);

/// Which module each voxel of a body belongs to.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ModuleMap {
    width: usize,
    /// Module per grid cell, row-major from the bottom row; `usize::MAX` where there is no voxel.
    cells: Vec<usize>,
}

/// The module names [`ModuleMap::parse`] knows.
pub const NAMED_MODULE_MAPS: [&str; 3] = ["halves", "legs-torso", "voxels"];

impl ModuleMap {
    /// A map from a function of the cell.
    pub fn from_fn(morphology: &Morphology, module: impl Fn(usize, usize) -> usize) -> ModuleMap {
        let (w, h) = (morphology.width(), morphology.height());
        let mut cells = vec![usize::MAX; w * h];
        for (x, y) in morphology.voxels() {
            cells[y * w + x] = module(x, y);
        }
        ModuleMap { width: w, cells }
    }

    /// Two modules: the cells of `region` (module 1) and the others (module 0).
    pub fn of_region(morphology: &Morphology, region: &[Cell]) -> ModuleMap {
        Self::from_fn(morphology, |x, y| usize::from(region.contains(&(x, y))))
    }

    /// A map by name or as rows of digits, top row first, separated by `/` (`.` where the body
    /// has no voxel): `halves` (x < W/2 and the rest: the worm's back and front), `legs-torso`
    /// (the first column, the last column, the columns between: the thesis' biped), `voxels`
    /// (every voxel its own module), or e.g. `0112/0112/0..2`. The error is about the text as a
    /// whole (no field path).
    pub fn parse(text: &str, morphology: &Morphology) -> Result<ModuleMap, FieldError> {
        let w = morphology.width();
        match text {
            "halves" => Ok(Self::from_fn(morphology, |x, _| usize::from(2 * x >= w))),
            "legs-torso" => Ok(Self::from_fn(morphology, |x, _| match x {
                0 => 0,
                x if x + 1 == w => 1,
                _ => 2,
            })),
            "voxels" => Ok(Self::from_fn(morphology, |x, y| y * w + x)),
            rows => Self::from_rows(rows, morphology).map_err(|e| {
                FieldError::message(format!(
                    "{e} (a module map is one of {} or rows of digits such as \"0112/0112/0..2\")",
                    NAMED_MODULE_MAPS.join(", ")
                ))
            }),
        }
    }

    /// A map from rows of digits; the error says which row or cell is wrong.
    fn from_rows(text: &str, morphology: &Morphology) -> Result<ModuleMap, FieldError> {
        let rows: Vec<&str> = text.split('/').collect();
        let (w, h) = (morphology.width(), morphology.height());
        if rows.len() != h || rows.iter().any(|r| r.chars().count() != w) {
            return Err(FieldError::message(format!(
                "\"{text}\" is not a {w}×{h} grid like the body's"
            )));
        }
        let mut cells = vec![usize::MAX; w * h];
        for (i, row) in rows.iter().enumerate() {
            let y = h - 1 - i;
            for (x, c) in row.chars().enumerate() {
                match (c.to_digit(10), morphology.has(x, y)) {
                    (Some(d), true) => cells[y * w + x] = d as usize,
                    (None, false) if c == '.' => {}
                    (_, true) => {
                        return Err(FieldError::message(format!(
                            "cell ({x}, {y}) holds a voxel: give it a module digit, not '{c}'"
                        )))
                    }
                    (_, false) => {
                        return Err(FieldError::message(format!(
                            "cell ({x}, {y}) holds no voxel: write '.' there, not '{c}'"
                        )))
                    }
                }
            }
        }
        Ok(ModuleMap { width: w, cells })
    }

    /// The map as rows of digits, top row first, `.` where there is no voxel (the form
    /// [`ModuleMap::parse`] reads; modules above 9 are written modulo 10).
    pub fn to_rows(&self) -> String {
        let h = self.cells.len() / self.width.max(1);
        grid_rows(self.width, h, |x, y| match self.module(x, y) {
            usize::MAX => '.',
            m => digit(m),
        })
    }

    /// The module of cell (x, y) (`usize::MAX` outside the body).
    pub fn module(&self, x: usize, y: usize) -> usize {
        self.cells.get(y * self.width + x).copied().unwrap_or(usize::MAX)
    }

    /// Whether two cells lie in the same module.
    pub fn same(&self, a: Cell, b: Cell) -> bool {
        self.module(a.0, a.1) == self.module(b.0, b.1)
    }
}

/// A W × H grid written as rows of one character per cell, top row first, joined by `/` (the
/// form of module maps, regions and partitions in files and messages).
pub fn grid_rows(width: usize, height: usize, cell: impl Fn(usize, usize) -> char) -> String {
    (0..height)
        .rev()
        .map(|y| (0..width).map(|x| cell(x, y)).collect::<String>())
        .collect::<Vec<_>>()
        .join("/")
}

/// The last decimal digit of `n`, as a character.
pub fn digit(n: usize) -> char {
    char::from_digit((n % 10) as u32, 10).unwrap_or('?')
}

/// A body region by name or as rows, top row first (`#` in the region, `.` not): `legs` (the
/// first and the last column: the thesis' biped cut), `back-half` (x < W/2: the worm's),
/// `front-half` (the rest), or e.g. `#..#/#..#/#..#`. Cells without a voxel are left out. The
/// error is about the text as a whole (no field path).
pub fn region(text: &str, morphology: &Morphology) -> Result<Vec<Cell>, FieldError> {
    let w = morphology.width();
    let pick = |f: &dyn Fn(usize) -> bool| morphology.voxels().filter(|&(x, _)| f(x)).collect::<Vec<_>>();
    let cells = match text {
        "legs" => pick(&|x| x == 0 || x + 1 == w),
        "back-half" => pick(&|x| 2 * x < w),
        "front-half" => pick(&|x| 2 * x >= w),
        rows => {
            let lines: Vec<&str> = rows.split('/').collect();
            let h = morphology.height();
            if lines.len() != h
                || lines.iter().any(|r| r.chars().count() != w)
                || rows.contains(|c| c != '#' && c != '.' && c != '/')
            {
                return Err(FieldError::message(format!(
                    "\"{text}\" is neither legs, back-half, front-half nor a {w}×{h} grid of '#' (in the region) and '.'"
                )));
            }
            morphology
                .voxels()
                .filter(|&(x, y)| lines[h - 1 - y].as_bytes()[x] == b'#')
                .collect()
        }
    };
    if cells.is_empty() || cells.len() == morphology.voxel_count() {
        return Err(FieldError::message(format!(
            "\"{text}\" must cover some of the body's voxels, not none or all"
        )));
    }
    Ok(cells)
}

/// What is logged per generation about a graph.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GraphStats {
    /// |V|.
    pub neurons: usize,
    /// |E|.
    pub edges: usize,
    /// |G| = |V| + |E| (thesis eq. 4.3).
    pub size: usize,
    /// Σ Euclidean edge lengths in voxel cells (the original's "connection cost", not squared).
    pub connection_cost: f64,
    /// Share of edges whose ends lie in the same module (NaN without edges).
    pub within_module: f64,
}

/// The statistics of a graph (neurons listed) under a module map.
pub fn stats(g: &GraphSpec, modules: &ModuleMap) -> GraphStats {
    let cell = |i: usize| g.neurons[i].cell();
    let connection_cost = g
        .edges
        .iter()
        .map(|e| {
            let ((ax, ay), (bx, by)) = (cell(e.from), cell(e.to));
            (ax as f64 - bx as f64).hypot(ay as f64 - by as f64)
        })
        .sum();
    let within = g
        .edges
        .iter()
        .filter(|e| modules.same(cell(e.from), cell(e.to)))
        .count();
    GraphStats {
        neurons: g.neurons.len(),
        edges: g.edges.len(),
        size: g.neurons.len() + g.edges.len(),
        connection_cost,
        within_module: if g.edges.is_empty() {
            f64::NAN
        } else {
            within as f64 / g.edges.len() as f64
        },
    }
}

/// The |w| + |b| mass of edge k.
pub(crate) fn mass(g: &GraphSpec, k: usize) -> f64 {
    g.parameters[2 * k].abs() + g.parameters[2 * k + 1].abs()
}

/// Module compactness (thesis eq. 4.5): the mass of the edges with both ends in `region` over
/// the mass of the edges with at least one end there; 0 when no edge, or no mass, touches it.
pub fn compactness(g: &GraphSpec, region: &[Cell]) -> f64 {
    let inside = |i: usize| region.contains(&g.neurons[i].cell());
    let (mut touching, mut within) = (0.0, 0.0);
    for (k, e) in g.edges.iter().enumerate() {
        let (a, b) = (inside(e.from), inside(e.to));
        if a || b {
            touching += mass(g, k);
            if a && b {
                within += mass(g, k);
            }
        }
    }
    if touching > 0.0 {
        within / touching
    } else {
        0.0
    }
}

/// A body split by [`discover`]: the most compact module and the pieces the rest falls into.
#[derive(Debug, Clone, PartialEq)]
pub struct Partition {
    /// The discovered module's cells, in grid order.
    pub module: Vec<Cell>,
    /// Its compactness.
    pub compactness: f64,
    /// The 4-connected pieces of the rest of the body, each in grid order.
    pub rest: Vec<Vec<Cell>>,
}

/// Largest candidate module [`discover`] enumerates (the count of candidates grows fast).
pub const MAX_MODULE_SIZE: usize = 8;

/// Automatic module discovery (thesis §4.1.5.7): among every 4-connected set of `sizes` voxels
/// (smaller than the body; sizes above [`MAX_MODULE_SIZE`] are ignored), the one of greatest
/// compactness; ties go to the smaller set, then to the one whose cell list (each sorted
/// by row, then column) compares first. `None` only when
/// the body has no such set. Unlike the original's heuristic, every connected set is a candidate.
pub fn discover(g: &GraphSpec, morphology: &Morphology, sizes: std::ops::RangeInclusive<usize>) -> Option<Partition> {
    let voxels: Vec<Cell> = morphology.voxels().collect();
    let largest = (*sizes.end()).min(MAX_MODULE_SIZE).min(voxels.len().saturating_sub(1));
    let mut best: Option<(f64, Vec<Cell>)> = None;
    for set in connected_sets(morphology, largest) {
        if set.len() < *sizes.start() {
            continue;
        }
        let c = compactness(g, &set);
        let better = match &best {
            None => true,
            Some((bc, bs)) => c > *bc || (c == *bc && (set.len(), &set) < (bs.len(), bs)),
        };
        if better {
            best = Some((c, set));
        }
    }
    let (compactness, module) = best?;
    let rest_cells: Vec<Cell> = voxels.iter().copied().filter(|c| !module.contains(c)).collect();
    Some(Partition {
        rest: pieces(&rest_cells),
        module,
        compactness,
    })
}

fn neighbours((x, y): Cell) -> impl Iterator<Item = Cell> {
    [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)].into_iter()
}

/// Every 4-connected set of at most `largest` voxels, each sorted in grid order (y, then x).
fn connected_sets(morphology: &Morphology, largest: usize) -> BTreeSet<Vec<Cell>> {
    let key = |c: &Cell| (c.1, c.0);
    let mut all = BTreeSet::new();
    let mut frontier: Vec<Vec<Cell>> = morphology.voxels().map(|c| vec![c]).collect();
    while let Some(set) = frontier.pop() {
        if !all.insert(set.clone()) || set.len() == largest {
            continue;
        }
        for &c in &set {
            for n in neighbours(c) {
                if morphology.has(n.0, n.1) && !set.contains(&n) {
                    let mut bigger = set.clone();
                    bigger.push(n);
                    bigger.sort_by_key(key);
                    if !all.contains(&bigger) {
                        frontier.push(bigger);
                    }
                }
            }
        }
    }
    all
}

/// The 4-connected pieces of a set of cells.
fn pieces(cells: &[Cell]) -> Vec<Vec<Cell>> {
    let mut left: Vec<Cell> = cells.to_vec();
    let mut out = Vec::new();
    while let Some(start) = left.first().copied() {
        let mut piece = vec![start];
        left.retain(|&c| c != start);
        let mut i = 0;
        while i < piece.len() {
            for n in neighbours(piece[i]) {
                if let Some(k) = left.iter().position(|&c| c == n) {
                    piece.push(left.remove(k));
                }
            }
            i += 1;
        }
        piece.sort_by_key(|c| (c.1, c.0));
        out.push(piece);
    }
    out
}

/// Whether a neuron is a hidden one.
pub(crate) fn is_hidden(n: &NeuronSpec) -> bool {
    matches!(n, NeuronSpec::Hidden { .. })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controllers::graph::EdgeSpec;
    use crate::Activation;

    fn biped() -> Morphology {
        Morphology::named("biped-4x3").unwrap()
    }

    /// A biped graph with an actuator per voxel and the given edges (weight 1, bias `b`).
    fn graph(edges: &[(Cell, Cell)], b: f64) -> GraphSpec {
        let m = biped();
        let neurons: Vec<NeuronSpec> = m
            .voxels()
            .map(|(x, y)| NeuronSpec::Hidden {
                x,
                y,
                activation: Activation::Tanh,
            })
            .collect();
        let index = |c: Cell| neurons.iter().position(|n| n.cell() == c).unwrap();
        let edges: Vec<EdgeSpec> = edges
            .iter()
            .map(|&(a, b)| EdgeSpec {
                from: index(a),
                to: index(b),
            })
            .collect();
        GraphSpec {
            parameters: edges.iter().flat_map(|_| [1.0, b]).collect(),
            neurons,
            edges,
            grow: 0,
        }
    }

    #[test]
    fn module_maps_by_name_and_by_rows_agree() {
        let m = biped();
        let named = ModuleMap::parse("legs-torso", &m).unwrap();
        let rows = ModuleMap::parse("0221/0221/0..1", &m).unwrap();
        assert_eq!(named, rows);
        assert!(named.same((1, 2), (2, 1)) && !named.same((0, 0), (3, 0)));
        let worm = Morphology::named("worm-6x2").unwrap();
        let halves = ModuleMap::parse("halves", &worm).unwrap();
        assert!(halves.same((0, 0), (2, 1)) && !halves.same((2, 0), (3, 0)));
        let err = ModuleMap::parse("0221/0221/0221", &m).unwrap_err();
        assert!(err.message.starts_with("cell (1, 0) holds no voxel"), "{err}");
        assert_eq!(err.path, "");
        assert!(ModuleMap::parse("tripartite", &m)
            .unwrap_err()
            .to_string()
            .contains("halves, legs-torso, voxels"));
    }

    #[test]
    fn regions_by_name_and_rows() {
        let m = biped();
        assert_eq!(region("legs", &m).unwrap(), region("#..#/#..#/#..#", &m).unwrap());
        assert_eq!(region("legs", &m).unwrap().len(), 6);
        let worm = Morphology::named("worm-6x2").unwrap();
        assert_eq!(region("back-half", &worm).unwrap().len(), 6);
        assert!(region("####/####/#..#", &m)
            .unwrap_err()
            .to_string()
            .contains("not none or all"));
        assert!(region("head", &m).is_err());
    }

    #[test]
    fn stats_count_size_cost_and_within_share() {
        let g = graph(&[((0, 0), (0, 1)), ((0, 1), (3, 1)), ((1, 2), (2, 2))], 0.0);
        let s = stats(&g, &ModuleMap::parse("legs-torso", &biped()).unwrap());
        assert_eq!((s.neurons, s.edges, s.size), (10, 3, 13));
        assert_eq!(s.connection_cost, 1.0 + 3.0 + 1.0);
        assert_eq!(s.within_module, 2.0 / 3.0);
    }

    #[test]
    fn compactness_is_the_inside_share_and_zero_when_untouched() {
        // (0,0)-(0,1) inside the leg; (0,1)-(1,1) leaves it; weights 1, biases 0.5
        let g = graph(&[((0, 0), (0, 1)), ((0, 1), (1, 1))], 0.5);
        assert_eq!(compactness(&g, &[(0, 0), (0, 1)]), 0.5);
        assert_eq!(compactness(&g, &[(0, 0), (0, 1), (1, 1)]), 1.0);
        // no edge touches the right leg: 0, not NaN (the original divides by zero)
        assert_eq!(compactness(&g, &[(3, 0), (3, 1)]), 0.0);
    }

    #[test]
    fn discovery_finds_the_densely_wired_set_and_splits_the_rest() {
        // a closed triangle of edges in the top row's right part, one edge leaving it
        let g = graph(
            &[
                ((1, 2), (2, 2)),
                ((2, 2), (3, 2)),
                ((3, 2), (1, 2)),
                ((3, 2), (3, 1)),
                ((0, 0), (0, 1)),
            ],
            0.0,
        );
        let p = discover(&g, &biped(), 2..=5).unwrap();
        // {(0,0),(0,1)} is fully inside too (compactness 1) and smaller: it wins the tie
        assert_eq!(p.module, vec![(0, 0), (0, 1)]);
        assert_eq!(p.compactness, 1.0);
        assert_eq!(p.rest.len(), 1);
        // without the leg's edge and with sets of 4 or 5 voxels: the triangle plus the cell its
        // edge reaches is the one set that no edge leaves
        let g = graph(
            &[((1, 2), (2, 2)), ((2, 2), (3, 2)), ((3, 2), (1, 2)), ((3, 2), (3, 1))],
            0.0,
        );
        let p = discover(&g, &biped(), 4..=5).unwrap();
        assert_eq!(p.compactness, 1.0);
        assert_eq!(p.module, vec![(3, 1), (1, 2), (2, 2), (3, 2)]);
        // an empty graph still gets a module, of compactness 0
        let empty = graph(&[], 0.0);
        let p = discover(&empty, &biped(), 2..=5).unwrap();
        assert_eq!((p.compactness, p.module.len()), (0.0, 2));
    }

    #[test]
    fn connected_sets_are_all_enumerated() {
        // a 1x3 worm: sets {a},{b},{c},{ab},{bc},{abc}
        let worm = Morphology::named("worm-3x1").unwrap();
        assert_eq!(connected_sets(&worm, 3).len(), 6);
        // 2x2 square: 4 singles, 4 dominoes, 4 triominoes, 1 square
        let square = Morphology::parse("##/##").unwrap();
        assert_eq!(connected_sets(&square, 4).len(), 13);
        let rest = pieces(&[(0, 0), (0, 1), (3, 0), (3, 1)]);
        assert_eq!(rest.len(), 2);
    }
}
