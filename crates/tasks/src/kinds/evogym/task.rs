//! [`EvoGym`]: an EvoGym task as a vsrlab task (`[task] kind = "evogym"`, `env = "Walker-v0"`, or
//! `evogym:walker-v0` on the command line). Its episodes run on the mass-spring engine through
//! [`EvoGymEnv`], with the robot's own brain choosing the actions, and are traced like every
//! other episode: the voxels' outlines coloured by material, the terrain, the centre.

use super::assemble::plan_object;
use super::robot::{action_of, EvoGymRobot};
use super::tasks::EvoGymTask;
use super::{EnvLanes, EvoGymEnv, LANES};
use crate::agent::{Agent, Robot};
use crate::channels::{OBSTACLES, OBSTACLE_CORNERS, UNIT_FILL};
use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::outcome::{Outcome, Trace, TraceLevel};
use crate::task::{check_objectives, fitness_values, task_field, Metrics, Objective, Task};
use serde::{Deserialize, Serialize};
use vsrlab_body::Probe;
use vsrlab_brain::Controller;
use vsrlab_field::FieldError;
use vsrlab_physics::Vec2;

/// Simulated seconds of one EvoGym step: 30 substeps of 1e-4 s.
pub const STEP_SECONDS: f64 = 30.0 * 1e-4;

/// What an EvoGym episode reports.
const METRICS: &[&str] = &["reward", "distance", "velocity", "steps"];

/// An EvoGym task and how its episodes are scored (default: the sum of EvoGym's rewards).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct EvoGym {
    /// The task (`Walker-v0`, `BridgeWalker-v0`, `BeamToppler-v0`, `CaveCrawler-v0`).
    pub env: String,
    /// Objectives among `reward` (EvoGym's summed reward), `distance` (the robot's centre, Δx),
    /// `velocity` and `steps`.
    pub fitness: Fitness,
    /// At most this many simulated seconds (steps of [`STEP_SECONDS`]); absent or longer: the
    /// task's own length (500 or 1000 steps).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub duration: Option<f64>,
}

impl Default for EvoGym {
    fn default() -> Self {
        EvoGym {
            env: EvoGymTask::Walker.name().to_string(),
            fitness: Fitness::maximize("reward"),
            duration: None,
        }
    }
}

impl EvoGym {
    /// Steps of an episode: the task's length, or fewer when `duration` says so.
    fn steps(&self, which: EvoGymTask) -> u64 {
        let own = which.episode_steps() as u64;
        match self.duration {
            Some(d) => own.min(crate::task::episode_steps(d, STEP_SECONDS)),
            None => own,
        }
    }

    /// The task named by `env`, the error naming `task.env`.
    fn which(&self) -> Result<EvoGymTask, EpisodeError> {
        EvoGymTask::from_name(&self.env)
            .ok_or_else(|| task_field(FieldError::new("env", EvoGymTask::unknown(&self.env))))
    }
}

