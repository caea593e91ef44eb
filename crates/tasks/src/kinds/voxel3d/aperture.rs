//! The affordance study's worlds (thesis §5.1.3.2, Voxcraft-python's `_create_fixed_world`,
//! thesis-code-facts §7.1): a body of length L voxels in front of a wall two voxels high across
//! the whole world, with an aperture through it, and a target cell.
//!
//! In lattice cells (x across, y towards the wall, z up), with `start = ⌊1.5 L⌋`,
//! `gap = ⌊L/2⌋` and the wall at `y_w = 2 gap + 2 L` spanning x in [0, 3L):
//! - the body's bounding box starts at (start − ⌊W/2⌋, gap + start − ⌊H/2⌋, 0) (which puts the
//!   study's three shapes where its code put them);
//! - `impassable`: an aperture 1 voxel wide at x = start, the target right behind it at
//!   (start, y_w + 1, 0);
//! - `passable-left`, `passable-right`: an aperture `2⌊(L−1)/2⌋ + 1` wide, centred at start and
//!   shifted by ∓⌈(L−1)/2⌉, the target at (start, y_w + L, 0) beyond the wall.

use serde::{Deserialize, Serialize};

/// One of the three environments of an evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Environment {
    /// An aperture 1 voxel wide: the robot should stop in front of it.
    Impassable,
    /// A wide aperture shifted to the left (−x).
    PassableLeft,
    /// A wide aperture shifted to the right (+x).
    PassableRight,
}

impl Environment {
    /// The three, in the study's order.
    pub const ALL: [Environment; 3] = [
        Environment::Impassable,
        Environment::PassableLeft,
        Environment::PassableRight,
    ];

    /// Whether the robot fits through (the ground truth of the votes).
    pub fn passable(self) -> bool {
        self != Environment::Impassable
    }

    /// Its name in metrics (`impassable`, `passable-left`, `passable-right`).
    pub fn name(self) -> &'static str {
        match self {
            Environment::Impassable => "impassable",
            Environment::PassableLeft => "passable-left",
            Environment::PassableRight => "passable-right",
        }
    }
}

/// A world of the study, in lattice cells.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ApertureWorld {
    /// Where the body's bounding box starts.
    pub body_origin: [i32; 3],
    /// The wall's cells.
    pub wall: Vec<[i32; 3]>,
    /// The target cell (a fixed voxel, as in the original).
    pub target: [i32; 3],
    /// The aperture's cells along x, [first, last).
    pub aperture: (i32, i32),
}

/// The world of `environment` for a body of length `length` voxels whose bounding box is
/// `width` × `depth` cells (x, y).
pub fn aperture_world(environment: Environment, length: usize, width: usize, depth: usize) -> ApertureWorld {
    let l = length as i32;
    let start = (3 * l) / 2;
    let gap = l / 2;
    let wall_y = 2 * gap + 2 * l;
    let aperture = if environment.passable() { l - 1 } else { 1 };
    let mut left_bank = start - aperture / 2 - 1;
    let mut right_bank = start + aperture / 2 + 1;
    let shift = (aperture + 1) / 2;
    match environment {
        Environment::PassableLeft => (left_bank, right_bank) = (left_bank - shift, right_bank - shift),
        Environment::PassableRight => (left_bank, right_bank) = (left_bank + shift, right_bank + shift),
        Environment::Impassable => {}
    }
    let wall = (0..3 * l)
        .filter(|x| !(left_bank + 1..right_bank).contains(x))
        .flat_map(|x| [[x, wall_y, 0], [x, wall_y, 1]])
        .collect();
    let target = match environment.passable() {
        true => [start, wall_y + l, 0],
        false => [start, wall_y + 1, 0],
    };
    ApertureWorld {
        body_origin: [start - width as i32 / 2, gap + start - depth as i32 / 2, 0],
        wall,
        target,
        aperture: (left_bank + 1, right_bank),
    }
}

/// The study's body length of its named shapes (flatworm 4, starfish 9, gecko 6).
pub fn shape_length(body: &str) -> Option<usize> {
    match body.trim() {
        "flatworm" => Some(4),
        "starfish" => Some(9),
        "gecko" => Some(6),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_starfish_worlds_are_the_originals() {
        // L = 9: start 13, gap 4, wall at y = 26; the starfish's 9 × 9 box from (9, 13)
        let w = aperture_world(Environment::Impassable, 9, 9, 9);
        assert_eq!(w.body_origin, [9, 13, 0]);
        assert_eq!(w.aperture, (13, 14));
        assert_eq!(w.target, [13, 27, 0]);
        assert_eq!(w.wall.len(), 2 * (27 - 1));
        assert!(w.wall.iter().all(|c| c[1] == 26 && c[2] <= 1));
        // passable: 8 wide nominal, carved 2⌊8/2⌋ + 1 = 9 wide, shifted by 4
        let left = aperture_world(Environment::PassableLeft, 9, 9, 9);
        assert_eq!(left.aperture, (9 - 4, 18 - 4));
        assert_eq!(left.target, [13, 35, 0]);
        let right = aperture_world(Environment::PassableRight, 9, 9, 9);
        assert_eq!(right.aperture, (9 + 4, 18 + 4));
        assert_eq!(right.wall.len(), 2 * (27 - 9));
    }

    #[test]
    fn the_flatworm_and_gecko_sit_where_the_original_put_them() {
        // flatworm: L = 4, cells x in [start − 2, start + 3), y from gap + start − 2 = 6 − 2 + 2
        let w = aperture_world(Environment::PassableRight, 4, 5, 5);
        assert_eq!(w.body_origin, [4, 6, 0]);
        // carved 2⌊3/2⌋ + 1 = 3 wide around 6, shifted by ⌈3/2⌉ = 2
        assert_eq!(w.aperture, (7, 10));
        // gecko: L = 6, start 9, gap 3: box from (6, 9)
        assert_eq!(aperture_world(Environment::Impassable, 6, 6, 6).body_origin, [6, 9, 0]);
        assert_eq!(shape_length("gecko"), Some(6));
        assert!(Environment::PassableLeft.passable() && !Environment::Impassable.passable());
    }
}
