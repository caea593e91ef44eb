//! [`Affordance`]: the affordance study's task (thesis §5.1.3, thesis-code-facts §7): a 3D voxel
//! robot walks towards a wall with an aperture, in three environments ([`Environment`]), and
//! every voxel votes each step on whether the aperture is passable (its brain's [`VOTE`]
//! channel, e.g. the `elman` brain).
//!
//! Per environment i, from the step the body first touches the wall on:
//! - the step's decision is "passable" when at least as many voxels vote > 0 as ≤ 0 (ties count
//!   as passable); `acc_i` = steps whose decision is the truth / all steps of the episode (eq.
//!   5.4), 0 when the body never touches the wall;
//! - `d_i` = distance of the body's centre of mass from the target at the end (m), capped at
//!   `d_max` (5, as the original's code, which measures in metres: the cap never binds);
//! - penalties (on by default, as the original's code, which differs from the thesis's "more than
//!   half of the voxels outside the bounding volume"): a voxel's centre beyond the wall voxels'
//!   centres along x or above the highest of them at any step sets `d_i = d_max` and `acc_i = 0`.
//!   With `flying = true`, so does having at least half of the bottom layer off the floor for
//!   longer than `flying_seconds` (0: a single step). Off by default: the thesis has no such
//!   rule, and the original's code counts the flying voxels with a non-atomic increment from one
//!   GPU thread per voxel, so that (a warp's lanes overwriting each other) at most about one
//!   voxel per warp is counted and the half is never reached for the study's bodies.
//!   Both are checked when the voxels sense, before they actuate, as in the original.
//!
//! Then `locomotion = max d_i` (minimised) and `sensing = min acc_i` (maximised), eqs. 5.5–5.6.
//!
//! The thesis's controls (§5.1.4.2, [`Evolved`]) replace one output of every voxel, every step,
//! by a uniform draw in [−1, 1] from the evaluation's seed; `worlds = "random"` draws each
//! environment's aperture and side walls from it ([`random_aperture_world`]).

use super::aperture::{aperture_world, random_aperture_world, shape_length, ApertureWorld, Environment};
use super::physics::{Built, Physics3d, MAX_STEPS};
use super::population::{run_population, LaneEpisode};
use super::recorder::Recorder;
use super::robot::Voxel3dRobot;
use super::setup::{lanes, prepare, prepare_batch, sense, Prepared};
use super::worlds::Worlds as WorldView;
use super::BodyGrid3;
use crate::agent::{Agent, Robot};
use crate::episode::EpisodeError;
use crate::fitness::Fitness;
use crate::outcome::{Outcome, Trace, TraceLevel};
use crate::task::{check_objectives, fitness_values, task_field, Metrics, Objective, Sense, Task};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};
use vsrlab_body::Capture;
use vsrlab_brain::controllers::elman::VOTE;
use vsrlab_brain::Controller;
use vsrlab_field::FieldError;
use vsrlab_physics3d::laned_worlds::LanedWorlds;
use vsrlab_physics3d::{Dof, VoxelId, World, WorldSettings};

/// What an affordance evaluation reports: the two objectives, then each environment's.
const METRICS: &[&str] = &[
    "locomotion",
    "sensing",
    "locomotion-impassable",
    "sensing-impassable",
    "locomotion-passable-left",
    "sensing-passable-left",
    "locomotion-passable-right",
    "sensing-passable-right",
    "steps",
];

/// The pieces of an affordance world: voxels link within a piece only.
const BODY: u32 = 0;
const WALL: u32 = 1;
const TARGET: u32 = 2;

/// Which of the network's two outputs evolution shapes: the thesis's treatment and its two
/// controls (§5.1.4.2). In a control, the other output is replaced, for every voxel at every
/// step, by a uniform draw in [−1, 1]: in what the world does with it (temperature, or the vote
/// counted), not in the signal the voxel passes to its neighbours.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Evolved {
    /// EvolvedBoth: both outputs are the network's.
    #[default]
    Both,
    /// EvolvedAffordance: the actuation is random, only the votes are evolved.
    Affordance,
    /// EvolvedLocomotion: the votes are random, only the actuation is evolved.
    Locomotion,
}

/// The study's three fixed worlds, or the original's randomised variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Worlds {
    /// The apertures of the study (`_create_fixed_world`).
    #[default]
    Fixed,
    /// Aperture centre and width and side walls drawn from the evaluation's seed
    /// (`_create_random_world`; set `random_terrain_per_evaluation` for a new draw per
    /// evaluation).
    Random,
}

/// Detect whether an aperture is passable while walking to the right target.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Affordance {
    /// Episode length per environment (simulated seconds; the original's code ran 5 s).
    pub duration: f64,
    /// The environments, each an episode (the trace shows the first).
    pub environments: Vec<Environment>,
    /// Objectives among the metrics (default: minimise `locomotion`, maximise `sensing`).
    pub fitness: Fitness,
    /// The world: material, lattice, gravity, collisions, time step, actuation amplitude.
    pub physics: Physics3d,
    /// The body length L that sizes the world (absent: the study's for its shapes, flatworm 4,
    /// starfish 9, gecko 6, else the body's larger side).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub body_length: Option<usize>,
    /// Upper bound of each distance (m).
    pub d_max: f64,
    /// Whether leaving the world's bounds (and flying, with `flying`) gives the worst scores.
    pub penalties: bool,
    /// Whether flying is penalised too (off: the thesis has no such rule and the original's is
    /// inert, see the module docs).
    pub flying: bool,
    /// How long (s) half of the bottom layer must stay off the floor to count as flying; default
    /// 0, the original's rule (a single step).
    pub flying_seconds: f64,
    /// Which outputs are the network's: `both`, or a control (`affordance`, `locomotion`).
    pub evolved: Evolved,
    /// `fixed` (the study's worlds) or `random`.
    pub worlds: Worlds,
    /// Frames per second of recorded traces.
    pub frame_rate: f64,
}