impl Task for EvoGym {
    fn kind(&self) -> &'static str {
        "evogym"
    }

    fn validate(&self) -> Result<(), EpisodeError> {
        self.which()?;
        if let Some(d) = self.duration {
            if !(d.is_finite() && d > 0.0) {
                return Err(task_field(FieldError::sentence(
                    "duration",
                    format!("must be a positive number of seconds, got {d}"),
                )));
            }
        }
        check_objectives(&self.fitness.0, METRICS)
    }

    fn duration(&self) -> f64 {
        self.which().map_or(0.0, |t| self.steps(t) as f64 * STEP_SECONDS)
    }

    fn step_seconds(&self) -> f64 {
        STEP_SECONDS
    }

    fn metric_names(&self) -> &'static [&'static str] {
        METRICS
    }

    fn as_any(&self) -> Option<&dyn std::any::Any> {
        Some(self)
    }

    fn objectives(&self) -> &[Objective] {
        &self.fitness.0
    }

    fn run_episode(
        &self,
        robot: &dyn Robot,
        seed: u64,
        level: TraceLevel,
        _observe: &mut dyn FnMut(f64, &dyn Agent),
    ) -> Result<Outcome, EpisodeError> {
        let (mut env, mut episode) = self.prepare(robot, seed)?;
        let grid = evogym_robot(robot)?
            .grid()
            .map_err(|e| EpisodeError::Field(e.at("robot")))?;
        let mut recorder = Recorder::new(level, env.task(), &grid, &env.task_world());
        recorder.record(&env, 0.0);
        while !episode.over {
            let result = env
                .step(episode.act())
                .map_err(|e| EpisodeError::Invalid(e.to_string()))?;
            episode.after(result.reward, result.done || result.truncated, result.observation);
            recorder.record(&env, episode.steps as f64 * STEP_SECONDS);
        }
        Ok(self.outcome(&env, &episode, recorder.finish()))
    }

    fn episode_group(&self, robot: &dyn Robot) -> Option<String> {
        let grid = evogym_robot(robot).ok()?.grid().ok()?;
        Some(format!("evogym {} {grid:?}", self.env))
    }

    fn episode_batch(&self) -> usize {
        LANES
    }

    fn run_episodes(&self, robots: &[&dyn Robot], seeds: &[u64]) -> Vec<Result<Outcome, EpisodeError>> {
        let prepared: Result<Vec<(EvoGymEnv, Episode)>, EpisodeError> = robots
            .iter()
            .zip(seeds)
            .map(|(robot, &seed)| self.prepare(*robot, seed))
            .collect();
        let Ok(mut prepared) = prepared else {
            // one of them is refused: each gives its own answer alone
            return crate::task::one_by_one(self, robots, seeds);
        };
        if prepared.is_empty() {
            return Vec::new();
        }
        // the lanes step the first LANES episodes not over: one that ends is replaced by the
        // batch's next, so the lanes stay full while the batch lasts
        let mut lanes = EnvLanes::new(&prepared[0].0);
        while prepared.iter().any(|(_, e)| !e.over) {
            if self.step_together(&mut lanes, &mut prepared).is_err() {
                // lanes that cannot take the batch (not expected of one group): each alone
                return crate::task::one_by_one(self, robots, seeds);
            }
        }
        prepared
            .iter_mut()
            .map(|(env, e)| match e.error.take() {
                Some(error) => Err(error),
                None => Ok(self.outcome(env, e, None)),
            })
            .collect()
    }
}

impl EvoGym {
    /// The environment and brain of `robot`'s episode, checked as `run_episode` checks them.
    fn prepare(&self, robot: &dyn Robot, seed: u64) -> Result<(EvoGymEnv, Episode), EpisodeError> {
        self.validate()?;
        let which = self.which()?;
        let robot = evogym_robot(robot)?;
        // a brain with weights was sized for one task's observation; a template fits any
        let template = robot.brain.parameters().is_empty();
        let made_for = robot.task().map_err(|e| EpisodeError::Field(e.at("robot")))?;
        if !template && made_for != which {
            return Err(EpisodeError::Field(FieldError::new(
                "robot.env",
                format!(
                    "the robot's brain sees {}'s observation, not {}'s: its weights were made for {} \
                     (run it there: --task {}), or give it a brain without weights, which draws \
                     random ones for the task it runs",
                    robot.env,
                    self.env,
                    robot.env,
                    made_for.short_name(),
                ),
            )));
        }
        let grid = robot.grid().map_err(|e| EpisodeError::Field(e.at("robot")))?;
        let mut env = EvoGymEnv::new(which, &grid).map_err(|e| EpisodeError::Invalid(e.to_string()))?;
        let shape = super::robot::shape(env.observation_size(), env.action_count());
        let at_brain = |e: vsrlab_brain::BrainError| EpisodeError::Field(FieldError::from(e).at("robot.brain"));
        let spec = crate::kinds::filled_brain(&robot.brain, &shape).map_err(at_brain)?;
        let mut brain = spec.build(&shape).map_err(at_brain)?;
        brain.reset();
        let observation = env.reset(seed).to_vec();
        let episode = Episode {
            brain,
            observation,
            outputs: vec![0.0; env.action_count()],
            actions: vec![0.0; env.action_count()],
            reward: 0.0,
            steps: 0,
            limit: self.steps(which),
            start: env.robot_centre().0,
            over: false,
            error: None,
        };
        Ok((env, episode))
    }

