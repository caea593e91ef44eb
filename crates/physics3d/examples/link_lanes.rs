//! Population lanes of the 3D engine's link (issue 52, item 2, first kernel): nanoseconds per
//! link update and episode, one scalar link per episode against one laned link stepping 4 or 8
//! episodes (bit-identical per lane: `link_lanes::tests`).
//!
//! `cargo run --release -p vsrlab-physics3d --example link_lanes [updates]`

fn main() {
    let updates: usize = std::env::args().nth(1).and_then(|s| s.parse().ok()).unwrap_or(200_000);
    for round in 1..=3 {
        let (scalar, four, eight) = vsrlab_physics3d::link_lanes::benchmark(updates);
        println!(
            "round {round}: scalar {scalar:.1} ns, 4 lanes {four:.1} ns ({:.2}x), 8 lanes {eight:.1} ns ({:.2}x) per link update and episode",
            scalar / four,
            scalar / eight
        );
    }
}
