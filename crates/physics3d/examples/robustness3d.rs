//! Robustness campaign of the 3D engine (issue 34): random connected bodies up to 6×6×6 of the
//! affordance study's material, collisions on, under random thermal actuation (every voxel's
//! temperature redrawn in ±14.4714 every step, or every 0.01, 0.05 or 0.2 s, by body) for a
//! number of simulated seconds. Every step must succeed and every state stay finite; a divergence
//! is reported as the engine's error, never a NaN passed on.
//!
//!   cargo run --release -p vsrlab-physics3d --example robustness3d -- [bodies=24] [seconds=5]

use std::time::Instant;
use vsrlab_physics3d::{Material, VoxelId, World, WorldSettings};

/// A small deterministic generator (64-bit LCG, top 53 bits).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The piece connected to the first filled cell of a random fill of a side³ box.
fn random_body(rng: &mut Lcg, side: i32, fill: f64) -> Vec<[i32; 3]> {
    let mut cells = Vec::new();
    for x in 0..side {
        for y in 0..side {
            for z in 0..side {
                if rng.next() < fill {
                    cells.push([x, y, z]);
                }
            }
        }
    }
    if cells.is_empty() {
        cells.push([0, 0, 0]);
    }
    let mut keep = vec![cells[0]];
    let mut i = 0;
    while i < keep.len() {
        let c = keep[i];
        for d in [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]] {
            let n = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
            if cells.contains(&n) && !keep.contains(&n) {
                keep.push(n);
            }
        }
        i += 1;
    }
    keep
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let bodies: usize = args.next().map_or(Ok(24), |s| s.parse())?;
    let seconds: f64 = args.next().map_or(Ok(5.0), |s| s.parse())?;
    let mut rng = Lcg(0x3D5EED);
    let (mut failures, mut voxel_steps) = (0, 0u64);
    let clock = Instant::now();
    for body in 0..bodies {
        let side = 2 + (body % 5) as i32;
        let fill = 0.4 + 0.6 * rng.next();
        let cells = random_body(&mut rng, side, fill);
        let mut w = World::new(WorldSettings::default())?;
        let m = w.add_material(Material::affordance())?;
        let ids: Vec<VoxelId> = cells.iter().map(|&c| w.add_voxel(m, c)).collect::<Result<_, _>>()?;
        let dt = 0.95 * w.recommended_time_step();
        let period = [dt, 0.01, 0.05, 0.2][body % 4];
        let per_draw = ((period / dt).round() as usize).max(1);
        let steps = (seconds / dt) as usize;
        let mut outcome = Ok(());
        for step in 0..steps {
            if step % per_draw == 0 {
                for &v in &ids {
                    w.set_temperature(v, 14.4714 * (2.0 * rng.next() - 1.0));
                }
            }
            if let Err(e) = w.step(dt) {
                outcome = Err(format!("step {step}: {e}"));
                break;
            }
        }
        let finite = ids
            .iter()
            .all(|&v| w.position(v).is_finite() && w.orientation(v).is_finite() && w.velocity(v).is_finite());
        let lowest = ids.iter().map(|&v| w.position(v).z).fold(f64::INFINITY, f64::min);
        voxel_steps += (ids.len() * steps) as u64;
        let verdict = match (&outcome, finite) {
            (Ok(()), true) => "finite".to_string(),
            (Err(e), _) => format!("ERROR {e}"),
            (Ok(()), false) => "NON-FINITE STATE WITHOUT AN ERROR".to_string(),
        };
        if verdict != "finite" {
            failures += 1;
        }
        println!(
            "body {body:2}: {side}×{side}×{side} box, {:3} voxels, actuation redrawn every {period:.5} s: {verdict}, lowest centre z {lowest:+.4} m",
            ids.len()
        );
    }
    println!(
        "{bodies} bodies × {seconds} s: {failures} failed; {:.2e} voxel·steps in {:.1} s",
        voxel_steps as f64,
        clock.elapsed().as_secs_f64()
    );
    Ok(())
}
