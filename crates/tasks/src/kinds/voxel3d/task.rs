//! [`Locomotion3d`]: a 3D voxel robot walks on the floor, among fixed obstacle voxels, for a
//! while; scored by how far its centre of mass moved (`[task] kind = "locomotion3d"`, or
//! `locomotion3d` on the command line). Its episodes run on the 3D engine
//! ([`vsrlab_physics3d`]): every step the engine steps, then every voxel senses, the brain
//! computes, and each voxel's temperature is set to `amplitude × actuation` for the next step
//! (voxcraft-sim evaluates its controller every physics step too).

use super::physics::{Built, Physics3d, MAX_STEPS};
use super::population::{run_population, LaneEpisode};
use super::recorder::Recorder;
use super::robot::Voxel3dRobot;
use super::setup::{lanes, prepare, prepare_batch, sense, Prepared};
use super::worlds::Worlds;
use crate::agent::{Agent, Robot};
use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::outcome::{Outcome, TraceLevel};
use crate::task::{check_objectives, episode_steps, fitness_values, task_field, Metrics, Objective, Task};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use vsrlab_brain::Controller;
use vsrlab_field::FieldError;
use vsrlab_physics3d::laned_worlds::LanedWorlds;
use vsrlab_physics3d::VoxelId;

/// What a 3D locomotion episode reports: the centre of mass's horizontal displacement (`distance`,
/// and its `dx`, `dy`), its final height over the start (`dz`), mean horizontal speed, steps.
const METRICS: &[&str] = &["distance", "dx", "dy", "dz", "velocity", "steps"];

/// Walk as far as possible in 3D.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Locomotion3d {
    /// Episode length (simulated seconds).
    pub duration: f64,
    /// Objectives among `distance`, `dx`, `dy`, `dz`, `velocity`, `steps`.
    pub fitness: Fitness,
    /// The world: material, lattice, gravity, collisions, time step, actuation amplitude.
    pub physics: Physics3d,
    /// Fixed voxels (walls, obstacles) at lattice cells [x, y, z]; the body occupies its grid's
    /// cells from [0, 0, 0], z up, the floor under z = 0.
    pub obstacles: Vec<[i32; 3]>,
    /// Frames per second of recorded traces (videos, replays).
    pub frame_rate: f64,
}

impl Default for Locomotion3d {
    fn default() -> Self {
        Locomotion3d {
            duration: 5.0,
            fitness: Fitness::maximize("distance"),
            physics: Physics3d::default(),
            obstacles: Vec::new(),
            frame_rate: 50.0,
        }
    }
}