    /// One step of the first [`LANES`] episodes of `batch` that are not over, their physics in
    /// lanes; an episode whose step fails ends with its error, as it would alone. Fails when the
    /// lanes refuse the episodes.
    fn step_together(
        &self,
        lanes: &mut EnvLanes,
        batch: &mut [(EvoGymEnv, Episode)],
    ) -> Result<(), super::EvoGymError> {
        let mut running: Vec<(&mut EvoGymEnv, &mut Episode)> = batch
            .iter_mut()
            .filter(|(_, e)| !e.over)
            .take(LANES)
            .map(|(v, e)| (v, e))
            .collect();
        for (_, episode) in running.iter_mut() {
            episode.act();
        }
        let (mut envs, episodes): (Vec<&mut EvoGymEnv>, Vec<&mut Episode>) =
            running.iter_mut().map(|(v, e)| (&mut **v, &mut **e)).unzip();
        let actions: Vec<&[f64]> = episodes.iter().map(|e| e.actions.as_slice()).collect();
        let steps = lanes.step(&mut envs, &actions)?;
        for ((env, episode), step) in envs.iter().zip(episodes).zip(steps) {
            match step {
                Ok(step) => episode.after(step.reward, step.done || step.truncated, env.observation()),
                Err(e) => episode.fail(EpisodeError::Invalid(e.to_string())),
            }
        }
        Ok(())
    }

    /// The outcome of a finished episode.
    fn outcome(&self, env: &EvoGymEnv, episode: &Episode, trace: Option<Trace>) -> Outcome {
        let steps = episode.steps;
        let seconds = steps as f64 * STEP_SECONDS;
        let distance = env.robot_centre().0 - episode.start;
        let metrics: Metrics = [
            ("reward", episode.reward),
            ("distance", distance),
            ("velocity", distance / seconds.max(STEP_SECONDS)),
            ("steps", steps as f64),
        ]
        .into_iter()
        .map(|(k, v)| (k.to_string(), v))
        .collect();
        Outcome {
            fitness: fitness_values(&self.fitness.0, &metrics),
            metrics,
            steps,
            units: env.action_count(),
            trace,
        }
    }
}

/// One episode's brain and running sums, stepped alone (`run_episode`) or with others in lanes
/// (`run_episodes`): the same calls in the same order either way.
struct Episode {
    brain: Box<dyn Controller>,
    observation: Vec<f64>,
    outputs: Vec<f64>,
    actions: Vec<f64>,
    reward: f64,
    steps: u64,
    limit: u64,
    start: f64,
    over: bool,
    /// Why a step failed (the episode's answer instead of an outcome).
    error: Option<EpisodeError>,
}

impl Episode {
    /// The brain's actions for the current observation.
    fn act(&mut self) -> &[f64] {
        let t = self.steps as f64 * STEP_SECONDS;
        self.brain.control(t, &self.observation, &mut self.outputs);
        for (a, &o) in self.actions.iter_mut().zip(&self.outputs) {
            *a = action_of(o);
        }
        &self.actions
    }

    /// Takes a step's reward and observation; `ended` when the task ended the episode.
    fn after(&mut self, reward: f64, ended: bool, observation: &[f64]) {
        self.reward += reward;
        self.steps += 1;
        self.observation.copy_from_slice(observation);
        self.over = ended || self.steps >= self.limit;
    }

    /// Ends the episode with a failed step's error.
    fn fail(&mut self, error: EpisodeError) {
        self.error = Some(error);
        self.over = true;
    }
}

/// The EvoGym robot behind a robot of any kind, or an error naming the task's kind.
fn evogym_robot(robot: &dyn Robot) -> Result<&EvoGymRobot, EpisodeError> {
    robot
        .description()
        .and_then(|d| d.as_any().downcast_ref::<EvoGymRobot>())
        .ok_or_else(|| {
            EpisodeError::Field(FieldError::new(
                "task.kind",
                "evogym tasks run EvoGym robots (a body `evogym:ROWS`, or a robot file with \"evogym\")",
            ))
        })
}

/// Whether a world object is terrain: every cell fixed (drawn as static squares).
fn is_terrain(object: &super::WorldObject) -> bool {
    object.grid.present().all(|(_, _, m)| m.code() == 5)
}

