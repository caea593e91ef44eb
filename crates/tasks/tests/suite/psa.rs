//! Pressure-based soft agents: the inflation protocol, episodes on every task, robustness.

use vsrlab_body::psa::{PsaParams, PsaSize};
use vsrlab_tasks::kinds::psa::inflation::{inflate, psa_physics};

#[test]
fn inflation_reaches_a_circle_for_every_size() {
    for size in PsaSize::ALL {
        let points = inflate(&PsaParams::of_size(size), &psa_physics(), 1200).unwrap();
        let last = points.last().unwrap();
        let early = points[10].phi;
        eprintln!("{size:?}: phi after 10 steps {early:.4}, at p_max {:.4}", last.phi);
        for (i, p) in points.iter().enumerate().step_by(60) {
            eprintln!("  {i} {:.3} {:.4}", p.pressure_ratio, p.phi);
        }
        assert_eq!(last.pressure_ratio, 1.0);
        let tail = &points[points.len() - 300..];
        let mean = tail.iter().map(|p| p.phi).sum::<f64>() / 300.0;
        let max = tail.iter().map(|p| p.phi).fold(0.0, f64::max);
        let min = tail.iter().map(|p| p.phi).fold(9.0, f64::min);
        eprintln!("{size:?}: last 300 steps mean {mean:.4} min {min:.4} max {max:.4}");
    }
}

#[test]
fn zero_gravity_balloon_settles_at_the_analytic_equilibrium() {
    // regular n-gon: the pressure's radial push p·s·cos(π/n) on a mass balances the two springs'
    // pull 2T·sin(π/n), with T = k (s − l) and k = μω², μ the two masses' reduced mass
    use std::f64::consts::PI;
    use vsrlab_physics::Vec2;
    for size in PsaSize::ALL {
        let params = PsaParams::of_size(size);
        let physics = vsrlab_physics::WorldSettings {
            gravity: Vec2::ZERO,
            ..psa_physics()
        };
        let points = inflate(&params, &physics, 1200).unwrap();
        let n = params.masses as f64;
        let mass = params.density * params.mass_side * params.mass_side;
        let k = 0.5 * mass * (2.0 * PI * params.spring_frequency).powi(2);
        let p = params.max_pressure();
        let l = params.rest_length();
        let s = l / (1.0 - p * (PI / n).cos() / (2.0 * (PI / n).sin() * k));
        let expected = n * s * s / (4.0 * (PI / n).tan()) / (PI * params.radius * params.radius);
        let got = points.last().unwrap().phi;
        eprintln!("{size:?}: φ {got:.4}, analytic {expected:.4}");
        assert!((got - expected).abs() < 0.005, "{size:?}: φ {got} vs {expected}");
    }
}

mod episodes {
    use std::time::Instant;
    use vsrlab_body::psa::{PsaBody, PsaSize};
    use vsrlab_brain::BrainSpec;
    use vsrlab_tasks::{episode, PsaRobot, TaskSpec, TraceLevel};

    fn robot(size: PsaSize, brain: &str, seed: u64) -> PsaRobot {
        let mut r = PsaRobot {
            body: PsaBody::of_size(size),
            brain: BrainSpec::parse(brain).unwrap(),
        };
        r.brain = r.brain.with_random_parameters(seed, &r.brain_shape()).unwrap();
        r
    }

    #[test]
    fn a_random_heads_brain_runs_every_task() {
        for task in ["locomotion:flat", "locomotion:psa-hilly-3-10", "escape", "carrier"] {
            let task = TaskSpec::parse(task).unwrap();
            let r = robot(PsaSize::Medium, "heads", 1);
            let start = Instant::now();
            let out = episode::run(&r, task.task(), 0, TraceLevel::None).unwrap();
            eprintln!(
                "{}: {:?} in {} steps, {:.3} s",
                task.kind(),
                out.metrics,
                out.steps,
                start.elapsed().as_secs_f64()
            );
            assert!(out.fitness.iter().all(|f| f.is_finite()));
        }
    }
}

mod robustness {
    use proptest::prelude::*;
    use vsrlab_body::psa::{PsaBody, PsaSize};
    use vsrlab_brain::{BrainSpec, HeadsSpec, RandomSpec};
    use vsrlab_physics::Vec2;
    use vsrlab_tasks::terrain::height_at;
    use vsrlab_tasks::{episode, PsaRobot, TaskSpec, TraceLevel};

    const TASKS: [&str; 4] = ["locomotion:flat", "locomotion:psa-hilly-3-10", "escape", "carrier"];

    /// The task with its cage or ball scaled to the agent, as the original (cage side 3r; ball
    /// of radius r/4 at (r, 2.5r + 1)).
    pub fn sized(task: &str, size: PsaSize) -> TaskSpec {
        let r = size.radius();
        let t = TaskSpec::parse(task).unwrap();
        match t.kind() {
            "escape" => t.with_settings(&[("side", serde_json::json!(3.0 * r))]).unwrap(),
            "carrier" => t
                .with_settings(&[(
                    "ball",
                    serde_json::json!({"radius": r / 4.0, "x": r, "y": 2.5 * r + 1.0, "density": 500.0, "friction": 10.0}),
                )])
                .unwrap(),
            _ => t,
        }
    }