impl Task for Locomotion3d {
    fn kind(&self) -> &'static str {
        "locomotion3d"
    }

    fn validate(&self) -> Result<(), EpisodeError> {
        let d = self.duration;
        if !(d.is_finite() && d > 0.0 && d <= 1e4) {
            return Err(task_field(FieldError::sentence(
                "duration",
                format!("must be in (0, 10000] seconds, got {d}"),
            )));
        }
        self.physics.validate().map_err(|e| task_field(e.at("physics")))?;
        let steps = d / self.physics.dt();
        if steps > MAX_STEPS {
            return Err(task_field(FieldError::sentence(
                "duration",
                format!(
                    "{d} s is {steps:.3e} steps of {:.3e} s (this material's time step): at most {MAX_STEPS:.0e} steps per episode",
                    self.physics.dt()
                ),
            )));
        }
        let r = self.frame_rate;
        if !(r.is_finite() && r > 0.0 && r <= 10_000.0) {
            return Err(task_field(FieldError::sentence(
                "frame_rate",
                format!("must be in (0, 10000] frames per second, got {r}"),
            )));
        }
        if self.obstacles.len() > 100_000 {
            return Err(task_field(FieldError::sentence(
                "obstacles",
                format!("at most 100000 voxels, got {}", self.obstacles.len()),
            )));
        }
        check_objectives(&self.fitness.0, METRICS)
    }

    fn duration(&self) -> f64 {
        self.duration
    }

    fn step_seconds(&self) -> f64 {
        self.physics.dt()
    }

    fn metric_names(&self) -> &'static [&'static str] {
        METRICS
    }

    fn objectives(&self) -> &[Objective] {
        &self.fitness.0
    }

    fn run_episode(
        &self,
        robot: &dyn Robot,
        _seed: u64,
        level: TraceLevel,
        _observe: &mut dyn FnMut(f64, &dyn Agent),
    ) -> Result<Outcome, EpisodeError> {
        self.validate()?;
        let Prepared {
            grid,
            sensors,
            mut brain,
            ..
        } = prepare(robot, "locomotion3d")?;
        let built = self.physics.build(&grid, &self.obstacles).map_err(task_field)?;
        let mut recorder = Recorder::new(level, &built, self.frame_rate);
        let Built {
            mut world, body, dt, ..
        } = built;
        recorder.record(&world, &body, &vec![0.0; body.len()], 0.0);
        let steps = crate::task::episode_steps(self.duration, dt);
        let mut lane = Lane::new(brain.as_mut(), &body, &sensors);
        self.episode(
            &mut world,
            &body,
            &sensors,
            &mut lane,
            dt,
            &mut |world, actuation, t| recorder.record(world, &body, actuation, t),
        );
        lane.result
            .map(|moved| self.outcome(moved, steps, dt, body.len(), recorder.finish()))
    }

    fn episode_group(&self, robot: &dyn Robot) -> Option<String> {
        same_body_group(robot)
    }

    fn episode_batch(&self) -> usize {
        lanes()
    }

    fn run_episodes(&self, robots: &[&dyn Robot], seeds: &[u64]) -> Vec<Result<Outcome, EpisodeError>> {
        let one_by_one = || crate::task::one_by_one(self, robots, seeds);
        let batch = (robots.len() > 1 && self.validate().is_ok())
            .then(|| prepare_batch(robots, "locomotion3d"))
            .flatten();
        let Some(mut prepared) = batch else {
            return one_by_one();
        };
        let Ok(built) = self.physics.build(&prepared[0].grid, &self.obstacles) else {
            return one_by_one();
        };
        let Ok(mut world) = LanedWorlds::of(&built.world) else {
            return one_by_one();
        };
        let (sensors, steps) = (prepared[0].sensors.clone(), episode_steps(self.duration, built.dt));
        let queue: Vec<Walk> = prepared
            .iter_mut()
            .map(|p| Walk::new(self, &built.body, &sensors, built.dt, p.brain.as_mut()))
            .collect();
        let n = built.body.len();
        run_population(&mut world, queue, steps, built.dt)
            .into_iter()
            .map(|result| result.map(|moved| self.outcome(moved, steps, built.dt, n, None)))
            .collect()
    }
}

/// The batch group of a 3D robot: robots of the same body grid can share a laned world.
pub(crate) fn same_body_group(robot: &dyn Robot) -> Option<String> {
    let robot = robot.description()?.as_any().downcast_ref::<Voxel3dRobot>()?;
    robot.grid().ok().map(|grid| format!("voxel3d {grid:?}"))
}

/// One episode of a laned loop: its brain, buffers, and how it ended (the body's displacement,
/// or the error that stopped it).
struct Lane<'a> {
    brain: &'a mut dyn Controller,
    readings: Vec<f64>,
    actuation: Vec<f64>,
    start: DVec3,
    result: Result<DVec3, EpisodeError>,
    running: bool,
}

impl<'a> Lane<'a> {
    fn new(brain: &'a mut dyn Controller, body: &[VoxelId], sensors: &[super::Sensor3]) -> Self {
        brain.reset();
        Lane {
            brain,
            readings: vec![0.0; body.len() * sensors.len()],
            actuation: vec![0.0; body.len()],
            start: DVec3::ZERO,
            result: Ok(DVec3::ZERO),
            running: true,
        }
    }

