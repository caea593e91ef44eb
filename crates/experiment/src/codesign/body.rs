//! Material grids → the bodies a co-design loop trains (thesis §5.2.4): the largest 4-connected
//! piece of present cells is kept, and a body without an actuator is refused (PPO would have no
//! action to learn). Two encodings make the grids:
//!
//! - **direct** ([`kept_body`] of the genotype's own cells);
//! - **CPPN** ([`cppn_body`], EvoGym's CPPN-NEAT, commit 7db4202 `examples/cppn_neat/run.py`):
//!   the network is queried once per cell with the cell's row i, column j (cell indices, as
//!   EvoGym's `meshgrid` of the structure shape) and its distance d from the grid's centre; its
//!   five outputs score empty, rigid, soft, horizontal and vertical actuator, and the cell takes
//!   the material of the largest. As the thesis, the largest piece is kept where EvoGym instead
//!   refuses a disconnected body.

use vsrlab_body::encodings::largest_component;
use vsrlab_evolution::neat::NetworkGenome;
use vsrlab_field::FieldError;
use vsrlab_tasks::kinds::evogym::{Material, MaterialGrid};

/// The materials the five outputs score, in order.
pub const OUTPUT_MATERIALS: [Material; 5] = [
    Material::Empty,
    Material::Rigid,
    Material::Soft,
    Material::HorizontalActuator,
    Material::VerticalActuator,
];

/// The body `cppn` draws on a `width × height` grid (see the module docs), as [`kept_body`].
pub fn cppn_body(cppn: &NetworkGenome, width: usize, height: usize) -> Result<MaterialGrid, FieldError> {
    let centre = ((height as f64 - 1.0) / 2.0, (width as f64 - 1.0) / 2.0);
    let mut cells = Vec::with_capacity(width * height);
    for i in 0..height {
        for j in 0..width {
            let (x, y) = (i as f64, j as f64);
            let d = ((x - centre.0).powi(2) + (y - centre.1).powi(2)).sqrt();
            let scores = cppn.evaluate(&[x, y, d]);
            // the first of equal scores wins, as numpy's argmax
            let best = (0..OUTPUT_MATERIALS.len()).fold(0, |best, k| {
                if scores.get(k).copied().unwrap_or(f64::NEG_INFINITY) > scores[best] {
                    k
                } else {
                    best
                }
            });
            cells.push(OUTPUT_MATERIALS[best]);
        }
    }
    kept_body(width, height, cells)
}

/// The body of a `width × height` grid of cells (row by row, top first): its largest
/// 4-connected piece of present cells, the rest emptied; an error naming `body` when nothing
/// present, or no actuator, remains.
pub fn kept_body(width: usize, height: usize, cells: Vec<Material>) -> Result<MaterialGrid, FieldError> {
    let present: Vec<bool> = cells.iter().map(|m| m.is_present()).collect();
    let kept = largest_component(width, height, &present).map_err(|e| FieldError::new("body", e.to_string()))?;
    let cells: Vec<Material> = cells
        .into_iter()
        .zip(kept)
        .map(|(m, keep)| if keep { m } else { Material::Empty })
        .collect();
    if !cells.iter().any(|m| m.is_actuator()) {
        return Err(FieldError::new("body", "the body has no actuator"));
    }
    MaterialGrid::new(width, height, cells)
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_evolution::neat::{Activation, ConnectionGene, NetworkGenome, NodeGene, NodeKind};

    /// A CPPN with no connections whose outputs are their biases, plus one connection from `d`
    /// to the vertical-actuator output with weight `w`.
    fn cppn(biases: [f64; 5], w: f64) -> NetworkGenome {
        let mut nodes: Vec<NodeGene> = (0..3).map(NodeGene::input).collect();
        for (k, &bias) in biases.iter().enumerate() {
            nodes.push(NodeGene {
                id: 3 + k as u32,
                kind: NodeKind::Output,
                bias,
                activation: Activation::Identity,
            });
        }
        let connections = vec![ConnectionGene {
            innovation: 0,
            from: 2,
            to: 7,
            weight: w,
            enabled: true,
        }];
        NetworkGenome { nodes, connections }
    }

    #[test]
    fn each_cell_takes_the_material_of_the_largest_output() {
        // horizontal actuators everywhere
        let all = cppn_body(&cppn([0.0, 0.0, 0.0, 1.0, 0.0], 0.0), 5, 5).unwrap();
        assert_eq!(all.to_rows(), "33333/33333/33333/33333/33333");
        // vertical actuators where d > 1.5 (the corners' ring), horizontal inside
        let ring = cppn_body(&cppn([0.0, 0.0, 0.0, 1.0, -0.5], 1.0), 5, 5).unwrap();
        assert_eq!(ring.to_rows(), "44444/43334/43334/43334/44444");
        // empty everywhere: refused
        assert!(cppn_body(&cppn([1.0, 0.0, 0.0, 0.0, 0.0], 0.0), 5, 5).is_err());
        // soft only: no actuator, refused naming the body
        let e = cppn_body(&cppn([0.0, 0.0, 1.0, 0.0, 0.0], 0.0), 5, 5).unwrap_err();
        assert!(e.to_string().contains("no actuator"), "{e}");
    }

    #[test]
    fn of_two_pieces_the_larger_is_kept() {
        // vertical = |i − 1.9| + 0.3 j through an abs hidden node, empty = 2: the top row's
        // right four cells with the cell under the last (5 cells), and the bottom row with the
        // cell above its last (6 cells), apart
        let mut g = cppn([2.0, 0.0, 0.0, 0.0, 0.0], 0.0);
        g.connections.clear();
        g.nodes.push(NodeGene {
            id: 8,
            kind: NodeKind::Hidden,
            bias: -1.9,
            activation: Activation::Abs,
        });
        let link = |innovation, from, to, weight| ConnectionGene {
            innovation,
            from,
            to,
            weight,
            enabled: true,
        };
        g.connections = vec![link(0, 0, 8, 1.0), link(1, 8, 7, 1.0), link(2, 1, 7, 0.3)];
        let body = cppn_body(&g, 5, 5).unwrap();
        assert_eq!(body.to_rows(), "00000/00000/00000/00004/44444");
    }

    #[test]
    fn a_direct_grid_keeps_its_largest_piece() {
        let m = |c: char| Material::from_char(c).unwrap();
        // a piece of 4 cells at the top, one of 5 at the bottom
        let cells: Vec<Material> = "33000/01100/00000/04400/02220"
            .chars()
            .filter(|&c| c != '/')
            .map(m)
            .collect();
        assert_eq!(
            kept_body(5, 5, cells).unwrap().to_rows(),
            "00000/00000/00000/04400/02220"
        );
        let soft: Vec<Material> = std::iter::repeat_n(Material::Soft, 25).collect();
        assert!(kept_body(5, 5, soft).unwrap_err().to_string().contains("no actuator"));
    }

    #[test]
    fn a_ring_around_an_empty_centre_is_kept_whole() {
        // empty where d < 1.2 (the centre's cross), vertical actuators beyond: one ring, kept whole
        let ring = cppn_body(&cppn([1.2, 0.0, 0.0, 0.0, 0.0], 1.0), 5, 5).unwrap();
        assert_eq!(ring.to_rows(), "44444/44044/40004/44044/44444");
        assert!(ring.is_connected());
    }
}