/// A material's colour as a channel value.
fn colour_of(material: super::Material) -> f64 {
    f64::from(material_colour(material.code()))
}

/// EvoGym's colours of a material code (its renderer's, approximately), as `0xRRGGBB`.
fn material_colour(code: u8) -> u32 {
    match code {
        1 => 0x262626, // rigid
        2 => 0xbfbfbf, // soft
        3 => 0xfd8e3e, // horizontal actuator
        4 => 0x6dafd6, // vertical actuator
        _ => 0x000000, // fixed
    }
}

/// The trace of an EvoGym episode: the robot's voxels, then the cells of the world's moving
/// objects, as outline polygons (filled with their material's colour), the terrain's cells as
/// obstacles.
struct Recorder {
    level: TraceLevel,
    trace: Trace,
    /// The corner points in the world of each drawn cell: the robot's, then the moving objects'.
    quads: Vec<[usize; 4]>,
}

impl Recorder {
    fn new(level: TraceLevel, which: EvoGymTask, grid: &super::MaterialGrid, world: &super::worlds::World) -> Recorder {
        if level != TraceLevel::Full {
            // an evaluation's episode: only times and centres, no geometry to plan
            return Recorder {
                level,
                trace: empty_trace(),
                quads: Vec::new(),
            };
        }
        // the robot's cells, then those of every object that moves (the bridge, the beam), with
        // their points numbered as the environment adds them: the robot first, then the
        // world's objects in order
        let mut parts = vec![(grid, which.robot_origin(), 0)];
        let mut first = plan_object(grid, which.robot_origin()).points.len();
        for object in world.objects() {
            if !is_terrain(object) {
                parts.push((&object.grid, object.origin, first));
            }
            first += plan_object(&object.grid, object.origin).points.len();
        }
        Recorder::drawing(level, parts, world)
    }

    /// A recorder drawing the cells of `parts` (each a grid at its origin, its points numbered
    /// from a world index) in their materials' colours, over the terrain of `world`.
    fn drawing(
        level: TraceLevel,
        parts: Vec<(&super::MaterialGrid, (usize, usize), usize)>,
        world: &super::worlds::World,
    ) -> Recorder {
        let (mut quads, mut colours) = (Vec::new(), Vec::new());
        for (grid, origin, first) in parts {
            let plan = plan_object(grid, origin);
            quads.extend(plan.quads.iter().map(|q| q.corners.map(|p| p + first)));
            colours.extend(grid.present().map(|(_, _, m)| colour_of(m)));
        }
        let mut trace = empty_trace();
        trace.fixed(&UNIT_FILL, 1, &colours);
        trace.outline_corners = vec![4; quads.len()];
        describe_terrain(world, &mut trace);
        Recorder { level, trace, quads }
    }

    fn record(&mut self, env: &EvoGymEnv, t: f64) {
        let (x, y) = env.robot_centre();
        self.record_points(env.world(), Vec2::new(x, y), t);
    }

    /// Records the time, the centre and (in a full trace) every drawn cell's outline in `world`.
    fn record_points(&mut self, world: &vsrlab_physics::mass_spring::MassSpringWorld, centre: Vec2, t: f64) {
        if self.level == TraceLevel::None {
            return;
        }
        self.trace.times.push(t);
        self.trace.centers.push(centre);
        if self.level != TraceLevel::Full {
            return;
        }
        let (px, py) = (world.positions_x(), world.positions_y());
        for quad in &self.quads {
            self.trace
                .outlines
                .extend(quad.iter().map(|&p| Vec2::new(px[p], py[p])));
        }
    }

    fn finish(self) -> Option<Trace> {
        (self.level != TraceLevel::None).then_some(self.trace)
    }
}

/// A trace of EvoGym's step and cell size, nothing recorded yet.
fn empty_trace() -> Trace {
    Trace {
        dt: STEP_SECONDS,
        side_length: super::CELL,
        ..Default::default()
    }
}

