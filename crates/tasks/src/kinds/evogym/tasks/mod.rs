//! EvoGym's tasks, one module each: its world, where the robot starts, how long an episode
//! lasts, what is observed, the reward and what ends an episode ([`TaskDefinition`]). Every task
//! is listed once, in [`EvoGymTask::ALL`]: a new task is one module (its world included, built
//! with `worlds.rs`'s layout helpers), its `mod` line and its line there. Sources
//! (commit `f63c649`): `evogym/envs/__init__.py` (names, episode lengths) and the task classes of
//! `evogym/envs/*.py`; `docs/evogym-envs.md` has the details of each task and where the thesis
//! differs, `docs/evogym-tasks-reference.md` the facts of all 32.

mod balancer;
mod beam_toppler;
mod bidirectional_walker;
mod bridge_walker;
mod catcher;
mod cave_crawler;
mod climber;
mod flipper;
mod jumper;
mod package;
mod shape;
mod stairs;
mod walker;

use super::rewards::{Reward, RobotAndBeam};
use super::worlds::World;
use std::fmt;
use std::hash::{Hash, Hasher};

/// How far the floor and ceiling observations look, in cells: a bin is empty, or farther, at
/// this distance (`base.py:281`, default `sight_range = 5`; a task's sight, the bins each side,
/// is its own).
pub const SIGHT_RANGE: f64 = 5.0;

/// Cells seen to each side by CaveCrawler's floor and ceiling observations, and how far
/// (`walk.py:179`).
pub const CAVE_SIGHT: (usize, f64) = (5, SIGHT_RANGE);

/// One piece of a task's observation, in the order the task lists them (simulator units).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece {
    /// The robot's mean velocity (x, y) (`base.py:236`).
    RobotVelocity,
    /// The robot's orientation since the start (`observe::Orientation`, `base.py:264`).
    RobotOrientation,
    /// Each robot point minus the robot's centre: all x, then all y (`base.py:250`): 2 per point.
    RobotPositions,
    /// The task's object's centre minus the robot's (x, y).
    ObjectOffset,
    /// The task's object's mean velocity (x, y).
    ObjectVelocity,
    /// The task's object's orientation since the start.
    ObjectOrientation,
    /// Distances down to the other objects, this many bins each side of the robot's centre
    /// (`observe::terrain_distances`, `base.py:276`).
    Floor(usize),
    /// Distances up to the other objects, this many bins each side (`base.py:329`).
    Ceiling(usize),
    /// [`Piece::Floor`] with vsrlab's first arithmetic for the centre
    /// (`observe::Centre::MeanFirst`), kept for CaveCrawler-v0, whose ch. 5.2 results used it.
    FloorMeanFirst(usize),
    /// [`Piece::Ceiling`] with vsrlab's first arithmetic, kept for CaveCrawler-v0.
    CeilingMeanFirst(usize),
    /// This many values the task writes itself ([`TaskDefinition::observe`]: a goal).
    Task(usize),
}

impl Piece {
    /// Values this piece adds for a robot of `robot_points` points.
    pub fn size(self, robot_points: usize) -> usize {
        match self {
            Piece::RobotVelocity | Piece::ObjectOffset | Piece::ObjectVelocity => 2,
            Piece::RobotOrientation | Piece::ObjectOrientation => 1,
            Piece::RobotPositions => 2 * robot_points,
            Piece::Floor(sight)
            | Piece::Ceiling(sight)
            | Piece::FloorMeanFirst(sight)
            | Piece::CeilingMeanFirst(sight) => 2 * sight + 1,
            Piece::Task(n) => n,
        }
    }
}

/// The observation of the tasks about a free object (BeamToppler-v0, BeamSlider-v0, Catcher-v0):
/// the object's centre minus the robot's, both centre velocities, the object's orientation, then
/// the robot's relative positions (`manipulate.py:636-645`).
pub const OBJECT_THEN_ROBOT: &[Piece] = &[
    Piece::ObjectOffset,
    Piece::RobotVelocity,
    Piece::ObjectVelocity,
    Piece::ObjectOrientation,
    Piece::RobotPositions,
];

/// What every task states: its names, its world, where the robot starts and how long an episode
/// lasts.
#[derive(Debug, Clone, Copy)]
pub struct Basics {
    /// EvoGym's registered name (`Walker-v0`).
    pub name: &'static str,
    /// Its short name on vsrlab's command line (`walker`).
    pub short_name: &'static str,
    /// Its world, without the robot.
    pub world: fn() -> World,
    /// Cell of the robot's bottom-left corner.
    pub robot_origin: (usize, usize),
    /// Steps per episode (`max_episode_steps`).
    pub episode_steps: usize,
}