/// The seed streams of one evaluation: control noise, and random worlds.
const NOISE_STREAM: u64 = 0x6e6f_6973_6500_0001;
const WORLD_STREAM: u64 = 0x776f_726c_6400_0002;

impl Default for Affordance {
    fn default() -> Self {
        Affordance {
            duration: 5.0,
            environments: Environment::ALL.to_vec(),
            fitness: Fitness(vec![
                Objective {
                    metric: "locomotion".into(),
                    sense: Sense::Minimize,
                },
                Objective::maximize("sensing"),
            ]),
            physics: Physics3d::default(),
            body_length: None,
            d_max: 5.0,
            penalties: true,
            flying: false,
            flying_seconds: 0.0,
            evolved: Evolved::Both,
            worlds: Worlds::Fixed,
            frame_rate: 50.0,
        }
    }
}

/// One environment's scores.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scores {
    /// Distance from the target at the end (m), capped.
    pub distance: f64,
    /// Accuracy of the collective votes (eq. 5.4).
    pub accuracy: f64,
}

/// The collective decision of one step: passable when at least as many votes are > 0 as ≤ 0.
pub fn decision(votes: &[f64]) -> bool {
    let yes = votes.iter().filter(|&&v| v > 0.0).count();
    yes >= votes.len() - yes
}

impl Affordance {
    fn length(&self, robot: &Voxel3dRobot, grid: &BodyGrid3) -> usize {
        let [w, h, _] = grid.extent();
        self.body_length
            .or_else(|| shape_length(&robot.body))
            .unwrap_or(w.max(h))
    }

    /// What the episodes of one environment share: the built world's body, obstacles, pieces,
    /// bounds and bottom layer, the time step and the step count.
    fn setting(&self, built: &Built) -> Setting {
        let (min_x, max_x, top) = bounds(built);
        let bottom = built
            .body
            .iter()
            .copied()
            .filter(|&v| built.world.position(v).z < 0.5 * self.physics.voxel_size)
            .collect();
        let mut pieces = vec![BODY; built.body.len() + built.obstacles.len()];
        for &v in &built.obstacles {
            pieces[v.index()] = built.world.piece(v);
        }
        Setting {
            body: built.body.clone(),
            target: built.obstacles[built.obstacles.len() - 1],
            pieces,
            bounds: (min_x, max_x, top),
            bottom,
            dt: built.dt,
            steps: crate::task::episode_steps(self.duration, built.dt),
        }
    }

    /// One environment's episode of `voter` in `world`, the study's loop: every step the world
    /// steps, then the robot senses, is checked for the penalties, controls, actuates and votes;
    /// `record(world, actuation, votes, t)` after every step.
    fn episode(
        &self,
        env: Environment,
        world: &mut World,
        setting: &Setting,
        sensors: &[super::Sensor3],
        voter: &mut Voter,
        record: &mut Record<World>,
    ) {
        for k in 1..=setting.steps {
            if let Err(e) = world.step(setting.dt) {
                voter.result = Some(Err(failure(env, k, setting.dt, &e)));
                return;
            }
            if !self.step_voter(env, world, 0, voter, setting, sensors, k) {
                return;
            }
            record(world, &voter.actuation, self.votes(voter), k as f64 * setting.dt);
        }
        voter.result = Some(Ok(self.scores(world, 0, voter, setting)));
    }

    /// Step `k` (from 1) of `voter`'s episode in lane `lane`, after the world stepped. False
    /// when the episode failed (its result is then set).
    #[allow(clippy::too_many_arguments)]
    fn step_voter<W: WorldView>(
        &self,
        env: Environment,
        world: &mut W,
        lane: usize,
        v: &mut Voter,
        setting: &Setting,
        sensors: &[super::Sensor3],
        k: u64,
    ) -> bool {
        let (dt, body) = (setting.dt, &setting.body);
        let (min_x, max_x, top) = setting.bounds;
        let flying_steps = (self.flying_seconds / dt).round() as u64;
        if let Some(e) = world.diverged(lane) {
            v.result = Some(Err(failure(env, k, dt, &e)));
            return false;
        }
        let t = k as f64 * dt;
        sense(world, lane, body, sensors, t, &mut v.readings);
        v.airborne = if flying(world, lane, &setting.bottom) {
            v.airborne + 1
        } else {
            0
        };
        if self.penalties && !v.penalised {
            let flown = self.flying && v.airborne > flying_steps;
            v.penalised = flown || out_of_bounds(world, lane, body, min_x, max_x, top);
        }
        v.brain.control(t, &v.readings, &mut v.actuation);
        if self.evolved == Evolved::Affordance {
            v.actuation
                .iter_mut()
                .for_each(|a| *a = v.noise.random_range(-1.0..=1.0));
        }
        for (&voxel, a) in body.iter().zip(&mut v.actuation) {
            *a = a.clamp(-1.0, 1.0);
            world.set_temperature(voxel, lane, self.physics.amplitude * *a);
        }
        v.brain.publish(&mut v.capture);
        if v.capture.get(VOTE.name).is_none() {
            v.result = Some(Err(EpisodeError::Field(FieldError::new(
                "robot.brain",
                "the affordance task needs a brain that votes (elman)",
            ))));
            return false;
        }
        if self.evolved == Evolved::Locomotion {
            v.random_votes
                .iter_mut()
                .for_each(|r| *r = v.noise.random_range(-1.0..=1.0));
        }
        v.touched = v.touched || touches_wall(world, lane, &setting.pieces);
        if v.touched && decision(self.votes(v)) == env.passable() {
            v.correct += 1;
        }
        true
    }

