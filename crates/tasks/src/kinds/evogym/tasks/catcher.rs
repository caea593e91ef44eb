//! Catcher-v0 (`manipulate.py:458`, class `CatchSmallRect` on `PackageBase`): a soft package
//! falls from above, bouncing off two pegs; the robot keeps under it and keeps it from falling.
//!
//! EvoGym builds a new world at every reset (`random_init`): Walker-v0's ground, the robot at
//! (22, 1), a 3 × 2 soft package at (21 + ox, 41 + oy) and two fixed 5 × 1 pegs at
//! (17 + ox, 39 + oy) and (19 + ox, 25 + oy), with ox uniform in −6 … 4 and oy in 0 … 5 drawn
//! from Python's unseeded global `random`, so no two of its runs share their worlds. vsrlab
//! draws (ox, oy) from the episode's seed (ChaCha8): the same seed, the same world. The 66
//! worlds are the task's world variants ([`TaskDefinition::world_count`]).

use super::{Basics, Piece, TaskDefinition, OBJECT_THEN_ROBOT};
use crate::kinds::evogym::grid::MaterialGrid;
use crate::kinds::evogym::rewards::{Reward, RobotAndBeam, UNSTABLE_PENALTY};
use crate::kinds::evogym::worlds::{self, World, WorldObject};
use rand::{Rng, SeedableRng};

/// Catcher-v0.
pub struct Catcher;

/// The package's and the pegs' horizontal offsets (cells), as EvoGym draws them
/// (`random.randint(-6, 4)`).
const X_OFFSETS: std::ops::RangeInclusive<i32> = -6..=4;
/// Their vertical offsets (`random.randint(0, 5)`).
const Y_OFFSETS: std::ops::RangeInclusive<i32> = 0..=5;
/// How many vertical offsets there are: a world's index is `(ox + 6) · 6 + oy`.
const Y_COUNT: usize = 6;
/// Below this height the package's drop is penalised (`thresh_height`, 5 cells).
const THRESHOLD: f64 = 5.0 * 0.1;

/// Catcher-v0's names, start and length (`envs/__init__.py:155-159`); its world without
/// offsets is [`Basics::world`].
const BASICS: Basics = Basics {
    name: "Catcher-v0",
    short_name: "catcher",
    world: unshifted,
    robot_origin: (22, 1),
    episode_steps: 400,
};

/// The world with both offsets 0.
fn unshifted() -> World {
    catcher_world(0, 0)
}

/// Walker-v0's ground, then `package`, `peg1` and `peg2` placed with offsets (ox, oy), in
/// EvoGym's order.
fn catcher_world(ox: i32, oy: i32) -> World {
    let mut world = worlds::walker_v0();
    let at = |x: i32, y: i32| ((x + ox) as usize, (y + oy) as usize);
    let package = MaterialGrid::from_rows("222/222").expect("a 3 × 2 soft package");
    let peg = MaterialGrid::from_rows("55555").expect("a 5 × 1 fixed peg");
    for object in [
        WorldObject::new("package", at(21, 41), package),
        WorldObject::new("peg1", at(17, 39), peg.clone()),
        WorldObject::new("peg2", at(19, 25), peg),
    ] {
        world
            .add(object)
            .expect("the package and the pegs lie apart, above the ground");
    }
    world
}

impl TaskDefinition for Catcher {
    fn basics(&self) -> &Basics {
        &BASICS
    }

    fn object(&self) -> Option<&'static str> {
        Some("package")
    }

    /// The package's centre minus the robot's, the robot's and the package's velocities, the
    /// package's orientation, then the robot's relative positions (`manipulate.py:549-557`).
    fn observation(&self) -> &'static [Piece] {
        OBJECT_THEN_ROBOT
    }

    /// One world per pair of offsets.
    fn world_count(&self) -> usize {
        X_OFFSETS.count() * Y_COUNT
    }

    /// The world of offsets `((index / 6) − 6, index % 6)`.
    fn world_at(&self, index: usize) -> World {
        let ox = *X_OFFSETS.start() + (index / Y_COUNT) as i32;
        let oy = *Y_OFFSETS.start() + (index % Y_COUNT) as i32;
        catcher_world(ox, oy)
    }

    /// The offsets drawn from `seed`, x first, as EvoGym draws them (`manipulate.py:481-482`).
    fn world_of(&self, seed: u64) -> usize {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let ox = rng.random_range(X_OFFSETS);
        let oy = rng.random_range(Y_OFFSETS);
        (ox - X_OFFSETS.start()) as usize * Y_COUNT + (oy - Y_OFFSETS.start()) as usize
    }

    /// The robot's approach to the package along x, 10 × the package's drop while it is below 5
    /// cells, −3 if unstable; nothing ends it early (`manipulate.py:514-531`, `:559-565`).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, _memory: &mut [f64]) -> Reward {
        let mut value = (before.robot.0 - before.beam.0).abs() - (after.robot.0 - after.beam.0).abs();
        if after.beam.1 < THRESHOLD {
            value += 10.0 * (after.beam.1 - before.beam.1);
        }
        if unstable {
            value -= UNSTABLE_PENALTY;
        }
        Reward { value, ends: false }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_world_is_a_pair_of_offsets_and_seeds_spread_over_them() {
        let task = Catcher;
        assert_eq!(task.world_count(), 66);
        let package = |w: &World| w.object("package").map(|o| o.origin);
        assert_eq!(package(&task.world_at(0)), Some((15, 41)), "ox −6, oy 0");
        assert_eq!(package(&task.world_at(65)), Some((25, 46)), "ox 4, oy 5");
        assert_eq!(task.world_at(6 * 6).object("peg2").map(|o| o.origin), Some((19, 25)));
        assert_eq!(package(&unshifted()), Some((21, 41)));
        let drawn: std::collections::BTreeSet<usize> = (0..2000).map(|s| task.world_of(s)).collect();
        assert_eq!(drawn.len(), 66, "2000 seeds reach every world");
        assert_eq!(task.world_of(7), task.world_of(7));
    }
}
