//! A 3D soft walker on the affordance study's material: a 4 × 3 × 2 slab on four 1-voxel legs,
//! every voxel's temperature a sine (amplitude 14.4714, 2 Hz) whose phase advances along x. Prints
//! how far the centre of mass moved and the speed in voxel·steps per CPU-second (one thread).
//! With `lanes`, a population of 8 episodes (each its own frequency, 2 + 0.05·i Hz) runs in
//! laned worlds (`LanedWorlds`, each lane the bits of a scalar world: one world of 8 lanes on a
//! CPU with AVX-512, two of 4 elsewhere), and the speed counts the voxel·steps of all 8.
//!
//! `cargo run --release -p vsrlab-physics3d --example walker3d [seconds] [quadruped|box6] [off|on] [lanes]`

use std::time::Instant;
use vsrlab_physics3d::laned_worlds::{lanes, LanedWorlds, MAX_LANES};
use vsrlab_physics3d::{Material, VoxelId, World, WorldSettings};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arg = |i: usize| std::env::args().nth(i);
    let seconds: f64 = arg(1).map_or(Ok(2.0), |s| s.parse())?;
    let body = arg(2).unwrap_or_else(|| "quadruped".into());
    // collisions off by default, as Voxelyze's default: the same model on both sides
    let collisions = arg(3).as_deref() == Some("on");
    let mut w = World::new(WorldSettings {
        collisions,
        ..WorldSettings::default()
    })?;
    let m = w.add_material(Material::affordance())?;
    let mut cells = Vec::new();
    if body == "box6" {
        for x in 0..6 {
            for y in 0..6 {
                for z in 0..6 {
                    cells.push([x, y, z]);
                }
            }
        }
    } else {
        for x in 0..4 {
            for y in 0..3 {
                for z in 1..3 {
                    cells.push([x, y, z]);
                }
            }
        }
        for (x, y) in [(0, 0), (0, 2), (3, 0), (3, 2)] {
            cells.push([x, y, 0]);
        }
    }
    let ids: Vec<(VoxelId, i32)> = cells
        .iter()
        .map(|&c| Ok((w.add_voxel(m, c)?, c[0])))
        .collect::<Result<_, vsrlab_physics3d::Physics3dError>>()?;
    if arg(4).as_deref() == Some("lanes") {
        return population(&w, &ids, seconds, collisions);
    }
    let centre = |w: &World| ids.iter().map(|&(v, _)| w.position(v)).sum::<glam::DVec3>() / ids.len() as f64;
    let start = centre(&w);
    let dt = 0.95 * w.recommended_time_step();
    let steps = (seconds / dt) as usize;
    let clock = Instant::now();
    for k in 0..steps {
        let t = k as f64 * dt;
        for &(v, x) in &ids {
            let phase = std::f64::consts::PI * f64::from(x) / 2.0;
            w.set_temperature(v, 14.4714 * (2.0 * std::f64::consts::PI * 2.0 * t - phase).sin());
        }
        w.step(dt)?;
    }
    let elapsed = clock.elapsed().as_secs_f64();
    let moved = centre(&w) - start;
    println!(
        "vsrlab (collisions {}): {} voxels, {} links, dt {:.4e} s, {steps} steps in {elapsed:.2} s: centre moved ({:+.4}, {:+.4}, {:+.4}) m ({:.2} body lengths), {:.0} voxel·steps/s, {:.0} voxel·s/s",
        if collisions { "on" } else { "off" },
        w.voxel_count(),
        w.link_count(),
        dt,
        moved.x,
        moved.y,
        moved.z,
        moved.x.abs() / 0.04,
        (w.voxel_count() * steps) as f64 / elapsed,
        w.voxel_count() as f64 * seconds / elapsed,
    );
    Ok(())
}

/// 8 episodes of the walker in two laned worlds of 4, episode `i` at 2 + 0.05·i Hz.
fn population(
    w: &World,
    ids: &[(VoxelId, i32)],
    seconds: f64,
    collisions: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let dt = 0.95 * w.recommended_time_step();
    let steps = (seconds / dt) as usize;
    let n = lanes();
    let mut worlds = (0..MAX_LANES / n)
        .map(|_| LanedWorlds::of(w))
        .collect::<Result<Vec<_>, _>>()?;
    let clock = Instant::now();
    for k in 0..steps {
        let t = k as f64 * dt;
        for (i, laned) in worlds.iter_mut().enumerate() {
            for &(v, x) in ids {
                let phase = std::f64::consts::PI * f64::from(x) / 2.0;
                for l in 0..n {
                    let hz = 2.0 + 0.05 * (i * n + l) as f64;
                    let temperature = 14.4714 * (2.0 * std::f64::consts::PI * hz * t - phase).sin();
                    laned.set_temperature(v, l, temperature);
                }
            }
            laned.step(dt)?;
        }
    }
    let elapsed = clock.elapsed().as_secs_f64();
    let diverged: usize = worlds
        .iter()
        .map(|w| (0..n).filter(|&l| w.diverged(l).is_some()).count())
        .sum();
    let voxel_steps = (MAX_LANES * ids.len() * steps) as f64;
    println!(
        "vsrlab lanes (collisions {}): {MAX_LANES} episodes of {} voxels in {} x {n} lanes, {steps} steps in {elapsed:.2} s ({diverged} lanes diverged): {:.0} voxel·steps/s",
        if collisions { "on" } else { "off" },
        ids.len(),
        MAX_LANES / n,
        voxel_steps / elapsed,
    );
    Ok(())
}