    fn inside(poly: &[Vec2], p: Vec2) -> bool {
        (0..poly.len()).all(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            (b - a).cross(p - a) > 0.0
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 120, ..ProptestConfig::default() })]
        /// Random controllers (fresh random outputs every step, or one-layer heads with weights up
        /// to ±10⁴ that slam the pressure between its limits) for 30 s on every task and size:
        /// the state stays finite, and no mass goes through the ground or a wall.
        #[test]
        fn random_controllers_never_explode_or_tunnel(
            size in 0usize..3, task in 0usize..4, heads in any::<bool>(),
            scale in 0.1f64..1e4, seed in 0u64..1000,
        ) {
            let size = PsaSize::ALL[size];
            let mut robot = PsaRobot { body: PsaBody::of_size(size), brain: BrainSpec::Random(RandomSpec { period: 0.0, seed }) };
            if heads {
                let spec = BrainSpec::Heads(HeadsSpec::default())
                    .with_random_parameters(seed, &robot.brain_shape())
                    .unwrap();
                let scaled: Vec<f64> = spec.parameters().iter().map(|w| w * scale).collect();
                robot.brain = spec.with_parameters(&scaled).unwrap();
            }
            let task = sized(TASKS[task], size);
            let out = episode::run(&robot, task.task(), seed, TraceLevel::Full);
            let out = out.map_err(|e| TestCaseError::fail(format!("{size:?} {}: {e}", task.kind())))?;
            prop_assert!(out.fitness.iter().all(|f| f.is_finite()));
            let trace = out.trace.unwrap();
            let n = size.masses();
            for k in 0..trace.len() {
                let polys = trace.polygons_at(k);
                let membrane = polys.iter().next().unwrap();
                for &m in &membrane[..n] {
                    prop_assert!(m.is_finite());
                    let ground = height_at(&trace.terrain, m.x).unwrap_or(f64::NEG_INFINITY);
                    prop_assert!(m.y > ground - 0.25, "step {k}: mass at {m:?} under the ground {ground}");
                    for wall in &vsrlab_tasks::channels::obstacles(&trace) {
                        prop_assert!(!inside(wall, m), "step {k}: mass at {m:?} inside a wall");
                    }
                }
            }
        }
    }
}

#[test]
fn absurd_gas_stays_finite_or_is_refused_naming_the_field() {
    use vsrlab_body::psa::PsaBody;
    use vsrlab_tasks::{episode, PsaRobot, TaskSpec, TraceLevel};
    let robot = |gas_mass: f64| {
        let mut body = PsaBody::of_size(PsaSize::Small);
        body.params.gas_mass = gas_mass;
        PsaRobot {
            body,
            brain: vsrlab_brain::BrainSpec::parse("constant:0").unwrap(),
        }
    };
    let task = TaskSpec::parse("carrier").unwrap();
    // the most gas allowed (a million times the thesis's): huge forces, and the engine caps each
    // body's travel per step, so the state stays finite
    let most = PsaBody::of_size(PsaSize::Small).params.gas_mass.max(1.0) * vsrlab_body::psa::SCALE_RANGE;
    let out = episode::run(&robot(most), task.task(), 0, TraceLevel::None).unwrap();
    assert!(out.fitness.iter().all(|f| f.is_finite()), "{out:?}");
    // more, up to a pressure that overflows, is refused before the episode, naming the field
    for gas in [most * 1.01, 1e300, f64::MAX] {
        let err = episode::run(&robot(gas), task.task(), 0, TraceLevel::None).unwrap_err();
        assert!(err.to_string().contains("robot.body.gas_mass"), "{gas}: {err}");
    }
}

#[test]
fn a_sensor_window_too_long_for_the_time_step_is_refused_naming_the_field() {
    use vsrlab_body::psa::PsaBody;
    use vsrlab_tasks::{episode, PsaRobot, TaskSpec, TraceLevel};
    let robot = |window: f64| {
        let mut body = PsaBody::of_size(PsaSize::Small);
        body.params.sensor_window = window;
        PsaRobot {
            body,
            brain: vsrlab_brain::BrainSpec::parse("constant:0").unwrap(),
        }
    };
    let task = TaskSpec::parse("locomotion:flat").unwrap();
    let task = task.with_settings(&[("duration", serde_json::json!(0.1))]).unwrap();
    // 1e300 s of 1/60 s steps used to panic with "capacity overflow"; 1e7 s to abort allocating
    for window in [1e300, 1e7] {
        let err = episode::run(&robot(window), task.task(), 0, TraceLevel::None).unwrap_err();
        assert!(err.to_string().contains("robot.body.sensor_window"), "{window}: {err}");
    }
    assert!(episode::run(&robot(1.0), task.task(), 0, TraceLevel::None).is_ok());
}