/// What makes an EvoGym task: implemented once per task, in its own module.
pub trait TaskDefinition: Sync {
    /// Its names, world, start cell and episode length.
    fn basics(&self) -> &Basics;

    /// The object besides the robot whose centre the reward or the observation reads (the
    /// beam), if any.
    fn object(&self) -> Option<&'static str> {
        None
    }

    /// The observation, piece by piece.
    fn observation(&self) -> &'static [Piece];

    /// How many worlds the task's episodes start in: 1 for a task whose world is always
    /// `Basics::world`; Catcher-v0 places its package and pegs at random, in one of 66.
    fn world_count(&self) -> usize {
        1
    }

    /// World `index` (below [`TaskDefinition::world_count`]), without the robot.
    fn world_at(&self, index: usize) -> World {
        let _ = index;
        (self.basics().world)()
    }

    /// The world (its index) of the episode whose seed is `seed`: 0 unless the task draws it.
    fn world_of(&self, seed: u64) -> usize {
        let _ = seed;
        0
    }

    /// The task's own measure of the robot's shape (its points' `xs` and `ys`), read before and
    /// after every step into [`RobotAndBeam::own`]: the hull's area, a span. 0 by default.
    fn measure(&self, xs: &[f64], ys: &[f64]) -> f64 {
        let _ = (xs, ys);
        0.0
    }

    /// The task's numbers kept across an episode's steps (`memory`), set at reset from the
    /// episode's seed: by default one 0 (Flipper counts whole turns in it);
    /// BidirectionalWalker draws its goals.
    fn start(&self, seed: u64, memory: &mut Vec<f64>) {
        let _ = seed;
        memory.clear();
        memory.push(0.0);
    }

    /// The values of [`Piece::Task`], from the measures now and the memory (before this step's
    /// reward changes it, as EvoGym writes the observation first).
    fn observe(&self, now: RobotAndBeam, memory: &[f64], out: &mut [f64]) {
        let _ = (now, memory);
        out.fill(0.0);
    }

    /// A step's reward and whether the task ends the episode (besides instability, which ends
    /// every task), from the measures before and after the step (equal when unstable: EvoGym
    /// reads the last stable snapshot), and the task's memory ([`TaskDefinition::start`]).
    fn reward(&self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, memory: &mut [f64]) -> Reward;
}

