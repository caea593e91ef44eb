//! [`EvoGymEnv`]: one of EvoGym's tasks with one robot, stepped with actions and answering with
//! observations and rewards as EvoGym's Python environments do (`evogym/envs/base.py`,
//! `walk.py`, `manipulate.py`, commit `f63c649`), over [`vsrlab_physics::mass_spring`].

use super::assemble::plan_object;
use super::error::EvoGymError;
use super::grid::MaterialGrid;
use super::observe::{mean, relative_positions, terrain_distances, Centre, Look, Orientation};
use super::rewards::RobotAndBeam;
use super::tasks::{EvoGymTask, Piece, SIGHT_RANGE};
use super::worlds::WorldObject;
use std::ops::Range;
use vsrlab_physics::mass_spring::{MassSpringBuilder, MassSpringError, MassSpringSettings, MassSpringWorld};

/// What one [`EvoGymEnv::step`] returns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepResult<'a> {
    /// The observation after the step (after an unstable step, the one before it, as EvoGym
    /// reads the last stable snapshot).
    pub observation: &'a [f64],
    /// The step's reward.
    pub reward: f64,
    /// The episode ended: unstable, or the task ended it (its goal, or a fall or flip in the
    /// tasks that have them) (gym's `terminated`).
    pub done: bool,
    /// The episode reached its length (gym's `truncated` from `max_episode_steps`).
    pub truncated: bool,
    /// The robot folded into itself or the state became non-finite; the reward carries the
    /// −3 penalty.
    pub unstable: bool,
}

/// An EvoGym task with one robot. Deterministic: the same robot and actions give the same
/// observations and rewards, bit for bit. `step` allocates nothing.
#[derive(Debug, Clone)]
pub struct EvoGymEnv {
    task: EvoGymTask,
    /// The robot, for building the world of a task that draws it at reset.
    grid: MaterialGrid,
    /// Which of the task's worlds `start` is ([`EvoGymTask::world_of`]).
    world_index: usize,
    /// The episode's start, and where the robot and the objects are.
    start: Start,
    world: MassSpringWorld,
    /// The task's numbers kept across the episode (`TaskDefinition::start`).
    memory: Vec<f64>,
    actions: usize,
    observation: Vec<f64>,
    steps: usize,
    over: bool,
}

/// An episode's start: the task's world with the robot, built, and where its parts are.
#[derive(Debug, Clone)]
struct Start {
    world: MassSpringWorld,
    robot: Range<usize>,
    /// The task's object (`TaskDefinition::object`), empty without one.
    object: Range<usize>,
    /// Every point but the robot's: what the floor and ceiling observations see.
    others: Range<usize>,
    robot_orientation: Option<Orientation>,
    object_orientation: Option<Orientation>,
}

impl Start {
    /// World `index` of `task` with `robot` at the task's start cell. Refuses a robot that
    /// overlaps the world, or a world the engine refuses.
    fn build(task: EvoGymTask, robot: &MaterialGrid, index: usize) -> Result<Start, EvoGymError> {
        let mut world = task.world_at(index);
        world
            .add(WorldObject::new("robot", task.robot_origin(), robot.clone()))
            .map_err(EvoGymError::World)?;
        let mut builder = MassSpringBuilder::new(MassSpringSettings::evogym());
        // EvoGym loads robots first, then the other objects by name (`evogym/sim.py:49-59`).
        let placed_robot = plan_object(robot, task.robot_origin()).add_to(&mut builder, true);
        let mut object = 0..0;
        for o in world.objects().iter().filter(|o| o.name != "robot") {
            let placed = plan_object(&o.grid, o.origin).add_to(&mut builder, false);
            if task.object() == Some(o.name.as_str()) {
                object = placed.points();
            }
        }
        let world = builder.build().map_err(EvoGymError::Physics)?;
        let robot = placed_robot.points();
        let pieces = task.observation();
        let orientation = |piece: Piece, points: &Range<usize>| {
            pieces
                .contains(&piece)
                .then(|| Orientation::new(world.positions_x(), world.positions_y(), points.clone()))
        };
        Ok(Start {
            robot_orientation: orientation(Piece::RobotOrientation, &robot),
            object_orientation: orientation(Piece::ObjectOrientation, &object),
            others: robot.end..world.point_count(),
            world,
            robot,
            object,
        })
    }
}