    /// Ends the lane with `error` at step `k`, as the scalar loop words it.
    fn fail(&mut self, k: u64, dt: f64, error: &vsrlab_physics3d::Physics3dError) {
        self.result = Err(EpisodeError::Invalid(format!(
            "episode failed at t = {:.4} s: {error}",
            k as f64 * dt
        )));
        self.running = false;
    }
}

/// A [`Lane`]'s episode in a laned population ([`run_population`]).
struct Walk<'a, 'b> {
    task: &'b Locomotion3d,
    body: &'b [VoxelId],
    sensors: &'b [super::Sensor3],
    dt: f64,
    lane: Lane<'a>,
}

impl<'a, 'b> Walk<'a, 'b> {
    /// `brain`'s episode of `task` with this body and its sensors.
    fn new(
        task: &'b Locomotion3d,
        body: &'b [VoxelId],
        sensors: &'b [super::Sensor3],
        dt: f64,
        brain: &'a mut dyn Controller,
    ) -> Self {
        Walk {
            task,
            body,
            sensors,
            dt,
            lane: Lane::new(brain, body, sensors),
        }
    }
}

impl LaneEpisode for Walk<'_, '_> {
    type Result = Result<DVec3, EpisodeError>;

    fn start(&mut self, world: &LanedWorlds, lane: usize) {
        self.lane.start = centre(world, self.body, lane);
    }

    fn advance(&mut self, world: &mut LanedWorlds, lane: usize, k: u64) -> bool {
        let (body, sensors) = (self.body, self.sensors);
        self.task
            .advance(world, lane, &mut self.lane, body, sensors, k, self.dt)
    }

    fn finish(mut self, world: &LanedWorlds, lane: usize) -> Self::Result {
        if self.lane.running {
            self.lane.result = Ok(centre(world, self.body, lane) - self.lane.start);
        }
        self.lane.result
    }

    fn refused(mut self, k: u64, error: &vsrlab_physics3d::Physics3dError) -> Self::Result {
        self.lane.fail(k, self.dt, error);
        self.lane.result
    }
}

impl Locomotion3d {
    /// One episode in `world`: every step the world steps, then the robot senses, controls and
    /// actuates; `record(world, actuation, t)` after every step.
    fn episode(
        &self,
        world: &mut vsrlab_physics3d::World,
        body: &[VoxelId],
        sensors: &[super::Sensor3],
        lane: &mut Lane,
        dt: f64,
        record: &mut dyn FnMut(&vsrlab_physics3d::World, &[f64], f64),
    ) {
        lane.start = centre(world, body, 0);
        let steps = episode_steps(self.duration, dt);
        for k in 1..=steps {
            if let Err(e) = world.step(dt) {
                return lane.fail(k, dt, &e);
            }
            self.advance(world, 0, lane, body, sensors, k, dt);
            record(world, &lane.actuation, k as f64 * dt);
        }
        lane.result = Ok(centre(world, body, 0) - lane.start);
    }

    /// Lane `l`'s `k`-th step of its episode, after the world stepped: the lane fails if it
    /// diverged, else the robot senses, controls, and sets its voxels' temperatures. Whether the
    /// lane still runs.
    #[allow(clippy::too_many_arguments)]
    fn advance<W: Worlds>(
        &self,
        world: &mut W,
        l: usize,
        lane: &mut Lane,
        body: &[VoxelId],
        sensors: &[super::Sensor3],
        k: u64,
        dt: f64,
    ) -> bool {
        if let Some(e) = world.diverged(l) {
            lane.fail(k, dt, &e);
            return false;
        }
        let t = k as f64 * dt;
        sense(world, l, body, sensors, t, &mut lane.readings);
        lane.brain.control(t, &lane.readings, &mut lane.actuation);
        for (&v, a) in body.iter().zip(&mut lane.actuation) {
            *a = a.clamp(-1.0, 1.0);
            world.set_temperature(v, l, self.physics.amplitude * *a);
        }
        true
    }