/// One of EvoGym's tasks: a handle on its [`TaskDefinition`], compared and hashed by name.
#[derive(Clone, Copy)]
pub struct EvoGymTask(&'static dyn TaskDefinition);

#[allow(non_upper_case_globals)]
impl EvoGymTask {
    /// Walker-v0: walk right on flat ground.
    pub const Walker: EvoGymTask = EvoGymTask(&walker::Walker);
    /// BridgeWalker-v0: walk right on a soft bridge.
    pub const BridgeWalker: EvoGymTask = EvoGymTask(&bridge_walker::BridgeWalker);
    /// BeamToppler-v0: push a beam off two pegs.
    pub const BeamToppler: EvoGymTask = EvoGymTask(&beam_toppler::BeamToppler);
    /// CaveCrawler-v0: crawl right through a low cave.
    pub const CaveCrawler: EvoGymTask = EvoGymTask(&cave_crawler::CaveCrawler);

    /// Every task, in EvoGym's registration order: the registry.
    pub const ALL: &'static [EvoGymTask] = &[
        EvoGymTask::Walker,
        EvoGymTask::BridgeWalker,
        EvoGymTask::CaveCrawler,
        EvoGymTask(&jumper::Jumper),
        EvoGymTask(&flipper::Flipper),
        EvoGymTask(&balancer::BALANCER_V0),
        EvoGymTask(&balancer::BALANCER_V1),
        EvoGymTask(&stairs::UP_STEPPER),
        EvoGymTask(&stairs::DOWN_STEPPER),
        EvoGymTask(&stairs::OBSTACLE_TRAVERSER_V0),
        EvoGymTask(&stairs::OBSTACLE_TRAVERSER_V1),
        EvoGymTask(&stairs::HURDLER),
        EvoGymTask(&stairs::GAP_JUMPER),
        EvoGymTask(&stairs::PLATFORM_JUMPER),
        EvoGymTask(&stairs::TRAVERSER),
        EvoGymTask(&package::LIFTER),
        EvoGymTask(&package::CARRIER_V0),
        EvoGymTask(&package::CARRIER_V1),
        EvoGymTask(&package::PUSHER_V0),
        EvoGymTask(&package::PUSHER_V1),
        EvoGymTask::BeamToppler,
        EvoGymTask(&package::BEAM_SLIDER),
        EvoGymTask(&package::THROWER),
        EvoGymTask(&catcher::Catcher),
        EvoGymTask(&shape::AREA_MAXIMIZER),
        EvoGymTask(&shape::AREA_MINIMIZER),
        EvoGymTask(&shape::WINGSPAN_MAXIMIZER),
        EvoGymTask(&shape::HEIGHT_MAXIMIZER),
        EvoGymTask(&climber::CLIMBER_V0),
        EvoGymTask(&climber::CLIMBER_V1),
        EvoGymTask(&climber::Climber2),
        EvoGymTask(&bidirectional_walker::BidirectionalWalker),
    ];

    /// The task named `name`: EvoGym's name in any case (`BridgeWalker-v0`, `bridgewalker-v0`)
    /// or the short name with or without the version (`bridge-walker`, `bridge-walker-v0`;
    /// `balancer-v1`).
    pub fn from_name(name: &str) -> Option<EvoGymTask> {
        let short = name.strip_suffix("-v0").unwrap_or(name);
        EvoGymTask::ALL.iter().copied().find(|t| {
            t.name().eq_ignore_ascii_case(name)
                || t.short_name().eq_ignore_ascii_case(short)
                || t.short_name().eq_ignore_ascii_case(name)
        })
    }

    /// The error for a task name that [`EvoGymTask::from_name`] does not know, listing those it
    /// does.
    pub fn unknown(name: &str) -> String {
        let known: Vec<&str> = EvoGymTask::ALL.iter().map(|t| t.name()).collect();
        format!("unknown EvoGym task '{name}': expected one of {}", known.join(", "))
    }

    /// EvoGym's name (`Walker-v0`, …).
    pub fn name(self) -> &'static str {
        self.0.basics().name
    }

    /// Its short name on vsrlab's command line (`walker`, `bridge-walker`, …).
    pub fn short_name(self) -> &'static str {
        self.0.basics().short_name
    }

    /// Its world, without the robot (the first episode's, seed 0, for a task that draws it).
    pub fn world(self) -> World {
        self.world_at(self.world_of(0))
    }

    /// How many worlds its episodes start in ([`TaskDefinition::world_count`]).
    pub fn world_count(self) -> usize {
        self.0.world_count()
    }

    /// World `index`, without the robot ([`TaskDefinition::world_at`]).
    pub fn world_at(self, index: usize) -> World {
        self.0.world_at(index)
    }

    /// The world of the episode with seed `seed` ([`TaskDefinition::world_of`]).
    pub fn world_of(self, seed: u64) -> usize {
        self.0.world_of(seed)
    }

    /// Cell of the robot's bottom-left corner.
    pub fn robot_origin(self) -> (usize, usize) {
        self.0.basics().robot_origin
    }

    /// Steps per episode (`max_episode_steps`).
    pub fn episode_steps(self) -> usize {
        self.0.basics().episode_steps
    }

    /// The object besides the robot that the task reads, if any.
    pub fn object(self) -> Option<&'static str> {
        self.0.object()
    }

    /// The observation, piece by piece.
    pub fn observation(self) -> &'static [Piece] {
        self.0.observation()
    }

    /// Observation length for a robot of `robot_points` points.
    pub fn observation_size(self, robot_points: usize) -> usize {
        self.observation().iter().map(|p| p.size(robot_points)).sum()
    }

    /// The task's own measure of the robot's shape ([`TaskDefinition::measure`]).
    pub fn measure(self, xs: &[f64], ys: &[f64]) -> f64 {
        self.0.measure(xs, ys)
    }

    /// The task's memory at reset ([`TaskDefinition::start`]).
    pub fn start(self, seed: u64, memory: &mut Vec<f64>) {
        self.0.start(seed, memory)
    }

    /// The values of [`Piece::Task`] ([`TaskDefinition::observe`]).
    pub fn observe(self, now: RobotAndBeam, memory: &[f64], out: &mut [f64]) {
        self.0.observe(now, memory, out)
    }

    /// A step's reward and whether the task ends the episode ([`TaskDefinition::reward`]).
    pub fn reward(self, before: RobotAndBeam, after: RobotAndBeam, unstable: bool, memory: &mut [f64]) -> Reward {
        self.0.reward(before, after, unstable, memory)
    }
}

impl PartialEq for EvoGymTask {
    fn eq(&self, other: &EvoGymTask) -> bool {
        self.name() == other.name()
    }
}

impl Eq for EvoGymTask {}

impl Hash for EvoGymTask {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.name().hash(state);
    }
}