impl EvoGymEnv {
    /// The task's world with `robot` at the task's start cell. Refuses an invalid robot
    /// (naming the field), one that overlaps the world (any of the worlds of a task that draws
    /// its world at every reset), or a world the engine refuses.
    pub fn new(task: EvoGymTask, robot: &MaterialGrid) -> Result<EvoGymEnv, EvoGymError> {
        robot.validate_robot().map_err(EvoGymError::Robot)?;
        let first = task.world_of(0);
        for index in (0..task.world_count()).filter(|&i| i != first) {
            Start::build(task, robot, index)?;
        }
        let start = Start::build(task, robot, first)?;
        let mut env = EvoGymEnv {
            task,
            grid: robot.clone(),
            world_index: first,
            world: start.world.clone(),
            actions: robot.actuator_count(),
            observation: vec![0.0; task.observation_size(start.robot.len())],
            start,
            memory: Vec::new(),
            steps: 0,
            over: false,
        };
        env.reset(0);
        Ok(env)
    }

    /// Back to the start; returns the first observation. `seed` sets what the task draws at
    /// reset (BidirectionalWalker's goals, Catcher's world); the other tasks have no
    /// randomness.
    pub fn reset(&mut self, seed: u64) -> &[f64] {
        let index = self.task.world_of(seed);
        if index != self.world_index {
            self.start =
                Start::build(self.task, &self.grid, index).expect("every world of the task was built by `new`");
            self.world_index = index;
        }
        self.world.clone_from(&self.start.world);
        self.steps = 0;
        self.task.start(seed, &mut self.memory);
        self.over = false;
        self.write_observation();
        &self.observation
    }