    /// The votes of this step that count: the brain's, or random ones when only locomotion was
    /// evolved (the study's control).
    fn votes<'v>(&self, v: &'v Voter) -> &'v [f64] {
        match self.evolved {
            Evolved::Locomotion => &v.random_votes,
            _ => v.capture.get(VOTE.name).unwrap_or_default(),
        }
    }

    /// The scores of `v`'s episode, which ran its last step in lane `lane`.
    fn scores<W: WorldView>(&self, world: &W, lane: usize, v: &Voter, setting: &Setting) -> Scores {
        let target = world.position(setting.target, lane);
        let centre = super::task::centre(world, &setting.body, lane);
        match v.penalised {
            true => Scores {
                distance: self.d_max,
                accuracy: 0.0,
            },
            false => Scores {
                distance: centre.distance(target).min(self.d_max),
                accuracy: v.correct as f64 / setting.steps as f64,
            },
        }
    }

    /// The outcome of a robot's environments: each one's scores and steps, and the trace of the
    /// first.
    fn outcome(&self, scores: &[(Environment, Scores)], steps: u64, units: usize, trace: Option<Trace>) -> Outcome {
        let mut metrics = Metrics::new();
        let (mut locomotion, mut sensing) = (0.0f64, 1.0f64);
        for (env, scores) in scores {
            metrics.insert(format!("locomotion-{}", env.name()), scores.distance);
            metrics.insert(format!("sensing-{}", env.name()), scores.accuracy);
            locomotion = locomotion.max(scores.distance);
            sensing = sensing.min(scores.accuracy);
        }
        metrics.insert("locomotion".into(), locomotion);
        metrics.insert("sensing".into(), sensing);
        metrics.insert("steps".into(), steps as f64);
        Outcome {
            fitness: fitness_values(&self.fitness.0, &metrics),
            metrics,
            steps,
            units,
            trace,
        }
    }

    /// The world: the body at the layout's origin, the wall and the target fixed, each a piece.
    fn build(&self, grid: &BodyGrid3, layout: &ApertureWorld) -> Result<Built, EpisodeError> {
        let p = &self.physics;
        let invalid = |e: vsrlab_physics3d::Physics3dError| EpisodeError::Invalid(e.to_string());
        let mut world = World::new(WorldSettings {
            voxel_size: p.voxel_size,
            gravity: p.gravity,
            floor: true,
            collisions: p.collisions,
        })
        .map_err(invalid)?;
        let material = world.add_material(p.material()).map_err(invalid)?;
        let o = layout.body_origin;
        let mut body = Vec::with_capacity(grid.voxel_count());
        for c in grid.cells() {
            let cell = [o[0] + c[0] as i32, o[1] + c[1] as i32, o[2] + c[2] as i32];
            body.push(world.add_voxel_to_piece(material, cell, BODY).map_err(invalid)?);
        }
        let mut obstacles = Vec::with_capacity(layout.wall.len() + layout.side_walls.len() + 1);
        // a random world's side wall leaves out the cells of a body wider than the original's
        // (its random worlds narrowed the flatworm to 3 voxels; ours keeps the 5 × 5)
        let occupied: std::collections::HashSet<[i32; 3]> = grid
            .cells()
            .map(|c| [o[0] + c[0] as i32, o[1] + c[1] as i32, o[2] + c[2] as i32])
            .collect();
        for &cell in layout.side_walls.iter().filter(|c| !occupied.contains(*c)) {
            let v = world.add_voxel_to_piece(material, cell, WALL).map_err(invalid)?;
            world.set_fixed(v, &Dof::ALL, true);
            obstacles.push(v);
        }
        for (&cell, piece) in layout.wall.iter().map(|c| (c, WALL)).chain([(&layout.target, TARGET)]) {
            let v = world.add_voxel_to_piece(material, cell, piece).map_err(|_| {
                task_field(FieldError::new(
                    "body_length",
                    format!("the body reaches the wall or the target at {cell:?}: give a larger body_length"),
                ))
            })?;
            world.set_fixed(v, &Dof::ALL, true);
            obstacles.push(v);
        }
        Ok(Built {
            world,
            body,
            obstacles,
            dt: p.dt(),
        })
    }
}

/// Whether a body voxel touched a wall voxel in lane `lane` this step (`pieces`: each voxel's).
fn touches_wall<W: WorldView>(world: &W, lane: usize, pieces: &[u32]) -> bool {
    world.any_contact(lane, &|a, b| {
        let pieces = (pieces[a.index()], pieces[b.index()]);
        pieces == (BODY, WALL) || pieces == (WALL, BODY)
    })
}