impl fmt::Debug for EvoGymTask {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_are_unique() {
        for &t in EvoGymTask::ALL {
            assert_eq!(EvoGymTask::from_name(t.name()), Some(t));
            assert_eq!(EvoGymTask::from_name(t.short_name()), Some(t), "{t:?}");
            let same = EvoGymTask::ALL
                .iter()
                .filter(|o| o.name() == t.name() || o.short_name() == t.short_name());
            assert_eq!(same.count(), 1, "{t:?}");
        }
        assert_eq!(EvoGymTask::from_name("Walker-v1"), None);
        assert_eq!(
            EvoGymTask::from_name("balancer-v1").map(|t| t.name()),
            Some("Balancer-v1")
        );
    }

    /// EvoGym's own first 50 steps of a full 5 × 5 body of horizontal actuators, every action
    /// 1.0 (docs/evogym-tasks-reference.md §6, measured with EvoGym 2.0's `gym.make`): the summed
    /// reward to the six decimals printed there, and no episode ends before. Not CaveCrawler-v0
    /// or Hurdler-v0: their robots fall (one and three cells) onto the floor and then rest, so
    /// their 50-step sums (EvoGym −0.000610 and −0.003760, vsrlab −0.002591 and −0.001351) are
    /// the sideways drift of a symmetric body at rest, set by rounding (both under 3e-4 per
    /// step); with a gait their episodes agree within 0.1 % and 0.22 % (docs/evogym-envs.md).
    /// Nor Flipper-v0, whose reward is the change of the robot's orientation: its orientation
    /// at reset, where the body has its start shape and should read 0, is rounding (EvoGym
    /// 0.000617, vsrlab 0.000077: points whose unit vectors' dot rounds above 1 read acos(0.99999));
    /// its first step's reward, and so every sum, differs by that 0.00054.
    #[test]
    fn fifty_steps_of_a_full_body_sum_to_evogyms_rewards() {
        use crate::kinds::evogym::{EvoGymEnv, MaterialGrid};
        let body = MaterialGrid::from_rows("33333/33333/33333/33333/33333").unwrap();
        let evogym = [
            ("Walker-v0", 0.006405),
            ("BeamToppler-v0", 0.055659),
            ("Jumper-v0", -0.059703),
            ("Balancer-v0", -0.007735),
            ("Balancer-v1", -0.009900),
            ("Climber-v0", -0.001512),
            ("Climber-v1", -0.001438),
            ("UpStepper-v0", -0.002571),
            ("DownStepper-v0", -0.004461),
            ("ObstacleTraverser-v0", 0.006405),
            ("ObstacleTraverser-v1", 0.036173),
            ("GapJumper-v0", 0.006619),
            ("PlatformJumper-v0", 0.006619),
            ("Climber-v2", -0.001531),
            ("AreaMaximizer-v0", -0.011549),
            ("AreaMinimizer-v0", 0.011549),
            ("WingspanMazimizer-v0", 0.001572),
            ("HeightMaximizer-v0", -0.003275),
            ("Lifter-v0", -0.177975),
            ("Carrier-v0", 0.011824),
            ("Carrier-v1", -0.002465),
            ("Pusher-v0", 0.009607),
            ("Pusher-v1", -0.000000),
            ("BeamSlider-v0", 0.006405),
            ("Thrower-v0", 0.014746),
            ("Traverser-v0", 0.006405),
        ];
        for (name, expected) in evogym {
            let task = EvoGymTask::from_name(name).unwrap();
            let mut env = EvoGymEnv::new(task, &body).unwrap();
            let mut total = 0.0;
            for step in 0..50 {
                let r = env.step(&[1.0; 25]).unwrap();
                assert!(!r.done && !r.truncated, "{name} ended at step {step}");
                total += r.reward;
            }
            assert!(
                (total - expected).abs() <= 0.5e-6,
                "{name}: {total:.9} against EvoGym's {expected}"
            );
        }
    }

