//! Population lanes of the 3D engine (issue 52, item 2): nanoseconds per update and episode of a
//! link, of a voxel and of a whole world with and without voxel–voxel collisions, one scalar copy per episode against
//! laned copies stepping 4 or 8 episodes at once (bit-identical per lane: `link_lanes::tests`,
//! `voxel_lanes::tests`, `world_lanes::tests`).
//!
//! `cargo run --release -p vsrlab-physics3d --features bench --example lanes3d [updates]`

use vsrlab_physics3d::{link_lanes, voxel_lanes, world_lanes};

fn main() {
    let updates: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(200_000);
    for round in 1..=3 {
        let (scalar, four, eight) = link_lanes::benchmark(updates);
        println!(
            "round {round}: link: scalar {scalar:.1} ns, 4 lanes {four:.1} ns ({:.2}x), 8 lanes {eight:.1} ns ({:.2}x) per update and episode",
            scalar / four,
            scalar / eight
        );
        let (world, one, four, eight) = voxel_lanes::benchmark(updates);
        println!(
            "round {round}: voxel: a one-voxel world {world:.1} ns per step; 1 lane {one:.1} ns, 4 lanes {four:.1} ns ({:.2}x), 8 lanes {eight:.1} ns ({:.2}x) per update and episode",
            one / four,
            one / eight
        );
        for collisions in [false, true] {
            let (scalar, four, eight) = world_lanes::benchmark(updates / 20, collisions);
            let on = if collisions { "on" } else { "off" };
            println!(
                "round {round}: world (11-voxel block, collisions {on}): scalar {scalar:.1} ns, 4 lanes {four:.1} ns ({:.2}x), 8 lanes {eight:.1} ns ({:.2}x) per voxel·step and episode",
                scalar / four,
                scalar / eight
            );
        }
    }
}