/// The original's bounding volume: the least and greatest x of the wall voxels' centres and the
/// highest centre (m).
fn bounds(built: &Built) -> (f64, f64, f64) {
    let wall = built.obstacles.iter().filter(|&&v| built.world.piece(v) == WALL);
    let (mut min_x, mut max_x, mut top) = (f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    for &v in wall {
        let p = built.world.position(v);
        (min_x, max_x, top) = (min_x.min(p.x), max_x.max(p.x), top.max(p.z));
    }
    (min_x, max_x, top)
}

/// Whether a body voxel's centre left the wall's centres along x or rose above the highest, in
/// lane `lane`.
fn out_of_bounds<W: WorldView>(world: &W, lane: usize, body: &[VoxelId], min_x: f64, max_x: f64, top: f64) -> bool {
    body.iter().any(|&v| {
        let p = world.position(v, lane);
        p.x < min_x || p.x > max_x || p.z > top
    })
}

/// Whether at least half of the bottom layer is off the floor in lane `lane`.
fn flying<W: WorldView>(world: &W, lane: usize, bottom: &[VoxelId]) -> bool {
    let off = bottom.iter().filter(|&&v| !world.touches_floor(v, lane)).count();
    !bottom.is_empty() && 2 * off >= bottom.len()
}

/// What a scalar episode records after every step: the world, the actuation and the votes, at
/// time t.
/// The error that ends an episode in `env` at its step `k`.
fn failure(env: Environment, k: u64, dt: f64, e: &vsrlab_physics3d::Physics3dError) -> EpisodeError {
    EpisodeError::Invalid(format!(
        "{}: episode failed at t = {:.4} s: {e}",
        env.name(),
        k as f64 * dt
    ))
}

/// A [`Voter`]'s episode in one environment, in a laned population ([`run_population`]).
struct Vote<'a, 'b> {
    task: &'b Affordance,
    env: Environment,
    setting: &'b Setting,
    sensors: &'b [super::Sensor3],
    voter: Voter<'a>,
}

impl LaneEpisode for Vote<'_, '_> {
    type Result = Result<Scores, EpisodeError>;

    fn start(&mut self, _world: &LanedWorlds, _lane: usize) {}

    fn advance(&mut self, world: &mut LanedWorlds, lane: usize, k: u64) -> bool {
        let (env, setting, sensors) = (self.env, self.setting, self.sensors);
        self.task
            .step_voter(env, world, lane, &mut self.voter, setting, sensors, k)
    }

    fn finish(self, world: &LanedWorlds, lane: usize) -> Self::Result {
        match self.voter.result {
            Some(result) => result,
            None => Ok(self.task.scores(world, lane, &self.voter, self.setting)),
        }
    }

    fn refused(self, k: u64, error: &vsrlab_physics3d::Physics3dError) -> Self::Result {
        Err(failure(self.env, k, self.setting.dt, error))
    }
}

type Record<'a, W> = dyn FnMut(&W, &[f64], &[f64], f64) + 'a;

/// What the episodes of one environment share (`Affordance::setting`).
struct Setting {
    body: Vec<VoxelId>,
    /// The target voxel.
    target: VoxelId,
    /// Each voxel's piece.
    pieces: Vec<u32>,
    /// The least and greatest x of the wall and its top (m).
    bounds: (f64, f64, f64),
    /// The body's bottom layer.
    bottom: Vec<VoxelId>,
    dt: f64,
    steps: u64,
}

/// One robot's episode in one environment: its brain and noise, buffers, what it did, and how
/// it ended (`None` while it runs).
struct Voter<'a> {
    brain: &'a mut dyn Controller,
    noise: &'a mut ChaCha8Rng,
    readings: Vec<f64>,
    actuation: Vec<f64>,
    random_votes: Vec<f64>,
    capture: Capture,
    touched: bool,
    correct: u64,
    penalised: bool,
    airborne: u64,
    result: Option<Result<Scores, EpisodeError>>,
}

impl<'a> Voter<'a> {
    /// A fresh episode of a robot (its brain reset) with `units` voxels of `sensors` readings.
    fn new(brain: &'a mut dyn Controller, noise: &'a mut ChaCha8Rng, units: usize, sensors: usize) -> Self {
        brain.reset();
        Voter {
            brain,
            noise,
            readings: vec![0.0; units * sensors],
            actuation: vec![0.0; units],
            random_votes: vec![0.0; units],
            capture: Capture::new(),
            touched: false,
            correct: 0,
            penalised: false,
            airborne: 0,
            result: None,
        }
    }
}