    /// The floor (or ceiling) bins of the first observation of a full 5 × 5 body, EvoGym's
    /// (reference sheet §6, measured with `gym.make`): at reset the centre sits on a bin border,
    /// and only EvoGym's arithmetic (`observe::Centre::EvoGym`) puts the border points in its bins.
    #[test]
    fn first_floor_bins_are_evogyms() {
        use crate::kinds::evogym::{EvoGymEnv, MaterialGrid};
        let body = MaterialGrid::from_rows("33333/33333/33333/33333/33333").unwrap();
        let (h, t) = (0.5, 0.25);
        let evogym: [(&str, &[f64]); 10] = [
            ("Jumper-v0", &[h; 5]),
            ("UpStepper-v0", &[h, h, h, h, h, t, h, h, t, h, h]),
            ("DownStepper-v0", &[h, h, h, h, h, 0.35, h, h, 0.35, h, h]),
            ("ObstacleTraverser-v0", &[h, h, h, h, t, h, h, t, h, h, h]),
            ("ObstacleTraverser-v1", &[h, h, h, h, t, h, h, 0.35, h, h, h]),
            ("Hurdler-v0", &[h; 11]),
            ("GapJumper-v0", &[h, h, h, h, h, t, h, h, t, h, h]),
            ("PlatformJumper-v0", &[h, h, h, h, h, t, h, h, t, h, h]),
            ("Traverser-v0", &[h, h, h, h, h, t, h, h, t, h, h]),
            ("Climber-v2", &[h, h, h, h, h, h, 0.05]),
        ];
        for (name, bins) in evogym {
            let env = EvoGymEnv::new(EvoGymTask::from_name(name).unwrap(), &body).unwrap();
            let o = env.observation();
            let tail = &o[o.len() - bins.len()..];
            let close = tail.iter().zip(bins).all(|(a, b)| (a - b).abs() < 1e-12);
            assert!(close, "{name}: {tail:?} against EvoGym's {bins:?}");
        }
    }

    /// The laid-out worlds have the files' cell counts (docs/evogym-tasks-reference.md §3, §5):
    /// Jumper 60 + 2 × 7 = 74 fixed; Balancer-v0 30 + 3 × 2 + 2 × 2 = 40, v1 41; Climber-v0
    /// 7 + 2 × 88 + 7 = 190; Climber-v1 42 soft and 108 fixed.
    #[test]
    fn laid_out_worlds_have_the_files_cells() {
        use crate::kinds::evogym::{Material, World};
        use std::collections::BTreeSet;
        let world = |name: &str| EvoGymTask::from_name(name).unwrap().world();
        let count =
            |w: &World, name: &str, m: Material| w.object(name).unwrap().grid.present().filter(|c| c.2 == m).count();
        assert_eq!(count(&world("Jumper-v0"), "ground", Material::Fixed), 74);
        assert_eq!(count(&world("Balancer-v0"), "ground", Material::Fixed), 40);
        assert_eq!(count(&world("Balancer-v1"), "ground", Material::Fixed), 41);
        assert_eq!(count(&world("Climber-v0"), "pipe", Material::Fixed), 190);
        let c = world("Climber-v1");
        assert_eq!(
            (count(&c, "pipe", Material::Soft), count(&c, "pipe", Material::Fixed)),
            (42, 108)
        );
        let pole: BTreeSet<_> = world("Balancer-v1").object("ground").unwrap().world_cells().collect();
        assert!(pole.contains(&(17, 3)) && !pole.contains(&(17, 4)) && pole.contains(&(29, 4)));
        // ObstacleTraverser-v1's ground has 195 cells (reference sheet §3.5)
        assert_eq!(count(&world("ObstacleTraverser-v1"), "ground", Material::Fixed), 195);
        let names = |w: &World| w.objects().iter().map(|o| o.name.clone()).collect::<Vec<_>>();
        assert_eq!(names(&world("GapJumper-v0")).len(), 5);
        assert_eq!(names(&world("PlatformJumper-v0"))[6], "platform_7");
        let every = [
            world("Jumper-v0"),
            world("Balancer-v0"),
            world("Balancer-v1"),
            world("Climber-v0"),
            c,
            world("Climber-v2"),
            world("UpStepper-v0"),
            world("DownStepper-v0"),
            world("ObstacleTraverser-v0"),
            world("ObstacleTraverser-v1"),
            world("Hurdler-v0"),
            world("GapJumper-v0"),
            world("PlatformJumper-v0"),
        ];
        for w in every {
            assert!(w.objects().iter().all(|o| o.grid.is_connected()), "{:?}", names(&w));
        }
    }

    /// A full 5 × 5 robot has 36 points: Walker 2 + 72 = 74, BridgeWalker 75, BeamToppler 79,
    /// CaveCrawler 2 + 72 + 22 = 96 (the sizes EvoGym's `gym.make` gives, docs/evogym-envs.md).
    #[test]
    fn observation_sizes_for_36_points() {
        let tasks = [
            EvoGymTask::Walker,
            EvoGymTask::BridgeWalker,
            EvoGymTask::BeamToppler,
            EvoGymTask::CaveCrawler,
        ];
        assert_eq!(tasks.map(|t| t.observation_size(36)), [74, 75, 79, 96]);
    }
}
