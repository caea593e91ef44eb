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
//!
//! [`random_aperture_world`] draws the original's randomised variant (`_create_random_world`).

use rand::seq::IndexedRandom;
use rand::Rng;
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
    /// Side walls from the near side up to the wall (random worlds only), two voxels high.
    pub side_walls: Vec<[i32; 3]>,
    /// The target cell (a fixed voxel, as in the original).
    pub target: [i32; 3],
    /// The aperture's cells along x, [first, last).
    pub aperture: (i32, i32),
}

/// The sizes every world of a body length shares, in lattice cells.
struct Sizes {
    /// The body length L.
    l: i32,
    /// ⌊1.5 L⌋: the centre of the world across, where the body and the nominal aperture sit.
    start: i32,
    /// ⌊L/2⌋.
    gap: i32,
    /// y of the wall: 2 gap + 2 L.
    wall_y: i32,
}

impl Sizes {
    fn of(length: usize) -> Sizes {
        let l = length as i32;
        let gap = l / 2;
        Sizes {
            l,
            start: (3 * l) / 2,
            gap,
            wall_y: 2 * gap + 2 * l,
        }
    }

    /// The world with the aperture `[first, end)` carved through the wall, the target at
    /// `target_x` (beyond the wall when passable, right behind it otherwise), these side walls,
    /// and the body's `width` × `depth` box placed as the original.
    fn world(
        &self,
        (first, end): (i32, i32),
        target_x: i32,
        environment: Environment,
        (width, depth): (usize, usize),
        side_walls: Vec<[i32; 3]>,
    ) -> ApertureWorld {
        let wall = (0..3 * self.l)
            .filter(|x| !(first..end).contains(x))
            .flat_map(|x| [[x, self.wall_y, 0], [x, self.wall_y, 1]])
            .collect();
        let target_y = if environment.passable() {
            self.wall_y + self.l
        } else {
            self.wall_y + 1
        };
        ApertureWorld {
            body_origin: [
                self.start - width as i32 / 2,
                self.gap + self.start - depth as i32 / 2,
                0,
            ],
            wall,
            side_walls,
            target: [target_x, target_y, 0],
            aperture: (first, end),
        }
    }
}

/// The world of `environment` for a body of length `length` voxels whose bounding box is
/// `width` × `depth` cells (x, y).
pub fn aperture_world(environment: Environment, length: usize, width: usize, depth: usize) -> ApertureWorld {
    let sizes = Sizes::of(length);
    let (l, start) = (sizes.l, sizes.start);
    let aperture = if environment.passable() { l - 1 } else { 1 };
    let mut left_bank = start - aperture / 2 - 1;
    let mut right_bank = start + aperture / 2 + 1;
    let shift = (aperture + 1) / 2;
    match environment {
        Environment::PassableLeft => (left_bank, right_bank) = (left_bank - shift, right_bank - shift),
        Environment::PassableRight => (left_bank, right_bank) = (left_bank + shift, right_bank + shift),
        Environment::Impassable => {}
    }
    sizes.world(
        (left_bank + 1, right_bank),
        start,
        environment,
        (width, depth),
        Vec::new(),
    )
}

/// A side wall's shape in a random world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SideWall {
    None,
    /// Straight from the near side to the wall.
    Straight,
    /// Outside the body's half, stepping in by L/4 at the body's far edge.
    Knee,
}

/// The original's randomised world of `environment` (Voxcraft-python's `_create_random_world`),
/// drawn from `rng`: the aperture's centre uniform in `start − 2 + [0, L/2]`, its nominal width
/// `a` uniform in `[0, L/2]` (impassable) or `{L+1, L+2, L+3}` (passable), carved
/// `[centre − ⌊a/2⌋, centre + ⌊a/2⌋)`; each side wall none, straight or a knee, 1 to ⌊L/3⌋ cells
/// outside the body's span or the aperture; the target at (centre, y_w + L) or right behind the
/// wall. The body is placed as in [`aperture_world`].
pub fn random_aperture_world(
    environment: Environment,
    length: usize,
    width: usize,
    depth: usize,
    rng: &mut impl Rng,
) -> ApertureWorld {
    let sizes = Sizes::of(length);
    let (l, start, gap, wall_y) = (sizes.l, sizes.start, sizes.gap, sizes.wall_y);
    let centre = start - 2 + rng.random_range(0..=l / 2);
    let a = match environment.passable() {
        true => l + rng.random_range(1..=3),
        false => rng.random_range(0..=l / 2),
    };
    let (first, end) = (centre - a / 2, centre + a / 2);
    let inset = 1..=(l / 3).max(1);
    let left = l.min(first) - rng.random_range(inset.clone());
    let right = (2 * l).max(end) + rng.random_range(inset);
    let kinds = [SideWall::None, SideWall::Straight, SideWall::Knee];
    let left_kind = *kinds.choose(rng).expect("three kinds");
    let right_kind = *kinds.choose(rng).expect("three kinds");
    let near = (l - 4).max(0);
    let elbow = gap + start + l / 2;
    let mut cells = Vec::new();
    let mut column = |x: i32, ys: std::ops::Range<i32>| cells.extend(ys.map(|y| [x, y]));
    match left_kind {
        SideWall::None => {}
        SideWall::Straight => column(left, near..wall_y),
        SideWall::Knee => {
            let inner = left + l / 4 - 1;
            column(left - 1, near..elbow);
            (left - 1..inner).for_each(|x| column(x, elbow..elbow + 1));
            column(inner, elbow..wall_y);
        }
    }
    match right_kind {
        SideWall::None => {}
        SideWall::Straight => column(right, near..wall_y),
        SideWall::Knee => {
            let inner = right - l / 4;
            column(right, near..elbow);
            (inner..right + 1).for_each(|x| column(x, elbow..elbow + 1));
            column(inner, elbow..wall_y);
        }
    }
    cells.sort_unstable();
    cells.dedup();
    let side_walls = cells.into_iter().flat_map(|[x, y]| [[x, y, 0], [x, y, 1]]).collect();
    sizes.world((first, end), centre, environment, (width, depth), side_walls)
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

    #[test]
    fn random_worlds_follow_the_originals_ranges() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let (mut widths, mut kinds_seen) = (std::collections::BTreeSet::new(), 0);
        for _ in 0..200 {
            for env in Environment::ALL {
                // the starfish: L = 9, start 13, wall at y = 26, body x in [9, 18)
                let w = random_aperture_world(env, 9, 9, 9, &mut rng);
                let (first, end) = w.aperture;
                let centre = (first + end) / 2;
                assert!((11..=15).contains(&centre), "{:?}", w.aperture);
                let width = end - first;
                widths.insert((env.passable(), width));
                match env.passable() {
                    true => assert!([10, 12].contains(&width) && w.target == [centre, 35, 0]),
                    false => assert!(width <= 4 && w.target == [centre, 27, 0]),
                }
                assert_eq!(w.wall.len(), 2 * (27 - width) as usize);
                // side walls stay outside the body's span and in front of the wall
                assert!(w
                    .side_walls
                    .iter()
                    .all(|c| (c[0] < 9 || c[0] >= 18 || c[1] >= 21) && (5..26).contains(&c[1])));
                kinds_seen += usize::from(!w.side_walls.is_empty());
            }
        }
        assert_eq!(
            widths.into_iter().collect::<Vec<_>>(),
            [(false, 0), (false, 2), (false, 4), (true, 10), (true, 12)]
        );
        assert!(kinds_seen > 400, "most worlds have a side wall: {kinds_seen} of 600");
    }
}