impl Task for Affordance {
    fn kind(&self) -> &'static str {
        "affordance"
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
        if d / self.physics.dt() > MAX_STEPS {
            return Err(task_field(FieldError::sentence(
                "duration",
                format!("{d} s is more than {MAX_STEPS:.0e} steps of this material's time step"),
            )));
        }
        if self.environments.is_empty() {
            return Err(task_field(FieldError::sentence("environments", "give at least one")));
        }
        if let Some(l) = self.body_length {
            if !(2..=64).contains(&l) {
                return Err(task_field(FieldError::sentence(
                    "body_length",
                    format!("must be 2 to 64 voxels, got {l}"),
                )));
            }
        }
        if !(self.flying_seconds.is_finite() && self.flying_seconds >= 0.0) {
            return Err(task_field(FieldError::sentence(
                "flying_seconds",
                format!("must be a number of seconds ≥ 0, got {}", self.flying_seconds),
            )));
        }
        if !(self.d_max.is_finite() && self.d_max > 0.0) {
            return Err(task_field(FieldError::sentence(
                "d_max",
                format!("must be a positive number, got {}", self.d_max),
            )));
        }
        let r = self.frame_rate;
        if !(r.is_finite() && r > 0.0 && r <= 10_000.0) {
            return Err(task_field(FieldError::sentence(
                "frame_rate",
                format!("must be in (0, 10000], got {r}"),
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
        seed: u64,
        level: TraceLevel,
        _observe: &mut dyn FnMut(f64, &dyn Agent),
    ) -> Result<Outcome, EpisodeError> {
        self.validate()?;
        let Prepared {
            robot,
            grid,
            sensors,
            mut brain,
        } = prepare(robot, "the affordance task")?;
        let length = self.length(robot, &grid);
        let [w, h, _] = grid.extent();
        let mut noise = ChaCha8Rng::seed_from_u64(seed ^ NOISE_STREAM);
        let mut draw = ChaCha8Rng::seed_from_u64(seed ^ WORLD_STREAM);
        let (mut scores, mut steps, mut trace) = (Vec::new(), 0, None);
        for (i, &env) in self.environments.iter().enumerate() {
            let level = if i == 0 { level } else { TraceLevel::None };
            let layout = match self.worlds {
                Worlds::Fixed => aperture_world(env, length, w, h),
                Worlds::Random => random_aperture_world(env, length, w, h, &mut draw),
            };
            let built = self.build(&grid, &layout)?;
            let setting = self.setting(&built);
            let n = setting.body.len();
            let mut recorder = Recorder::new(level, &built, self.frame_rate);
            recorder.record(&built.world, &built.body, &vec![0.0; n], 0.0);
            recorder.record_channel(&VOTE, &vec![0.0; n]);
            let mut world = built.world;
            let mut voter = Voter::new(brain.as_mut(), &mut noise, n, sensors.len());
            self.episode(
                env,
                &mut world,
                &setting,
                &sensors,
                &mut voter,
                &mut |world, actuation, votes, t| {
                    recorder.record(world, &setting.body, actuation, t);
                    recorder.record_channel(&VOTE, votes);
                },
            );
            scores.push((env, voter.result.expect("every episode ends")?));
            steps += setting.steps;
            trace = trace.or(recorder.finish());
        }
        Ok(self.outcome(&scores, steps, grid.voxel_count(), trace))
    }

    fn episode_group(&self, robot: &dyn Robot) -> Option<String> {
        // a random world depends on the evaluation's seed: such episodes run alone
        (self.worlds == Worlds::Fixed)
            .then(|| super::task::same_body_group(robot))
            .flatten()
    }

    fn episode_batch(&self) -> usize {
        lanes()
    }

    fn run_episodes(&self, robots: &[&dyn Robot], seeds: &[u64]) -> Vec<Result<Outcome, EpisodeError>> {
        let one_by_one = || crate::task::one_by_one(self, robots, seeds);
        let batch = (robots.len() > 1 && self.worlds == Worlds::Fixed && self.validate().is_ok())
            .then(|| prepare_batch(robots, "the affordance task"))
            .flatten();
        let Some(mut prepared) = batch else {
            return one_by_one();
        };
        let first = &prepared[0];
        let (grid, sensors) = (first.grid.clone(), first.sensors.clone());
        let length = self.length(first.robot, &grid);
        if prepared.iter().any(|p| self.length(p.robot, &p.grid) != length) {
            return one_by_one();
        }
        let [w, h, _] = grid.extent();
        let mut noises: Vec<ChaCha8Rng> = seeds
            .iter()
            .map(|&s| ChaCha8Rng::seed_from_u64(s ^ NOISE_STREAM))
            .collect();
        let mut ended: Vec<Option<EpisodeError>> = robots.iter().map(|_| None).collect();
        let mut scores: Vec<Vec<(Environment, Scores)>> = robots.iter().map(|_| Vec::new()).collect();
        let mut steps = 0;
        for &env in &self.environments {
            let built = match self.build(&grid, &aperture_world(env, length, w, h)) {
                Ok(built) => built,
                Err(_) => return one_by_one(),
            };
            let setting = self.setting(&built);
            let n = setting.body.len();
            let running: Vec<usize> = (0..robots.len()).filter(|&r| ended[r].is_none()).collect();
            let Ok(mut world) = LanedWorlds::of(&built.world) else {
                return one_by_one();
            };
            // the robots that did not fail in an earlier environment
            let queue: Vec<Vote> = prepared
                .iter_mut()
                .zip(noises.iter_mut())
                .zip(&ended)
                .filter(|(_, ended)| ended.is_none())
                .map(|((p, noise), _)| Vote {
                    task: self,
                    env,
                    setting: &setting,
                    sensors: &sensors,
                    voter: Voter::new(p.brain.as_mut(), noise, n, sensors.len()),
                })
                .collect();
            let results = run_population(&mut world, queue, setting.steps, setting.dt);
            for (&r, result) in running.iter().zip(results) {
                match result {
                    Ok(s) => scores[r].push((env, s)),
                    Err(e) => ended[r] = Some(e),
                }
            }
            steps += setting.steps;
        }
        scores
            .iter()
            .zip(ended)
            .map(|(scores, ended)| match ended {
                Some(e) => Err(e),
                None => Ok(self.outcome(scores, steps, grid.voxel_count(), None)),
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::channels::{ACTUATION, FIXED_VOXELS};
    use crate::kinds::{from_short_forms, RobotArgs};
    use vsrlab_brain::controllers::elman::ElmanSpec;
    use vsrlab_brain::BrainSpec;

    #[test]
    fn ties_count_as_passable() {
        assert!(decision(&[0.5, -0.5]));
        assert!(decision(&[0.5, 0.2, -0.9]));
        assert!(!decision(&[0.5, -0.2, -0.9]));
        assert!(!decision(&[0.0]), "a vote of 0 is a no");
    }

    /// The outcome of `robot` on `task` (episode seed `seed`, trace `level`).
    fn episode(task: &Affordance, robot: &crate::AnyRobot, seed: u64, level: TraceLevel) -> Outcome {
        task.run_episode(robot.as_robot(), seed, level, &mut |_, _| {}).unwrap()
    }

    /// A robot whose every voxel always votes `vote` and never actuates (an Elman brain with
    /// zero weights but the vote's bias).
    fn voter(body: &str, vote: f64) -> crate::AnyRobot {
        biased(body, 0.0, vote)
    }

    /// A robot whose every voxel always actuates `actuation` (as tanh of it) and votes `vote`.
    fn biased(body: &str, actuation: f64, vote: f64) -> crate::AnyRobot {
        let robot = from_short_forms(&RobotArgs {
            body,
            brain: Some("elman"),
            sensors: None,
            preset: None,
        })
        .unwrap();
        let r = robot.downcast_ref::<Voxel3dRobot>().unwrap();
        let shape = r.brain_shape().unwrap();
        let n = r.brain.parameter_count(&shape).unwrap();
        let mut weights = vec![0.0; n];
        // the biases of the actuation and the vote: the first of each of the last two m + 1 blocks
        weights[n - 14] = actuation;
        weights[n - 7] = vote;
        crate::AnyRobot::new(Voxel3dRobot {
            brain: BrainSpec::Elman(ElmanSpec {
                weights,
                ..ElmanSpec::default()
            }),
            ..r.clone()
        })
    }

    /// Robots of `body` with Elman brains of random parameters (one seed each).
    fn random_elmans(body: &str, seeds: std::ops::Range<u64>) -> Vec<Voxel3dRobot> {
        let base = biased(body, 0.0, 0.0);
        super::super::robot::with_random_brains(base.downcast_ref::<Voxel3dRobot>().unwrap(), seeds)
    }

    #[test]
    fn a_batch_in_lanes_gives_every_robot_the_bits_of_its_own_evaluation() {
        // 9 robots: a full chunk of lanes (8 with AVX-512, else 4) and a chunk with idle lanes;
        // each control, with its noise per seed, and the flying penalty (lanes penalised at
        // different steps)
        let robots = random_elmans("3d:starfish", 1..10);
        let refs: Vec<&dyn Robot> = robots.iter().map(|r| r as &dyn Robot).collect();
        let seeds = [11, 12, 13, 14, 15, 16, 17, 18, 19];
        let mut penalised = 0;
        // (EvolvedBoth runs below, with bodies at the wall)
        for (evolved, flying) in [(Evolved::Affordance, true), (Evolved::Locomotion, false)] {
            let task = Affordance {
                duration: 0.04,
                evolved,
                flying,
                flying_seconds: 0.02,
                ..Affordance::default()
            };
            assert!(task.episode_group(refs[0]).is_some());
            let mut values = Vec::new();
            for alone in crate::task::assert_batch_is_alone(&task, &refs, &seeds) {
                penalised += usize::from(alone.metrics["locomotion"] == task.d_max);
                values.push(alone.metrics["locomotion-impassable"]);
            }
            values.sort_by(f64::total_cmp);
            values.dedup();
            if evolved == Evolved::Locomotion {
                assert!(values.len() >= 4, "the robots moved each its own way: {values:?}");
            }
        }
        // the flying rule penalised some lanes (at their own steps), not all
        assert!(penalised > 0 && penalised < 18, "{penalised}");
        // bodies that touch the wall from the start (L = 2, as the test below): the votes count
        let robots = random_elmans("3d:###/###/###/###", 1..5);
        let refs: Vec<&dyn Robot> = robots.iter().map(|r| r as &dyn Robot).collect();
        let task = Affordance {
            duration: 0.02,
            body_length: Some(2),
            ..Affordance::default()
        };
        let batch = task.run_episodes(&refs, &seeds[..4]);
        let mut sensing = Vec::new();
        for ((robot, &seed), laned) in refs.iter().zip(&seeds).zip(&batch) {
            let alone = task
                .run_episode(*robot, seed, TraceLevel::None, &mut |_, _| {})
                .unwrap();
            assert_eq!(laned.as_ref().unwrap().metrics, alone.metrics);
            sensing.push(alone.metrics["sensing-passable-left"]);
        }
        sensing.sort_by(f64::total_cmp);
        sensing.dedup();
        assert!(sensing.len() >= 2 && sensing.iter().any(|&s| s > 0.0), "{sensing:?}");
        // random worlds depend on the seed: not batched
        let random = Affordance {
            worlds: Worlds::Random,
            ..Affordance::default()
        };
        assert!(random.episode_group(refs[0]).is_none());
    }

    #[test]
    fn a_robot_touching_the_wall_from_the_start_and_voting_passable_scores_by_the_truth() {
        // L = 2: the wall at y = 6 and apertures 1 wide (at x = 3, 2 and 4); a 3 × 4 body from
        // (2, 2) ends next to the wall and touches it at once in all three
        let task = Affordance {
            duration: 0.02,
            body_length: Some(2),
            ..Affordance::default()
        };
        let yes = voter("3d:###/###/###/###", 10.0);
        let o = episode(&task, &yes, 0, TraceLevel::Full);
        assert_eq!(o.metric("sensing-passable-left"), 1.0, "{:?}", o.metrics);
        assert_eq!(o.metric("sensing-passable-right"), 1.0);
        assert_eq!(o.metric("sensing-impassable"), 0.0);
        assert_eq!(o.metric("sensing"), 0.0, "the worst of the three");
        let trace = o.trace.unwrap();
        assert_eq!(
            trace.at(VOTE.name, 0).unwrap(),
            [0.0; 12],
            "no vote before the first step"
        );
        assert!(trace.at(VOTE.name, 1).unwrap().iter().all(|&v| v > 0.99));
        let no = voter("3d:###/###/###/###", -10.0);
        let o = episode(&task, &no, 0, TraceLevel::None);
        assert_eq!(
            (o.metric("sensing-impassable"), o.metric("sensing-passable-left")),
            (1.0, 0.0)
        );
    }

    #[test]
    fn the_controls_replace_one_output_by_seeded_noise() {
        let task = Affordance {
            duration: 0.05,
            body_length: Some(2),
            penalties: false,
            ..Affordance::default()
        };
        let yes = voter("3d:###/###/###/###", 10.0);
        let run = |task: &Affordance, seed: u64| episode(task, &yes, seed, TraceLevel::Full);
        // EvolvedLocomotion: the votes counted are random, so "passable" is no longer unanimous
        let locomotion = Affordance {
            evolved: Evolved::Locomotion,
            ..task.clone()
        };
        let o = run(&locomotion, 3);
        let (left, impassable) = (o.metric("sensing-passable-left"), o.metric("sensing-impassable"));
        assert!(left < 1.0 && impassable > 0.0, "{:?}", o.metrics);
        let votes = o.trace.as_ref().unwrap().at(VOTE.name, 1).unwrap();
        assert!(votes.iter().all(|v| (-1.0..=1.0).contains(v)) && votes.iter().any(|&v| v < 0.0));
        assert_eq!(run(&locomotion, 3).metrics, o.metrics, "the same seed, the same noise");
        assert_ne!(run(&locomotion, 4).metrics, o.metrics);
        // the actuation is untouched: the distances are those of the treatment
        let both = run(&task, 3);
        assert_eq!(o.metric("locomotion"), both.metric("locomotion"));
        assert_eq!(both.metric("sensing-passable-left"), 1.0);
        // EvolvedAffordance: a robot that never actuates is shaken by random temperatures
        let affordance = Affordance {
            evolved: Evolved::Affordance,
            ..task.clone()
        };
        let o = run(&affordance, 3);
        let actuation = o.trace.as_ref().unwrap().at(ACTUATION.name, 1).unwrap();
        assert!(actuation.iter().any(|a| a.abs() > 0.1), "{actuation:?}");
        assert_eq!(both.trace.as_ref().unwrap().at(ACTUATION.name, 1).unwrap(), [0.0; 12]);
        assert_ne!(o.metric("locomotion"), both.metric("locomotion"));
        assert_eq!(o.metric("sensing-passable-left"), 1.0, "the votes are the network's");
    }

    #[test]
    fn random_worlds_are_drawn_from_the_seed() {
        let task = Affordance {
            duration: 0.02,
            worlds: Worlds::Random,
            ..Affordance::default()
        };
        let robot = voter("3d:starfish", 10.0);
        let metrics = |seed: u64| {
            let o = episode(&task, &robot, seed, TraceLevel::Full);
            let walls = o.trace.unwrap().fixed_values(FIXED_VOXELS.name).to_vec();
            (o.metrics, walls)
        };
        let (a, walls_a) = metrics(1);
        assert_eq!(metrics(1), (a.clone(), walls_a.clone()));
        let differ = (2..6).filter(|&s| metrics(s).1 != walls_a).count();
        assert!(differ >= 3, "worlds change with the seed: {differ} of 4");
        // every random world builds for the flatworm, whose 5 × 5 body a knee wall would cross
        let flatworm = voter("3d:flatworm", 10.0);
        for seed in 0..40 {
            episode(&task, &flatworm, seed, TraceLevel::None);
        }
    }

    #[test]
    fn a_robot_that_never_reaches_the_wall_scores_0_and_distances_are_capped() {
        let task = Affordance {
            duration: 0.05,
            d_max: 0.01,
            ..Affordance::default()
        };
        let o = episode(&task, &voter("3d:flatworm", 10.0), 0, TraceLevel::None);
        assert_eq!(o.metric("sensing"), 0.0);
        // the flatworm starts 2 L voxels (8 cm) and more from its targets
        assert_eq!(o.metric("locomotion"), 0.01);
        assert_eq!(o.fitness, vec![0.01, 0.0]);
    }

    #[test]
    fn a_body_that_contracts_its_belly_flies_and_gets_the_worst_scores_when_flying_counts() {
        let task = Affordance {
            duration: 0.05,
            body_length: Some(2),
            flying: true,
            ..Affordance::default()
        };
        // contracted voxels lift their bottom faces off the floor at once
        let shrinking = biased("3d:###/###/###/###", -10.0, 10.0);
        let o = episode(&task, &shrinking, 0, TraceLevel::None);
        assert_eq!(
            (o.metric("locomotion"), o.metric("sensing")),
            (5.0, 0.0),
            "{:?}",
            o.metrics
        );
        // by default flying is not penalised (the original's rule never fires)
        let default = Affordance {
            flying: false,
            ..task.clone()
        };
        let o = episode(&default, &shrinking, 0, TraceLevel::None);
        assert!(o.metric("locomotion") < 0.1, "{:?}", o.metrics);
        let lenient = Affordance {
            penalties: false,
            ..task.clone()
        };
        let o = episode(&lenient, &shrinking, 0, TraceLevel::None);
        assert!(
            o.metric("locomotion") < 0.1 && o.metric("sensing-passable-left") == 1.0,
            "{:?}",
            o.metrics
        );
        // flying for less than `flying_seconds` is tolerated
        let patient = Affordance {
            flying_seconds: 1.0,
            ..task.clone()
        };
        let o = episode(&patient, &shrinking, 0, TraceLevel::None);
        assert!(o.metric("locomotion") < 0.1, "{:?}", o.metrics);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 8, ..Default::default() })]
        /// Random Elman weights on the study's shapes, in every treatment, fixed or random worlds:
        /// every metric is finite and the scores stay in their ranges.
        #[test]
        fn random_voters_give_finite_scores_in_range(
            shape in proptest::sample::select(vec!["3d:flatworm", "3d:starfish", "3d:gecko"]),
            weights in proptest::collection::vec(-3.0f64..3.0, 158),
            evolved in proptest::sample::select(vec![Evolved::Both, Evolved::Affordance, Evolved::Locomotion]),
            random in proptest::bool::ANY,
            seed in 0u64..1000,
        ) {
            let template = voter(shape, 0.0);
            let r = template.downcast_ref::<Voxel3dRobot>().unwrap();
            let robot = crate::AnyRobot::new(Voxel3dRobot {
                brain: BrainSpec::Elman(ElmanSpec { weights, ..ElmanSpec::default() }),
                ..r.clone()
            });
            let task = Affordance {
                duration: 0.04,
                evolved,
                worlds: if random { Worlds::Random } else { Worlds::Fixed },
                flying: true,
                ..Affordance::default()
            };
            let o = episode(&task, &robot, seed, TraceLevel::None);
            proptest::prop_assert!(o.metrics.values().all(|v| v.is_finite()), "{:?}", o.metrics);
            proptest::prop_assert!((0.0..=5.0).contains(&o.metric("locomotion")));
            proptest::prop_assert!((0.0..=1.0).contains(&o.metric("sensing")));
        }
    }

    #[test]
    fn a_voxel_above_the_wall_gets_the_worst_scores() {
        // a column three voxels high: its top centre (z = 2 voxels) is above the wall's top (1)
        let task = Affordance {
            duration: 0.02,
            body_length: Some(2),
            ..Affordance::default()
        };
        let tower = voter("3d:#|#|#", 10.0);
        let o = episode(&task, &tower, 0, TraceLevel::None);
        assert_eq!(
            (o.metric("locomotion"), o.metric("sensing")),
            (5.0, 0.0),
            "{:?}",
            o.metrics
        );
        let lenient = Affordance {
            penalties: false,
            ..task
        };
        let o = episode(&lenient, &tower, 0, TraceLevel::None);
        assert!(o.metric("locomotion") < 0.1, "{:?}", o.metrics);
    }

    #[test]
    fn a_batch_refills_the_lanes_of_robots_that_fail_and_each_keeps_its_own_evaluation() {
        // 11 robots of one body in 8 (or 4) lanes; four have brains that do not vote, whose
        // episodes fail at their first step: their lanes go to the robots still waiting
        let mut robots = random_elmans("3d:starfish", 1..12);
        let phase = from_short_forms(&RobotArgs {
            body: "3d:starfish",
            brain: Some("phase"),
            sensors: None,
            preset: None,
        })
        .unwrap();
        let phase = phase.downcast_ref::<Voxel3dRobot>().unwrap().brain.clone();
        for i in [0, 4, 5, 9] {
            robots[i].brain = phase.clone();
        }
        let refs: Vec<&dyn Robot> = robots.iter().map(|r| r as &dyn Robot).collect();
        assert!(prepare_batch(&refs, "the affordance task").is_some(), "one batch");
        let task = Affordance {
            duration: 0.04,
            ..Affordance::default()
        };
        let seeds: Vec<u64> = (20..31).collect();
        let batch = task.run_episodes(&refs, &seeds);
        let mut failed = 0;
        for (i, ((robot, &seed), laned)) in refs.iter().zip(&seeds).zip(&batch).enumerate() {
            let alone = task.run_episode(*robot, seed, TraceLevel::None, &mut |_, _| {});
            match (alone, laned) {
                (Ok(alone), Ok(laned)) => {
                    for (name, value) in &alone.metrics {
                        assert_eq!(laned.metrics[name].to_bits(), value.to_bits(), "robot {i}, {name}");
                    }
                }
                (Err(alone), Err(laned)) => {
                    assert_eq!(alone.to_string(), laned.to_string(), "robot {i}");
                    failed += 1;
                }
                (alone, laned) => panic!("robot {i}: alone {alone:?}, in lanes {laned:?}"),
            }
        }
        assert_eq!(failed, 4);
    }

    #[test]
    fn brains_that_do_not_vote_and_bad_settings_are_refused_naming_the_field() {
        let phase = from_short_forms(&RobotArgs {
            body: "3d:flatworm",
            brain: Some("phase"),
            sensors: None,
            preset: None,
        })
        .unwrap();
        let e = Affordance::default()
            .run_episode(phase.as_robot(), 0, TraceLevel::None, &mut |_, _| {})
            .unwrap_err();
        assert!(
            e.to_string().starts_with("robot.brain") && e.to_string().contains("vote"),
            "{e}"
        );
        let err = |t: Affordance| t.validate().unwrap_err().to_string();
        assert!(err(Affordance {
            environments: vec![],
            ..Default::default()
        })
        .starts_with("task.environments"));
        assert!(err(Affordance {
            body_length: Some(1),
            ..Default::default()
        })
        .starts_with("task.body_length"));
        assert!(err(Affordance {
            d_max: f64::NAN,
            ..Default::default()
        })
        .starts_with("task.d_max"));
        // a body too deep for its length reaches the wall
        let long = Affordance {
            body_length: Some(2),
            ..Affordance::default()
        };
        let e = long
            .run_episode(
                voter("3d:#/#/#/#/#", 1.0).as_robot(),
                0,
                TraceLevel::None,
                &mut |_, _| {},
            )
            .unwrap_err();
        assert!(e.to_string().starts_with("task.body_length"), "{e}");
    }
}