    /// One step of 30 physics substeps with `actions` (one per actuator voxel, in the robot's
    /// cell order: row-major from the top row; EvoGym's units, clipped into [0.6, 1.6]).
    pub fn step(&mut self, actions: &[f64]) -> Result<StepResult<'_>, EvoGymError> {
        let before = self.begin_step(actions)?;
        let physics = self.world.step(actions).map(|_| ());
        self.finish_step(before, physics)
    }

    /// The start of a step: refuses a step after the episode's end or bad actions; returns the
    /// centres before the step.
    pub(super) fn begin_step(&self, actions: &[f64]) -> Result<RobotAndBeam, EvoGymError> {
        if self.over {
            return Err(EvoGymError::EpisodeOver);
        }
        self.check(actions)?;
        Ok(self.centres())
    }

    /// The end of a step whose physics gave `physics` (the world stepped with the actions,
    /// alone or in lanes): reward, observation, the episode's end.
    pub(super) fn finish_step(
        &mut self,
        before: RobotAndBeam,
        physics: Result<(), MassSpringError>,
    ) -> Result<StepResult<'_>, EvoGymError> {
        let unstable = match physics {
            Ok(()) => false,
            Err(MassSpringError::SelfOverlap { .. } | MassSpringError::NonFinite { .. }) => true,
            Err(e) => return Err(EvoGymError::Physics(e)),
        };
        // EvoGym reads the snapshot of the last stable step: nothing moved when unstable.
        let after = if unstable { before } else { self.centres() };
        // EvoGym writes the observation before the reward (which may change the task's memory)
        if !unstable {
            self.write_observation();
        }
        let reward = self.task.reward(before, after, unstable, &mut self.memory);
        self.steps += 1;
        let truncated = self.steps >= self.task.episode_steps();
        let done = unstable || reward.ends;
        self.over = done || truncated;
        Ok(StepResult {
            observation: &self.observation,
            reward: reward.value,
            done,
            truncated,
            unstable,
        })
    }

    /// The world, for stepping in lanes.
    pub(super) fn world_mut(&mut self) -> &mut MassSpringWorld {
        &mut self.world
    }

    fn check(&self, actions: &[f64]) -> Result<(), EvoGymError> {
        if actions.len() != self.actions {
            return Err(EvoGymError::ActionCount {
                expected: self.actions,
                got: actions.len(),
            });
        }
        match actions.iter().position(|a| !a.is_finite()) {
            Some(index) => Err(EvoGymError::NonFiniteAction {
                index,
                value: actions[index],
            }),
            None => Ok(()),
        }
    }

    /// Centres of the robot and the task's object, and the robot's orientation, now.
    fn centres(&self) -> RobotAndBeam {
        let (xs, ys) = (self.world.positions_x(), self.world.positions_y());
        let centre = |r: &Range<usize>| {
            if r.is_empty() {
                (0.0, 0.0)
            } else {
                (mean(xs, r.clone()), mean(ys, r.clone()))
            }
        };
        let robot_angle = self
            .start
            .robot_orientation
            .as_ref()
            .map_or(0.0, |a| a.angle(xs, ys, self.start.robot.clone()));
        let r = self.start.robot.clone();
        RobotAndBeam {
            robot: centre(&self.start.robot),
            beam: centre(&self.start.object),
            robot_angle,
            own: self.task.measure(&xs[r.clone()], &ys[r]),
        }
    }

    /// Writes the task's observation of the current state, piece by piece.
    fn write_observation(&mut self) {
        let (xs, ys) = (self.world.positions_x(), self.world.positions_y());
        let (vx, vy) = (self.world.velocities_x(), self.world.velocities_y());
        let (r, b) = (self.start.robot.clone(), self.start.object.clone());
        let mut at = 0;
        for &piece in self.task.observation() {
            let size = piece.size(r.len());
            let o = &mut self.observation[at..at + size];
            at += size;
            match piece {
                Piece::RobotVelocity => o.copy_from_slice(&[mean(vx, r.clone()), mean(vy, r.clone())]),
                Piece::RobotOrientation => {
                    o[0] = self
                        .start
                        .robot_orientation
                        .as_ref()
                        .map_or(0.0, |a| a.angle(xs, ys, r.clone()))
                }
                Piece::RobotPositions => relative_positions(xs, ys, r.clone(), o),
                Piece::ObjectOffset => {
                    let (rc, bc) = (
                        (mean(xs, r.clone()), mean(ys, r.clone())),
                        (mean(xs, b.clone()), mean(ys, b.clone())),
                    );
                    o.copy_from_slice(&[bc.0 - rc.0, bc.1 - rc.1]);
                }
                Piece::ObjectVelocity => o.copy_from_slice(&[mean(vx, b.clone()), mean(vy, b.clone())]),
                Piece::ObjectOrientation => {
                    o[0] = self
                        .start
                        .object_orientation
                        .as_ref()
                        .map_or(0.0, |a| a.angle(xs, ys, b.clone()))
                }
                Piece::Task(_) => {
                    let now = RobotAndBeam {
                        robot: (mean(xs, r.clone()), mean(ys, r.clone())),
                        ..RobotAndBeam::default()
                    };
                    self.task.observe(now, &self.memory, o);
                }
                Piece::Floor(sight)
                | Piece::Ceiling(sight)
                | Piece::FloorMeanFirst(sight)
                | Piece::CeilingMeanFirst(sight) => {
                    let look = match piece {
                        Piece::Floor(_) | Piece::FloorMeanFirst(_) => Look::Floor,
                        _ => Look::Ceiling,
                    };
                    let centre = match piece {
                        Piece::Floor(_) | Piece::Ceiling(_) => Centre::EvoGym,
                        _ => Centre::MeanFirst,
                    };
                    let (t, range) = (self.start.others.clone(), (sight, SIGHT_RANGE));
                    terrain_distances(xs, ys, t, r.clone(), centre, range, look, o);
                }
            }
        }
    }

    /// The task.
    pub fn task(&self) -> EvoGymTask {
        self.task
    }

    /// Number of actions `step` takes: the robot's actuator voxels.
    pub fn action_count(&self) -> usize {
        self.actions
    }

    /// Length of the observation.
    pub fn observation_size(&self) -> usize {
        self.observation.len()
    }

    /// The current observation.
    pub fn observation(&self) -> &[f64] {
        &self.observation
    }

    /// Whether the episode is over (goal, instability or its length): `step` refuses until
    /// `reset`.
    pub fn is_over(&self) -> bool {
        self.over
    }

    /// Steps taken since the last reset.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// The task's numbers kept across the episode (`TaskDefinition::start`: BidirectionalWalker's
    /// current goal and its goals).
    pub fn task_memory(&self) -> &[f64] {
        &self.memory
    }

    /// The robot's material grid.
    pub fn robot_grid(&self) -> &MaterialGrid {
        &self.grid
    }

    /// The task's world this episode started in, without the robot (the one its seed drew, in
    /// a task that draws it).
    pub fn task_world(&self) -> super::worlds::World {
        self.task.world_at(self.world_index)
    }

    /// The physics world (positions, velocities, springs).
    pub fn world(&self) -> &MassSpringWorld {
        &self.world
    }

    /// World indices of the robot's points, in EvoGym's order.
    pub fn robot_points(&self) -> Range<usize> {
        self.start.robot.clone()
    }

    /// The robot's centre (mean of its points) now.
    pub fn robot_centre(&self) -> (f64, f64) {
        self.centres().robot
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    const FULL: &str = "33333/33333/33333/33333/33333";

    fn env(task: EvoGymTask, rows: &str) -> EvoGymEnv {
        EvoGymEnv::new(task, &MaterialGrid::from_rows(rows).unwrap()).unwrap()
    }

    fn all_finite(o: &[f64]) -> bool {
        o.iter().all(|v| v.is_finite())
    }

    #[test]
    fn observation_sizes_of_a_full_body() {
        let sizes: Vec<(&str, usize)> = EvoGymTask::ALL
            .iter()
            .map(|&t| {
                let e = env(t, FULL);
                assert_eq!(e.observation().len(), e.observation_size());
                (t.name(), e.observation_size())
            })
            .collect();
        // the sizes EvoGym's `gym.make` gives (docs/evogym-tasks-reference.md §4)
        let expected = [
            ("Walker-v0", 74),
            ("BridgeWalker-v0", 75),
            ("CaveCrawler-v0", 96),
            ("Jumper-v0", 79),
            ("Flipper-v0", 73),
            ("Balancer-v0", 73),
            ("Balancer-v1", 73),
            ("UpStepper-v0", 86),
            ("DownStepper-v0", 86),
            ("ObstacleTraverser-v0", 86),
            ("ObstacleTraverser-v1", 86),
            ("Hurdler-v0", 86),
            ("GapJumper-v0", 86),
            ("PlatformJumper-v0", 86),
            ("Traverser-v0", 86),
            ("Lifter-v0", 79),
            ("Carrier-v0", 78),
            ("Carrier-v1", 78),
            ("Pusher-v0", 78),
            ("Pusher-v1", 78),
            ("BeamToppler-v0", 79),
            ("BeamSlider-v0", 79),
            ("Thrower-v0", 78),
            ("Catcher-v0", 79),
            ("AreaMaximizer-v0", 72),
            ("AreaMinimizer-v0", 72),
            ("WingspanMazimizer-v0", 72),
            ("HeightMaximizer-v0", 72),
            ("Climber-v0", 74),
            ("Climber-v1", 74),
            ("Climber-v2", 82),
            ("BidirectionalWalker-v0", 77),
        ];
        assert_eq!(sizes, expected);
    }

    /// Catcher-v0 draws its world at reset from the seed: the same seed, the same package; a
    /// robot that would overlap a peg in any of its worlds is refused at once.
    #[test]
    fn a_drawn_world_follows_the_seed() {
        let task = EvoGymTask::from_name("Catcher-v0").unwrap();
        let mut e = env(task, FULL);
        let package = |e: &EvoGymEnv| mean(e.world().positions_x(), e.start.object.clone());
        let mut seen = Vec::new();
        for seed in 0..6 {
            e.reset(seed);
            let x = package(&e);
            assert!(all_finite(e.observation()));
            let fresh = env(task, FULL);
            let mut again = fresh.clone();
            again.reset(seed);
            assert_eq!(package(&again).to_bits(), x.to_bits(), "seed {seed}");
            assert_eq!(again.observation(), e.observation(), "seed {seed}");
            seen.push(x);
        }
        seen.sort_by(f64::total_cmp);
        seen.dedup();
        assert!(seen.len() > 1, "six seeds, one world: {seen:?}");
        let tall = vec!["3"; 30].join("/");
        let err = EvoGymEnv::new(task, &MaterialGrid::from_rows(&tall).unwrap()).unwrap_err();
        assert!(err.to_string().contains("overlap"), "{err}");
    }

    /// "31240/22222/00400": actuators 3, 4 (row 0) and 4 (row 2): three actions.
    #[test]
    fn one_action_per_actuator_voxel() {
        let e = env(EvoGymTask::Walker, "31240/22222/00400");
        assert_eq!(e.action_count(), 3);
        assert_eq!(e.world().actuator_count(), 3);
        assert_eq!(env(EvoGymTask::Walker, FULL).action_count(), 25);
    }

    /// A full 5 × 5 body at cell (1, 1): points at x = 0.1 … 0.6 and y = 0.1 … 0.6, six by six,
    /// so the centre is (0.35, 0.35); the first point (top-left, (0.1, 0.6)) is at (−0.25, 0.25)
    /// from it; velocities are zero.
    #[test]
    fn first_observation_by_hand() {
        let e = env(EvoGymTask::Walker, FULL);
        let (cx, cy) = e.robot_centre();
        assert!((cx - 0.35).abs() < 1e-12 && (cy - 0.35).abs() < 1e-12, "{cx} {cy}");
        let o = e.observation();
        assert_eq!(&o[..2], &[0.0, 0.0]);
        assert!((o[2] + 0.25).abs() < 1e-12 && (o[2 + 36] - 0.25).abs() < 1e-12);
        // Last point: bottom-right (0.6, 0.1).
        assert!((o[2 + 35] - 0.25).abs() < 1e-12 && (o[2 + 71] + 0.25).abs() < 1e-12);
    }

    /// The reward of a step is the robot centre's x after minus before, read independently
    /// from the world's points.
    #[test]
    fn reward_is_the_centres_x_gain() {
        let mut e = env(EvoGymTask::Walker, FULL);
        let points = e.robot_points();
        let x_mean = |e: &EvoGymEnv| {
            let xs = e.world().positions_x();
            points.clone().map(|i| xs[i]).sum::<f64>() / 36.0
        };
        let gait: Vec<f64> = (0..25).map(|i| if i % 5 < 2 { 1.6 } else { 0.6 }).collect();
        for _ in 0..20 {
            let before = x_mean(&e);
            let r = e.step(&gait).unwrap();
            let reward = r.reward;
            assert!(!r.unstable);
            assert!((reward - (x_mean(&e) - before)).abs() < 1e-15);
        }
    }

    /// With every action 1 (goal = rest length) the robot only settles: over a whole episode it
    /// stays within half a cell of its start, finite and stable; the episode is truncated at 500
    /// steps and refuses a 501st.
    #[test]
    fn constant_actions_stay_in_place_for_an_episode() {
        let mut e = env(EvoGymTask::Walker, FULL);
        let start = e.robot_centre();
        let ones = vec![1.0; 25];
        for k in 1..=500 {
            let r = e.step(&ones).unwrap();
            assert!(all_finite(r.observation) && !r.unstable && !r.done, "step {k}");
            assert_eq!(r.truncated, k == 500);
        }
        let end = e.robot_centre();
        assert!(
            (end.0 - start.0).abs() < 0.05 && (end.1 - start.1).abs() < 0.05,
            "{start:?} → {end:?}"
        );
        assert_eq!(e.step(&ones), Err(EvoGymError::EpisodeOver));
        e.reset(0);
        assert_eq!(e.steps(), 0);
        assert_eq!(e.robot_centre(), start);
    }

    /// A square wave of period 20 steps, phase shifted along the body, moves the robot.
    fn gait(t: usize) -> Vec<f64> {
        (0..25)
            .map(|i| if (t + 5 * (i % 5)) % 20 < 10 { 1.6 } else { 0.6 })
            .collect()
    }

    #[test]
    fn an_alternating_gait_moves() {
        let mut e = env(EvoGymTask::Walker, FULL);
        let start = e.robot_centre().0;
        let mut total = 0.0;
        for t in 0..200 {
            let r = e.step(&gait(t)).unwrap();
            assert!(!r.unstable, "step {t}");
            total += r.reward;
        }
        let moved = e.robot_centre().0 - start;
        assert!((total - moved).abs() < 1e-12);
        // Measured: +0.405 (about 4 cells) in 200 steps.
        assert!(moved > 0.3, "moved {moved}");
    }

    #[test]
    fn every_task_steps_finite_and_deterministically() {
        for &task in EvoGymTask::ALL {
            let mut a = env(task, FULL);
            let mut b = env(task, FULL);
            for t in 0..20 {
                let ra = a.step(&gait(t)).unwrap();
                assert!(all_finite(ra.observation) && !ra.unstable, "{} step {t}", task.name());
                let (oa, rwa) = (ra.observation.to_vec(), ra.reward);
                let rb = b.step(&gait(t)).unwrap();
                assert_eq!(oa, rb.observation);
                assert_eq!(rwa.to_bits(), rb.reward.to_bits());
            }
        }
    }

    /// The beam (rows 5 and 6, centre y 0.6) rests on its pegs while the robot is far away.
    #[test]
    fn the_beam_rests_on_its_pegs() {
        let mut e = env(EvoGymTask::BeamToppler, FULL);
        let ones = vec![1.0; 25];
        for _ in 0..50 {
            e.step(&ones).unwrap();
        }
        let beam_y = mean(e.world().positions_y(), e.start.object.clone());
        assert!((beam_y - 0.6).abs() < 0.01, "{beam_y}");
        let o = e.observation();
        // Beam centre (3.4, 0.6) minus robot centre (≈ 0.35, ≈ 0.35).
        assert!(
            (o[0] - 3.05).abs() < 0.02 && (o[1] - 0.25).abs() < 0.02,
            "{:?}",
            &o[..2]
        );
    }

    #[test]
    fn wrong_robots_and_actions_are_refused() {
        let bad = MaterialGrid::from_rows("3.3").unwrap();
        let e = EvoGymEnv::new(EvoGymTask::Walker, &bad).unwrap_err();
        assert!(matches!(e, EvoGymError::Robot(ref f) if f.path == "cells"), "{e}");
        // 20 wide and 6 high from cell (1, 2) reaches (20, 7): CaveCrawler's terrain.
        let big = MaterialGrid::from_rows(&vec!["3".repeat(20); 6].join("/")).unwrap();
        let e = EvoGymEnv::new(EvoGymTask::CaveCrawler, &big).unwrap_err();
        assert!(
            matches!(e, EvoGymError::World(ref f) if f.message.contains("overlaps")),
            "{e}"
        );
        let mut e = env(EvoGymTask::Walker, "33");
        assert_eq!(e.step(&[1.0]), Err(EvoGymError::ActionCount { expected: 2, got: 1 }));
        assert!(matches!(
            e.step(&[1.0, f64::NAN]),
            Err(EvoGymError::NonFiniteAction { index: 1, .. })
        ));
    }

    /// Random 5 × 5 bodies of every material mix (codes 0–4, kept when EvoGym would accept them
    /// as robots) under random actions for up to 400 steps of every task: every observation is
    /// finite, and an episode ends early only at the task's end (goal, fall, flip) or as
    /// unstable with the −3 penalty.
    #[test]
    fn random_5x5_bodies_run_whole_episodes_of_every_task() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(33);
        let mut robots = Vec::new();
        while robots.len() < 3 {
            let cells = (0..25)
                .map(|_| super::super::Material::from_code(rng.random_range(0..=4u64)).unwrap())
                .collect();
            let grid = MaterialGrid::new(5, 5, cells).unwrap();
            if grid.validate_robot().is_ok() {
                robots.push(grid);
            }
        }
        let mut episodes = 0;
        for &task in EvoGymTask::ALL {
            for grid in &robots {
                let Ok(mut e) = EvoGymEnv::new(task, grid) else {
                    continue; // overlaps the task's terrain (CaveCrawler's ceiling)
                };
                episodes += 1;
                let n = e.action_count();
                let mut actions = vec![0.0; n];
                // the first 400 steps (Climber-v0's whole episode, with its truncation), to keep
                // the test's time as tasks are added
                for step in 1..=task.episode_steps().min(400) {
                    actions.iter_mut().for_each(|a| *a = rng.random_range(0.0..2.0));
                    let r = e.step(&actions).unwrap();
                    assert!(
                        all_finite(r.observation) && r.reward.is_finite(),
                        "{task:?} step {step}"
                    );
                    if r.unstable {
                        assert!(r.done && r.reward <= -2.0, "{task:?}: unstable ends with −3");
                    }
                    if r.done || r.truncated {
                        assert!(r.done || step == task.episode_steps());
                        break;
                    }
                }
            }
        }
        assert!(episodes >= 9, "only {episodes} episodes ran");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]

        /// Random grids of up to 4 × 4 cells (codes 0–4) with random actions: either refused as
        /// robots, or every step ends finite or reports instability.
        #[test]
        fn random_robots_never_produce_non_finite_observations(
            w in 1usize..=4,
            h in 1usize..=4,
            codes in prop::collection::vec(0u64..=4, 16),
            actions in prop::collection::vec(-1.0f64..3.0, 16 * 15),
        ) {
            let cells = codes[..w * h].iter().map(|&c| super::super::Material::from_code(c).unwrap()).collect();
            let grid = MaterialGrid::new(w, h, cells).unwrap();
            let Ok(mut e) = EvoGymEnv::new(EvoGymTask::Walker, &grid) else {
                prop_assert!(grid.validate_robot().is_err());
                return Ok(());
            };
            let n = e.action_count();
            for t in 0..15 {
                let r = e.step(&actions[t * n..(t + 1) * n]).unwrap();
                prop_assert!(all_finite(r.observation));
                if r.done {
                    prop_assert!(r.unstable && r.reward <= -2.0);
                    break;
                }
            }
        }
    }

    /// EvoGym 2.0.0's positions after one BridgeWalker-v0 step (robot 13231/34443/32023/33033/40004,
    /// every action 1.0; recorded with the venv of `bench/evogym`). A bridge point next to a fixed
    /// anchor sags as EvoGym's only if fixed points drift inside the RK4 stages; the robot's corner
    /// resting exactly on a bridge corner, and that bridge corner, move as EvoGym's only if the
    /// edge a point is pushed through is chosen in EvoGym's order (right before bottom).
    #[test]
    fn one_bridge_step_lands_where_evogym_puts_it() {
        let mut e = env(EvoGymTask::BridgeWalker, "13231/34443/32023/33033/40004");
        let w = e.world();
        let start: Vec<(f64, f64)> = w
            .positions_x()
            .iter()
            .copied()
            .zip(w.positions_y().iter().copied())
            .collect();
        let n = w.point_count();
        let actions = vec![1.0; e.action_count()];
        e.step(&actions).unwrap();
        let robot = e.robot_points();
        let find = |mut range: Range<usize>, x: f64, y: f64| {
            range
                .find(|&i| (start[i].0 - x).abs() < 1e-9 && (start[i].1 - y).abs() < 1e-9)
                .unwrap()
        };
        let recorded = [
            (find(robot.end..n, 1.2, 0.5), (1.200032593396046, 0.49963150357908914)),
            (find(robot.end..n, 0.3, 0.5), (0.3004274728303495, 0.4979007711389167)),
            (find(robot.clone(), 0.3, 0.5), (0.29844530933135816, 0.501714568086073)),
        ];
        let w = e.world();
        for (i, (x, y)) in recorded {
            let (dx, dy) = (w.positions_x()[i] - x, w.positions_y()[i] - y);
            assert!(
                dx.abs() < 1e-12 && dy.abs() < 1e-12,
                "point {i}: off EvoGym's by ({dx:e}, {dy:e})"
            );
        }
    }

    /// Two of the random bodies that EvoGym 2.0.0 ended as unstable under held extreme actions
    /// (`bench/evogym/instability.py`, runs 30 and 6: every actuator 0.6 or 1.6 from the action
    /// stream of the run's index, redrawn every 15 steps): vsrlab ends them at the same step with
    /// EvoGym's −3, and refuses another step.
    #[test]
    fn instability_ends_the_episode_at_the_step_evogym_does() {
        for (seed, body, evogym_step) in [
            (30, "24223/40044/30004/30434/30030", 42),
            (6, "03002/32434/04000/03042/04430", 62),
        ] {
            let mut e = env(EvoGymTask::Walker, body);
            let mut stream = super::super::ActionStream::new(seed);
            let mut actions = vec![0.0; e.action_count()];
            let mut ended = None;
            for t in 0..300 {
                if t % 15 == 0 {
                    stream.fill_extremes(&mut actions, 0.6, 1.6);
                }
                let r = e.step(&actions).unwrap();
                if r.unstable {
                    assert!(r.done && r.reward == -3.0, "{r:?}");
                    ended = Some(t + 1);
                    break;
                }
            }
            assert_eq!(ended, Some(evogym_step), "{body}");
            assert!(matches!(e.step(&actions), Err(EvoGymError::EpisodeOver)));
        }
    }
}