/// One frame of `env` as it is now, drawn as an episode's trace draws it (the robot's voxels and
/// the moving objects' cells filled with their materials' colours, the terrain's cells): for
/// rendering a single state (Gymnasium's `render_mode="rgb_array"`).
pub fn frame(env: &EvoGymEnv) -> Trace {
    let mut recorder = Recorder::new(TraceLevel::Full, env.task(), env.robot_grid(), &env.task_world());
    recorder.record(env, env.steps() as f64 * STEP_SECONDS);
    recorder.trace
}

/// One frame of a simulation of any world ([`super::EvoGymSim`]) as it is now: every object
/// that moves drawn cell by cell in its materials' colours, the terrain's cells, the centre of
/// the first robot (or of the first object).
pub fn sim_frame(sim: &super::EvoGymSim) -> Trace {
    let layout = sim.layout();
    let parts = sim
        .objects()
        .iter()
        .filter_map(|placed| layout.object(&placed.name).map(|o| (o, placed.points.start)))
        .filter(|(o, _)| !is_terrain(o))
        .map(|(o, first)| (&o.grid, o.origin, first))
        .collect();
    let mut recorder = Recorder::drawing(TraceLevel::Full, parts, layout);
    let (px, py) = (sim.world().positions_x(), sim.world().positions_y());
    let first = &sim.objects()[0].points;
    let mean = |v: &[f64]| v[first.clone()].iter().sum::<f64>() / first.len().max(1) as f64;
    recorder.record_points(
        sim.world(),
        Vec2::new(mean(px), mean(py)),
        sim.steps() as f64 * STEP_SECONDS,
    );
    recorder.trace
}