    /// The outcome of an episode whose body moved by `moved`.
    fn outcome(
        &self,
        moved: DVec3,
        steps: u64,
        dt: f64,
        units: usize,
        trace: Option<crate::outcome::Trace>,
    ) -> Outcome {
        let seconds = steps as f64 * dt;
        let distance = moved.truncate().length();
        let metrics: Metrics = [
            ("distance", distance),
            ("dx", moved.x),
            ("dy", moved.y),
            ("dz", moved.z),
            ("velocity", distance / seconds),
            ("steps", steps as f64),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        Outcome {
            fitness: fitness_values(&self.fitness.0, &metrics),
            metrics,
            steps,
            units,
            trace,
        }
    }
}

/// The centre of mass of the body's voxels in lane `lane` (all of one material: their mean
/// position).
pub(crate) fn centre<W: Worlds + ?Sized>(world: &W, body: &[VoxelId], lane: usize) -> DVec3 {
    body.iter().map(|&v| world.position(v, lane)).sum::<DVec3>() / body.len().max(1) as f64
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinds::{from_short_forms, RobotArgs};
    use crate::registry::TaskSpec;

    fn robot(body: &str, brain: &str) -> crate::AnyRobot {
        from_short_forms(&RobotArgs {
            body,
            brain: Some(brain),
            sensors: None,
            preset: None,
        })
        .unwrap()
    }

    /// Robots of one body with brains of their own (random parameters from `seed`).
    fn quadrupeds(brain: &str, seeds: std::ops::Range<u64>) -> Vec<Voxel3dRobot> {
        let base = robot("3d:quadruped", brain);
        let base = base
            .as_robot()
            .description()
            .and_then(|d| d.as_any().downcast_ref::<Voxel3dRobot>());
        super::super::robot::with_random_brains(base.unwrap(), seeds)
    }

    #[test]
    fn a_batch_in_lanes_gives_every_robot_the_bits_of_its_own_episode() {
        let task = TaskSpec::parse("locomotion3d:0.1").unwrap();
        let task = task.task();
        // 10 robots: a full chunk of lanes (8 with AVX-512, else 4) and a chunk with idle lanes
        let robots = quadrupeds("mlp", 1..11);
        let refs: Vec<&dyn Robot> = robots.iter().map(|r| r as &dyn Robot).collect();
        let groups: Vec<Option<String>> = refs.iter().map(|r| task.episode_group(*r)).collect();
        assert!(groups[0].is_some() && groups.iter().all(|g| *g == groups[0]));
        let seeds = [3, 1, 4, 1, 5, 9, 2, 6, 5, 3];
        let alone = crate::task::assert_batch_is_alone(task, &refs, &seeds);
        let mut distances: Vec<f64> = alone.iter().map(|o| o.metrics["distance"]).collect();
        // the robots moved, each its own way (not one episode compared with itself)
        distances.sort_by(f64::total_cmp);
        distances.dedup();
        assert_eq!(distances.len(), 10, "{distances:?}");
        // another body is another group
        let other = robot("3d:worm", "mlp");
        assert_ne!(task.episode_group(other.as_robot()), groups[0]);
    }

    /// A travelling sine on every voxel that turns to NaN (a broken brain) from `fails_at` s.
    struct Breaking {
        phase: f64,
        fails_at: f64,
    }

    impl Controller for Breaking {
        fn reset(&mut self) {}

        fn control(&mut self, t: f64, _readings: &[f64], actuations: &mut [f64]) {
            for (i, a) in actuations.iter_mut().enumerate() {
                let wave = (2.0 * std::f64::consts::PI * 2.0 * t + self.phase + 0.5 * i as f64).sin();
                *a = if t >= self.fails_at { f64::NAN } else { wave };
            }
        }
    }

    #[test]
    fn lanes_whose_episodes_fail_are_refilled_and_every_episode_keeps_its_own_bits() {
        let task = Locomotion3d {
            duration: 0.1,
            ..Locomotion3d::default()
        };
        let r = robot("3d:quadruped", "phase");
        let Prepared { grid, sensors, .. } = prepare(r.as_robot(), "locomotion3d").unwrap();
        let built = task.physics.build(&grid, &[]).unwrap();
        let fails = [
            f64::INFINITY,
            0.0,
            0.03,
            f64::INFINITY,
            0.011,
            0.07,
            0.002,
            f64::INFINITY,
        ];
        let mut brains: Vec<Breaking> = (0..19)
            .map(|i| Breaking {
                phase: 0.37 * i as f64,
                fails_at: fails[i % fails.len()],
            })
            .collect();
        let alone: Vec<Result<DVec3, EpisodeError>> = brains
            .iter_mut()
            .map(|brain| {
                let mut lane = Lane::new(brain, &built.body, &sensors);
                let mut world = built.world.clone();
                task.episode(
                    &mut world,
                    &built.body,
                    &sensors,
                    &mut lane,
                    built.dt,
                    &mut |_, _, _| {},
                );
                lane.result
            })
            .collect();
        let queue = brains
            .iter_mut()
            .map(|brain| Walk::new(&task, &built.body, &sensors, built.dt, brain))
            .collect();
        let mut world = LanedWorlds::of(&built.world).unwrap();
        let steps = episode_steps(task.duration, built.dt);
        let laned = run_population(&mut world, queue, steps, built.dt);
        let key = |r: &Result<DVec3, EpisodeError>| match r {
            Ok(moved) => Ok(moved.to_array().map(f64::to_bits)),
            Err(e) => Err(e.to_string()),
        };
        for (i, (a, b)) in alone.iter().zip(&laned).enumerate() {
            assert_eq!(key(a), key(b), "episode {i}");
        }
        // failures at many steps, and walkers that moved their own ways
        let failed = alone.iter().filter(|r| r.is_err()).count();
        let mut moved: Vec<u64> = alone
            .iter()
            .filter_map(|r| r.as_ref().ok())
            .map(|m| m.x.to_bits())
            .collect();
        moved.sort_unstable();
        moved.dedup();
        assert_eq!((failed, moved.len()), (12, 7), "{alone:?}");
        assert!(
            alone[4].as_ref().unwrap_err().to_string().contains("t = 0.01"),
            "{alone:?}"
        );
    }

    #[test]
    fn a_quadruped_on_a_travelling_sine_walks_and_is_traced_and_repeatable() {
        let task = TaskSpec::parse("locomotion3d:1").unwrap();
        let r = robot("3d:quadruped", "phase");
        let o = crate::episode::run(r.as_robot(), task.task(), 0, TraceLevel::Full).unwrap();
        let trace = o.trace.as_ref().unwrap();
        assert_eq!(o.units, 28);
        // 1 s at 50 frames per second: frames at 0, 0.02, …, 1.0
        assert_eq!(trace.times.len(), 51, "{:?}", &trace.times[..3]);
        assert_eq!(trace.at(VOXEL_XYZ_NAME, 50).unwrap().len(), 28 * 3);
        assert!(o.metric("distance") > 1e-4, "the walker moves: {:?}", o.metrics);
        assert!(o.metrics.values().all(|v| v.is_finite()));
        let again = crate::episode::run(r.as_robot(), task.task(), 7, TraceLevel::None).unwrap();
        assert_eq!(again.fitness, o.fitness);
        assert_eq!(again.steps, o.steps);
    }

    #[test]
    fn an_obstacle_voxel_next_to_the_body_pushes_it_away_and_is_felt() {
        // no actuation: the body rests, held by static friction, unless something pushes it
        let still = Physics3d {
            amplitude: 0.0,
            ..Physics3d::default()
        };
        let r = robot("3d:box-2x1x1", "phase");
        let mut task = Locomotion3d {
            duration: 0.05,
            physics: still,
            ..Locomotion3d::default()
        };
        let alone = task
            .run_episode(r.as_robot(), 0, TraceLevel::None, &mut |_, _| {})
            .unwrap();
        assert_eq!(alone.metric("dx"), 0.0);
        // a wall cell right after the body's last voxel: their spheres overlap by s/4
        task.obstacles = vec![[2, 0, 0], [2, 0, 1]];
        let pushed = task
            .run_episode(r.as_robot(), 0, TraceLevel::Full, &mut |_, _| {})
            .unwrap();
        assert!(pushed.metric("dx") < -1e-3, "{:?}", pushed.metrics);
        let trace = pushed.trace.unwrap();
        assert_eq!(
            trace.fixed_values(crate::channels::FIXED_VOXELS.name),
            [0.02, 0.0, 0.0, 0.02, 0.0, 0.01]
        );
        task.obstacles.push([0, 0, 0]);
        let e = task
            .run_episode(r.as_robot(), 0, TraceLevel::None, &mut |_, _| {})
            .unwrap_err();
        assert!(e.to_string().contains("obstacles[2]"), "{e}");
    }

    #[test]
    fn bad_settings_and_robots_of_another_kind_are_refused_naming_the_field() {
        let err = |t: Locomotion3d| t.validate().unwrap_err().to_string();
        assert!(err(Locomotion3d {
            duration: -1.0,
            ..Default::default()
        })
        .starts_with("task.duration"));
        assert!(err(Locomotion3d {
            frame_rate: 0.0,
            ..Default::default()
        })
        .starts_with("task.frame_rate"));
        let long = Locomotion3d {
            duration: 1e4,
            ..Default::default()
        };
        assert!(err(long).contains("steps per episode"));
        let stiff = Locomotion3d {
            physics: Physics3d {
                youngs_modulus: 1e12,
                ..Default::default()
            },
            ..Default::default()
        };
        assert!(err(stiff).starts_with("task.duration"));
        let flat = robot("biped-4x3", "phase");
        let e = Locomotion3d::default()
            .run_episode(flat.as_robot(), 0, TraceLevel::None, &mut |_, _| {})
            .unwrap_err();
        assert!(e.to_string().contains("runs 3D voxel robots"), "{e}");
    }

    const VOXEL_XYZ_NAME: &str = crate::channels::VOXEL_XYZ.name;
}

#[cfg(test)]
mod properties {
    use super::*;
    use crate::kinds::{from_short_forms, RobotArgs};
    use proptest::prelude::*;

