//! Every corner square of a voxel robot, step by step, as CSV: for comparing vsrlab's physics
//! with another simulator's run of the same robot and gait, step by step (docs/fidelity.md).
//!
//! Usage: `cargo run --release -p vsrlab-cli --example parts_trace -- BODY PRESET SOLVER STEPS
//! SHIFT BRAIN OUT.csv [--no-ccd]`, e.g. `biped-4x3 2022 sequential-impulses 300 0 phase b.csv`.
//! BRAIN is a `vsrlab simulate --brain` short form (`phase`, `constant:1`, …). Flat ground, the
//! robot's left edge at x = 11 + SHIFT. Rows: step, grid x, grid y (0 = bottom row), corner
//! (0 NW, 1 NE, 2 SE, 3 SW), centre x, centre y, angle, vx, vy, angular velocity; step 0 is the
//! placement, before the first step. `--velocity-iterations N` overrides the solver's sweeps;
//! `--contacts` prints the number of contacts after each step to standard error.
use std::io::Write;
use vsrlab_physics::{PartHandle, Solver};
use vsrlab_tasks::episode::Episode;
use vsrlab_tasks::{ensemble, Locomotion, RobotSpec, TaskSpec, TraceLevel};

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() < 7 {
        return Err(
            "usage: parts_trace BODY PRESET SOLVER STEPS SHIFT BRAIN OUT.csv [--no-ccd] [--velocity-iterations N] [--contacts]"
                .into(),
        );
    }
    let robot = RobotSpec::from_short_forms(&args[0], &args[1], "empty", &args[5]).map_err(|e| e.to_string())?;
    let mut task = Locomotion::default();
    task.physics.solver = args[2].parse::<Solver>().map_err(|e| format!("SOLVER: {e}"))?;
    task.physics.continuous_collision = !args.iter().any(|a| a == "--no-ccd");
    if let Some(n) = args.iter().position(|a| a == "--velocity-iterations") {
        let value = args.get(n + 1).and_then(|v| v.parse().ok());
        task.physics.velocity_iterations = value.ok_or("--velocity-iterations: expected a count")?;
    }
    let steps: usize = args[3]
        .parse()
        .map_err(|_| format!("STEPS: not a count: '{}'", args[3]))?;
    let shift: f64 = args[4]
        .parse()
        .map_err(|_| format!("SHIFT: not a number: '{}'", args[4]))?;
    task.duration = steps as f64 / 60.0 + 0.5;
    let spec = ensemble::shifted_task(&TaskSpec::Locomotion(task), shift).map_err(|e| e.to_string())?;
    let task = spec.task().rigid().ok_or("not a rigid-body task")?;
    let mut episode = Episode::new(&robot, task, 0, TraceLevel::None).map_err(|e| e.to_string())?;
    let cells: Vec<(usize, usize)> = robot.body.voxels().collect();
    let mut out = std::io::BufWriter::new(std::fs::File::create(&args[6]).map_err(|e| format!("{}: {e}", args[6]))?);
    let mut write = |step: usize, episode: &Episode| -> std::io::Result<()> {
        let world = episode.world();
        for (v, (gx, gy)) in cells.iter().enumerate() {
            for corner in 0..4 {
                let h = PartHandle((4 * v + corner) as u32);
                let (p, vel) = (world.part_position(h), world.part_velocity(h));
                writeln!(
                    out,
                    "{step},{gx},{gy},{corner},{},{},{},{},{},{}",
                    p.x,
                    p.y,
                    world.part_angle(h),
                    vel.x,
                    vel.y,
                    world.part_angular_velocity(h)
                )?;
            }
        }
        Ok(())
    };
    let print_contacts = args.iter().any(|a| a == "--contacts");
    write(0, &episode).map_err(|e| e.to_string())?;
    for step in 1..=steps {
        episode.step(None).map_err(|e| e.to_string())?;
        write(step, &episode).map_err(|e| e.to_string())?;
        if print_contacts {
            eprintln!("step {step}: {} contacts", episode.world().contact_count());
        }
    }
    Ok(())
}