/// The cells of the world's terrain (objects whose cells are all fixed) as static squares. No
/// ground line: EvoGym's worlds have no ground besides their objects (a line at y = 0 was drawn
/// as a slab under the start, and under BridgeWalker's bridge).
fn describe_terrain(world: &super::worlds::World, trace: &mut Trace) {
    let cell = super::CELL;
    let mut squares = Vec::new();
    for object in world.objects().iter().filter(|o| is_terrain(o)) {
        for (x, y, _) in object.grid.present() {
            let (ox, oy) = object.origin;
            let left = (ox + x) as f64 * cell;
            let top = (oy + object.grid.height() - y) as f64 * cell;
            squares.push([left, top - cell, left + cell, top - cell, left + cell, top, left, top]);
        }
    }
    trace.fixed(&OBSTACLE_CORNERS, 1, &vec![4.0; squares.len()]);
    trace.fixed(&OBSTACLES, 2, &squares.concat());
    trace.terrain.clear();
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

    const FULL: &str = "evogym:33333/33333/33333/33333/33333";

    #[test]
    fn a_walker_episode_is_scored_traced_and_repeatable() {
        let task = TaskSpec::parse("evogym:walker-v0").unwrap();
        let r = robot(FULL, "mlp");
        let o = crate::episode::run(r.as_robot(), task.task(), 0, TraceLevel::Full).unwrap();
        assert_eq!(
            o.metrics["steps"], 500.0,
            "Walker-v0 runs 500 steps without reaching x = 9.9"
        );
        assert_eq!(o.units, 25);
        // Walker's reward is the centre's Δx each step: the sum telescopes to the distance
        // (no goal bonus, no instability here)
        assert!(
            (o.metrics["reward"] - o.metrics["distance"]).abs() < 1e-9,
            "{:?}",
            o.metrics
        );
        assert_eq!(o.fitness, vec![o.metrics["reward"]]);
        let trace = o.trace.as_ref().unwrap();
        assert_eq!(trace.times.len(), 501);
        assert_eq!(trace.outline_corners, vec![4; 25]);
        assert_eq!(trace.outlines.len(), 501 * 25 * 4);
        assert!(trace.outlines.iter().all(|p| p.is_finite()));
        assert_eq!(trace.fixed_values(UNIT_FILL.name), vec![f64::from(0xfd8e3e); 25]);
        assert!(
            !trace.fixed_values(OBSTACLES.name).is_empty(),
            "the ground's cells are drawn"
        );
        assert!(trace.terrain.is_empty(), "no ground line besides the ground's cells");
        let again = crate::episode::run(r.as_robot(), task.task(), 0, TraceLevel::None).unwrap();
        assert_eq!(again.metrics, o.metrics, "bit-identical");
    }

    /// A Catcher-v0 episode draws the pegs where its seed placed them.
    #[test]
    fn a_drawn_worlds_trace_shows_that_world() {
        let task = TaskSpec::parse("evogym:catcher")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(0.05))])
            .unwrap();
        let which = EvoGymTask::from_name("Catcher-v0").unwrap();
        let r = walkers("33333/33333/33333/33333/33333", "Catcher-v0", 1..2).remove(0);
        let (a, b) = (0, (1..100).find(|&s| which.world_of(s) != which.world_of(0)).unwrap());
        let obstacles = |seed: u64| {
            let o = crate::episode::run(&r, task.task(), seed, TraceLevel::Full).unwrap();
            o.trace.unwrap().fixed_values(OBSTACLES.name).to_vec()
        };
        let expected = |seed: u64| {
            let mut trace = Trace::default();
            describe_terrain(&which.world_at(which.world_of(seed)), &mut trace);
            trace.fixed_values(OBSTACLES.name).to_vec()
        };
        assert_eq!(obstacles(a), expected(a));
        assert_eq!(obstacles(b), expected(b));
        assert_ne!(obstacles(a), obstacles(b));
    }

    /// A simulation of Walker-v0's world draws as the task's environment does.
    #[test]
    fn a_simulations_frame_is_its_environments() {
        let grid = super::super::MaterialGrid::from_rows("33333/33333/33333").unwrap();
        let mut env = EvoGymEnv::new(EvoGymTask::Walker, &grid).unwrap();
        let mut world = EvoGymTask::Walker.world();
        world
            .add(super::super::WorldObject::new("robot", (1, 1), grid))
            .unwrap();
        let mut sim = super::super::EvoGymSim::new(&world).unwrap();
        for t in 0..20 {
            let action = vec![if t % 10 < 5 { 1.6 } else { 0.6 }; 15];
            env.step(&action).unwrap();
            sim.set_action("robot", &action).unwrap();
            sim.step().unwrap();
        }
        let (a, b) = (frame(&env), sim_frame(&sim));
        assert_eq!(a.outlines, b.outlines);
        assert_eq!(a.outline_corners, b.outline_corners);
        assert_eq!(a.fixed_values(UNIT_FILL.name), b.fixed_values(UNIT_FILL.name));
        assert_eq!(a.fixed_values(OBSTACLES.name), b.fixed_values(OBSTACLES.name));
        assert_eq!((a.times, a.centers), (b.times, b.centers));
    }

    /// EvoGym robots of one body, each with its own random MLP.
    fn walkers(body: &str, env: &str, seeds: std::ops::Range<u64>) -> Vec<EvoGymRobot> {
        let grid = super::super::MaterialGrid::from_rows(body).unwrap();
        let task = EvoGymTask::from_name(env).unwrap();
        let probe = EvoGymEnv::new(task, &grid).unwrap();
        let shape = super::super::robot::shape(probe.observation_size(), probe.action_count());
        let template = vsrlab_brain::BrainSpec::parse("mlp").unwrap();
        seeds
            .map(|seed| EvoGymRobot {
                body: body.to_string(),
                env: env.to_string(),
                brain: template.with_random_parameters(seed, &shape).unwrap(),
            })
            .collect()
    }

    #[test]
    fn a_batch_in_lanes_gives_every_robot_the_bits_of_its_own_episode() {
        // Catcher-v0's robots start in the worlds their seeds draw, side by side in the lanes
        for (env, body) in [
            ("Walker-v0", "33333/33333/33333"),
            ("BeamToppler-v0", "3303/3443/1331"),
            ("Catcher-v0", "33333/33333/33333"),
        ] {
            let task = TaskSpec::parse(&format!("evogym:{env}"))
                .unwrap()
                .with_settings(&[("duration", serde_json::json!(0.15))])
                .unwrap();
            let task = task.task();
            // 10 robots: two full chunks of 4 lanes and a chunk of 2 with 2 idle lanes
            let robots = walkers(body, env, 1..11);
            let refs: Vec<&dyn Robot> = robots.iter().map(|r| r as &dyn Robot).collect();
            let groups: Vec<Option<String>> = refs.iter().map(|r| task.episode_group(*r)).collect();
            assert!(groups[0].is_some() && groups.iter().all(|g| *g == groups[0]));
            let seeds: Vec<u64> = (0..10).collect();
            let alone = crate::task::assert_batch_is_alone(task, &refs, &seeds);
            let mut distances: Vec<f64> = alone.iter().map(|o| o.metrics["distance"]).collect();
            // the robots moved, each its own way (not one episode compared with itself)
            distances.sort_by(f64::total_cmp);
            distances.dedup();
            assert_eq!(distances.len(), 10, "{env}: {distances:?}");
        }
        // another body, or the same body on another task, is another group
        let task = TaskSpec::parse("evogym:walker-v0").unwrap();
        let walker = robot("evogym:33333/33333/33333", "mlp");
        let other = robot("evogym:3333/3333/3333", "mlp");
        let group = task.task().episode_group(walker.as_robot());
        assert!(group.is_some());
        assert_ne!(task.task().episode_group(other.as_robot()), group);
        let bridge = TaskSpec::parse("evogym:bridgewalker-v0").unwrap();
        assert_ne!(bridge.task().episode_group(walker.as_robot()), group);
    }

    /// Episodes that end early (unstable) leave their lanes to the batch's next robots: every
    /// robot still gets the bits of its episode alone.
    #[test]
    fn lanes_refilled_as_episodes_end_give_every_robot_its_own_bits() {
        let task = TaskSpec::parse("evogym:walker-v0")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(3.0))])
            .unwrap();
        // a body EvoGym itself ends as unstable under extreme actions, driven by brains whose
        // large weights saturate their outputs
        let mut robots = walkers("24223/40044/30004/30434/30030", "Walker-v0", 1..10);
        for r in &mut robots {
            let strong: Vec<f64> = r.brain.parameters().iter().map(|w| 40.0 * w).collect();
            r.brain = r.brain.with_parameters(&strong).unwrap();
        }
        let refs: Vec<&dyn Robot> = robots.iter().map(|r| r as &dyn Robot).collect();
        let seeds: Vec<u64> = (0..9).collect();
        let alone = crate::task::assert_batch_is_alone(task.task(), &refs, &seeds);
        let mut steps: Vec<u64> = alone.iter().map(|o| o.steps).collect();
        steps.sort_unstable();
        steps.dedup();
        assert!(steps.len() >= 3, "episodes of different lengths: {steps:?}");
    }

    /// A batch with a robot its task refuses: every robot gets the answer it gets alone.
    #[test]
    fn a_batch_with_a_refused_robot_answers_each_as_alone() {
        let task = TaskSpec::parse("evogym:walker-v0")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(0.03))])
            .unwrap();
        let good = walkers("33333/33333/33333", "Walker-v0", 1..3);
        let mut bad = good[0].clone();
        bad.env = "CaveCrawler-v0".into(); // weights for Walker's observation, made for another task
        let refs: Vec<&dyn Robot> = vec![&good[0], &bad, &good[1]];
        let batch = task.task().run_episodes(&refs, &[0, 0, 0]);
        assert!(batch[0].is_ok() && batch[2].is_ok());
        let err = batch[1].as_ref().unwrap_err().to_string();
        assert!(err.contains("robot.env"), "{err}");
    }

    #[test]
    fn a_duration_shortens_the_episode_and_a_bad_one_is_refused() {
        let r = robot(FULL, "mlp");
        let short = TaskSpec::parse("evogym")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(0.3))])
            .unwrap();
        let o = crate::episode::run(r.as_robot(), short.task(), 0, TraceLevel::None).unwrap();
        assert_eq!(o.metrics["steps"], 100.0, "0.3 s of 3 ms steps");
        assert!((short.task().duration() - 0.3).abs() < 1e-12);
        let long = TaskSpec::parse("evogym")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(30.0))])
            .unwrap();
        assert!(
            (long.task().duration() - 1.5).abs() < 1e-12,
            "no longer than Walker's 500 steps"
        );
        let bad = TaskSpec::parse("evogym")
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(-1.0))])
            .unwrap();
        let err = bad.task().validate().unwrap_err().to_string();
        assert!(err.contains("task.duration"), "{err}");
    }

    #[test]
    fn evogym_robot_files_run_any_task_with_a_template_brain() {
        // EvoGym's own robot file (rows from the bottom: a rigid foot, an actuator, a rigid foot)
        let native = r#"{"grid_width": 3, "grid_height": 1, "objects": {"robot": {
            "indices": [0, 1, 2], "types": [1, 3, 1], "neighbors": {"0": [1], "1": [0, 2], "2": [1]}}}}"#;
        let r = crate::files::any_robot_from_json(native, "walker.json").unwrap();
        assert_eq!(r.kind().name, "evogym");
        let bridge = TaskSpec::parse("evogym:bridgewalker-v0").unwrap();
        let o = crate::episode::run(r.as_robot(), bridge.task(), 0, TraceLevel::Full).unwrap();
        assert!(
            o.metrics["reward"].is_finite() && o.metrics["steps"] > 0.0,
            "{:?}",
            o.metrics
        );
        // the bridge's cells are drawn after the robot's three, moving
        let trace = o.trace.unwrap();
        let polygons = trace.outline_corners.len();
        assert!(
            polygons > 3 && trace.fixed_values(UNIT_FILL.name).len() == polygons,
            "{polygons}"
        );
        let last = trace.outlines.len() - 4 * polygons;
        let moved = (3 * 4..4 * polygons).any(|i| trace.outlines[i] != trace.outlines[last + i]);
        assert!(moved, "the bridge sags under the robot");
        // no ground besides the world's objects: nothing is drawn under the bridge (issue 56, item
        // 5)
        assert!(trace.terrain.is_empty(), "{:?}", trace.terrain);
        // written back in vsrlab's form, it reads again as the same robot
        let again = crate::files::any_robot_from_json(&r.to_json(None), "again.json").unwrap();
        assert_eq!(again.to_json(None), r.to_json(None));
        let apart = native
            .replace(r#""1": [0, 2]"#, r#""1": [2]"#)
            .replace(r#""0": [1]"#, r#""0": []"#);
        let err = crate::files::any_robot_from_json(&apart, "apart.json")
            .unwrap_err()
            .to_string();
        assert!(err.contains("apart.json") && err.contains("objects"), "{err}");
    }

    #[test]
    fn robots_and_tasks_of_other_engines_are_refused_naming_the_field() {
        let evogym = TaskSpec::parse("evogym").unwrap();
        let voxel = robot("biped-4x3", "phase");
        let err = crate::episode::run(voxel.as_robot(), evogym.task(), 0, TraceLevel::None).unwrap_err();
        assert!(err.to_string().contains("task.kind"), "{err}");
        let walker = robot(FULL, "mlp");
        let flat = TaskSpec::parse("locomotion:flat").unwrap();
        let err = crate::episode::run(walker.as_robot(), flat.task(), 0, TraceLevel::None).unwrap_err();
        assert!(err.to_string().contains("task.kind"), "{err}");
        let bridge = TaskSpec::parse("evogym:BridgeWalker-v0").unwrap();
        let err = crate::episode::run(walker.as_robot(), bridge.task(), 0, TraceLevel::None).unwrap_err();
        assert!(err.to_string().contains("robot.env"), "{err}");
        let unknown = TaskSpec::parse("evogym:Climber-v9").unwrap_err();
        assert!(unknown.to_string().contains("Climber-v9"), "{unknown}");
    }

    #[test]
    fn the_brain_sees_the_task_observation_and_drives_every_actuator() {
        // a 3-voxel robot with one horizontal actuator: 8 points, so Walker's observation has
        // 2 + 2·8 = 18 values, and a no-hidden-layer MLP has (18 + 1)·1 weights
        let r = robot("evogym:131", "mlp:none");
        assert_eq!(r.brain().parameters().len(), 19);
        let bridge = robot("evogym:BridgeWalker-v0:131", "mlp:none");
        assert_eq!(
            bridge.brain().parameters().len(),
            20,
            "BridgeWalker adds the orientation"
        );
        for (output, action) in [(-1.0, 0.6), (0.0, 1.1), (1.0, 1.6), (f64::INFINITY, 1.6), (-7.0, 0.6)] {
            assert!(
                (action_of(output) - action).abs() < 1e-12,
                "{output} -> {}",
                action_of(output)
            );
        }
    }
}