    /// A random body text of `w × h × d` cells from `bits` (at least the first cell kept).
    fn body_text(w: usize, h: usize, d: usize, bits: &[bool]) -> String {
        let layers: Vec<String> = (0..d)
            .map(|z| {
                (0..h)
                    .map(|y| {
                        (0..w)
                            .map(|x| {
                                let i = (z * h + y) * w + x;
                                if i == 0 || bits[i % bits.len()] {
                                    '#'
                                } else {
                                    '.'
                                }
                            })
                            .collect::<String>()
                    })
                    .collect::<Vec<_>>()
                    .join("/")
            })
            .collect();
        format!("3d:{}", layers.join("|"))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 12, ..ProptestConfig::default() })]
        /// Random bodies (refused when in pieces) under random brains with random weights: every
        /// episode either ends with finite metrics or is an error, never a NaN fitness.
        #[test]
        fn random_bodies_and_brains_never_give_non_finite_outcomes(
            w in 1usize..5, h in 1usize..5, d in 1usize..4,
            bits in proptest::collection::vec(any::<bool>(), 1..64),
            brain in prop_oneof![Just("mlp"), Just("distributed-mlp"), Just("phase")],
            seconds in 0.05f64..0.3,
        ) {
            let args = RobotArgs { body: &body_text(w, h, d, &bits), brain: Some(brain), sensors: None, preset: None };
            let Ok(robot) = from_short_forms(&args) else {
                return Ok(()); // a body in pieces is refused, naming why (tested in grid.rs)
            };
            let task = Locomotion3d { duration: seconds, ..Locomotion3d::default() };
            match task.run_episode(robot.as_robot(), 0, TraceLevel::None, &mut |_, _| {}) {
                Ok(o) => prop_assert!(
                    o.fitness.iter().chain(o.metrics.values()).all(|v| v.is_finite()),
                    "{:?}", o.metrics
                ),
                Err(e) => prop_assert!(e.to_string().contains("episode failed"), "{e}"),
            }
        }
    }
}
