//! A third robot kind written in this one file, touching no existing file: a ring of square
//! links joined by actuated springs, whose brain sees the links as a ring (`RingLayout`). It has
//! its own registry entry (`KIND`: name, command-line form, robot-file form), runs on a task
//! through the one episode loop with a distributed MLP that exchanges signals around the ring,
//! and its channels (its own and its brain's) are recorded, drawn and replayed like any kind's.
//! Registering it for the command line and the Python package would be one line in
//! `ROBOT_KINDS` (crates/tasks/src/kinds/mod.rs).

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use vsrlab_body::{Body, Probe, VoxelState};
use vsrlab_brain::{BrainShape, BrainSpec, Controller, RingLayout};
use vsrlab_physics::{PartDesc, PartHandle, Polygon, SpringDesc, SpringHandle, Vec2, World, WorldBuilder};
use vsrlab_render::replay::{Replay, ReplayOptions};
use vsrlab_render::{render_frame, RenderOptions};
use vsrlab_tasks::files::{self, FileError};
use vsrlab_tasks::kinds::{AnyRobot, RobotArgs, RobotDescription, RobotKind};
use vsrlab_tasks::{
    channels, episode, Agent, EpisodeError, Robot, RobotArgsError, RobotPart, TaskSpec, Trace, TraceLevel,
};
use vsrlab_tasks::{evaluate, BodyPart, BodySource, EvaluationError, FieldError, Representation};

/// The chain's registry entry.
const KIND: RobotKind = RobotKind {
    name: "chain",
    file_keys: &["chain"],
    body_usage: "chain:<links>",
    claims_body: |body| body.starts_with("chain:"),
    from_short_forms,
    from_file,
    body_tables: &["chain"],
    physics: || vsrlab_tasks::Locomotion::default().physics,
    foreign_formats: &[],
    decode_body,
};

/// The chain's `[representation] body` form: `{ kind = "chain", links = N }` (no body genes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ChainForm {
    kind: String,
    links: usize,
}

fn decode_body(value: serde_json::Value) -> Result<BodyPart, FieldError> {
    let body: ChainForm = serde_json::from_value(value).map_err(|e| FieldError::message(e.to_string()))?;
    if !(3..=50).contains(&body.links) {
        return Err(FieldError::new("links", format!("3 to 50, got {}", body.links)));
    }
    Ok(BodyPart::new(body))
}

impl BodySource for ChainForm {
    fn kind(&self) -> &'static RobotKind {
        &KIND
    }
    fn genes(&self) -> usize {
        0
    }
    fn brain_genes(&self, representation: &Representation) -> Result<usize, EvaluationError> {
        let chain = Chain {
            links: self.links,
            brain: representation.brain.clone(),
        };
        chain
            .brain
            .parameter_count(&chain.shape())
            .map_err(|e| EvaluationError::Representation(e.into()))
    }
    fn robot(&self, _: &Representation, _genes: &[f64], brain: BrainSpec) -> Result<AnyRobot, EvaluationError> {
        Ok(AnyRobot::new(Chain {
            links: self.links,
            brain,
        }))
    }
    fn size(&self) -> usize {
        self.links
    }
}

/// A ring of `links` square links; its brain takes 3 readings per link (touch, vx, vy).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Chain {
    links: usize,
    brain: BrainSpec,
}

const SIDE: f64 = 1.0;
const READINGS: usize = 3;

impl Chain {
    fn shape(&self) -> BrainShape {
        BrainShape::new(RingLayout::new(self.links, 0), vec![READINGS; self.links])
    }

    /// Where link i sits in the ring, relative to the ring's centre.
    fn offset(&self, i: usize) -> Vec2 {
        let radius = self.links as f64 * SIDE * 0.4;
        let a = 2.0 * PI * i as f64 / self.links as f64;
        Vec2::new(radius * a.cos(), radius * a.sin())
    }
}

fn from_short_forms(args: &RobotArgs) -> Result<AnyRobot, RobotArgsError> {
    let links = args
        .body
        .strip_prefix("chain:")
        .and_then(|n| n.parse().ok())
        .filter(|&n| (3..=50).contains(&n));
    let links = links.ok_or_else(|| RobotArgsError::Kind {
        part: RobotPart::Body,
        message: format!("'{}': expected chain:<3 to 50 links>", args.body),
    })?;
    let brain = BrainSpec::parse(args.brain.unwrap_or("distributed-mlp")).map_err(RobotArgsError::Brain)?;
    let mut chain = Chain { links, brain };
    chain.brain = chain
        .brain
        .with_random_parameters(0, &chain.shape())
        .map_err(RobotArgsError::Brain)?;
    Ok(AnyRobot::new(chain))
}

#[derive(Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct ChainFile {
    format: String,
    chain: Chain,
}

fn from_file(text: &str, origin: &str) -> Result<AnyRobot, FileError> {
    let file: ChainFile = files::parse_json(text, origin)?;
    files::check_format(&file.format, origin)?;
    Ok(AnyRobot::new(file.chain))
}

impl RobotDescription for Chain {
    fn kind(&self) -> &'static RobotKind {
        &KIND
    }
    fn brain(&self) -> &BrainSpec {
        &self.brain
    }
    fn to_json(&self, _note: Option<&str>) -> String {
        let file = ChainFile {
            format: files::ROBOT_FORMAT.into(),
            chain: self.clone(),
        };
        serde_json::to_string_pretty(&file).unwrap()
    }
    fn body_details(&self, actuators: usize) -> String {
        format!("{} links, {actuators} springs", self.links)
    }
    fn sensors_label(&self) -> String {
        "touch and velocity of each link".into()
    }
    fn preset_label(&self) -> String {
        "chain".into()
    }
    fn size(&self) -> usize {
        self.links
    }
    fn label(&self) -> String {
        format!("chain of {} links", self.links)
    }
    fn clone_box(&self) -> Box<dyn RobotDescription> {
        Box::new(self.clone())
    }
    fn as_any(&self) -> &dyn std::any::Any {
        self
    }
}

impl Robot for Chain {
    fn footprint(&self) -> Vec<Vec2> {
        let r = self.links as f64 * SIDE * 0.4 + SIDE;
        vec![Vec2::new(0.0, 0.0), Vec2::new(2.0 * r, 0.0)]
    }

    fn assemble(&self, builder: &mut WorldBuilder, origin: Vec2, _seed: u64) -> Result<Box<dyn Agent>, EpisodeError> {
        let centre = origin
            + Vec2::new(
                self.links as f64 * SIDE * 0.4 + SIDE,
                self.links as f64 * SIDE * 0.4 + SIDE,
            );
        let links: Vec<PartHandle> = (0..self.links)
            .map(|i| {
                let desc = PartDesc::new(centre + self.offset(i), Polygon::square(Vec2::ZERO, SIDE)).friction(1.0);
                builder.add_part(desc)
            })
            .collect();
        let rest = (self.offset(1) - self.offset(0)).length();
        let springs = (0..self.links)
            .map(|i| {
                let j = (i + 1) % self.links;
                builder.add_spring(SpringDesc {
                    part_a: links[i],
                    anchor_a: Vec2::ZERO,
                    part_b: links[j],
                    anchor_b: Vec2::ZERO,
                    rest_length: rest,
                    frequency: 8.0,
                    damping_ratio: 0.3,
                    mass_model: Default::default(),
                    collide_connected: false,
                })
            })
            .collect();
        let mut brain = self
            .brain
            .build(&self.shape())
            .map_err(|e| EpisodeError::Invalid(format!("robot.{e}")))?;
        brain.reset();
        Ok(Box::new(ChainAgent {
            body: ChainBody { links, springs, rest },
            brain,
            readings: vec![0.0; READINGS * self.links],
            actuations: vec![0.0; self.links],
        }))
    }
}

/// The links and springs in the world.
struct ChainBody {
    links: Vec<PartHandle>,
    springs: Vec<SpringHandle>,
    rest: f64,
}

/// The chain in its world: its body, its brain, and the buffers between them.
struct ChainAgent {
    body: ChainBody,
    brain: Box<dyn Controller>,
    readings: Vec<f64>,
    actuations: Vec<f64>,
}

impl Body for ChainBody {
    fn actuator_count(&self) -> usize {
        self.springs.len()
    }
    fn actuate(&self, world: &mut World, values: &[f64]) {
        for (&s, &a) in self.springs.iter().zip(values) {
            world.set_spring_rest_length(s, self.rest * (1.0 - 0.3 * a.clamp(-1.0, 1.0)));
        }
    }
    fn center(&self, world: &World) -> Vec2 {
        let sum = self.links.iter().fold(Vec2::ZERO, |s, &l| s + world.part_position(l));
        sum * (1.0 / self.links.len() as f64)
    }
    fn sensing_units(&self) -> usize {
        0
    }
    fn unit_state(&self, _world: &World, i: usize) -> VoxelState {
        unreachable!("the chain reads its links itself, not through unit {i}")
    }
    fn outline_corners(&self) -> Vec<usize> {
        vec![4; self.links.len()]
    }
    fn outline(&self, world: &World, out: &mut Vec<Vec2>) {
        let h = SIDE / 2.0;
        for &l in &self.links {
            for (x, y) in [(-h, h), (h, h), (h, -h), (-h, -h)] {
                out.push(world.part_point(l, Vec2::new(x, y)));
            }
        }
    }
}

impl Agent for ChainAgent {
    fn body(&self) -> &dyn Body {
        &self.body
    }
    fn act(&mut self, world: &mut World, t: f64) {
        self.sense(world, t);
        self.brain.control(t, &self.readings, &mut self.actuations);
        self.body.actuate(world, &self.actuations);
    }
    fn sense(&mut self, world: &World, _t: f64) {
        for (r, &l) in self.readings.chunks_mut(READINGS).zip(&self.body.links) {
            let v = world.part_velocity(l);
            r.copy_from_slice(&[f64::from(u8::from(world.part_touching(l))), v.x.tanh(), v.y.tanh()]);
        }
    }
    fn readings(&self) -> &[f64] {
        &self.readings
    }
    fn describe(&mut self, trace: &mut Trace) {
        trace.side_length = SIDE;
    }
    fn record(&self, trace: &mut Trace) {
        trace.step(&channels::ACTUATION, &self.actuations);
        let touch: Vec<f64> = self.readings.chunks(READINGS).map(|r| r[0]).collect();
        trace.step(&channels::TOUCH, &touch);
    }
    fn brain(&self) -> Option<&dyn Controller> {
        Some(self.brain.as_ref())
    }
}

fn args(body: &str) -> RobotArgs<'_> {
    RobotArgs {
        body,
        brain: None,
        sensors: None,
        preset: None,
    }
}

#[test]
fn a_third_kind_plugs_in_from_its_own_file() {
    let chain = (KIND.from_short_forms)(&args("chain:8")).unwrap();
    assert_eq!(chain.kind().name, "chain");
    // the brain is built on the ring: a distributed MLP with 2 neighbour directions per link
    // (3 readings + 2 signals in, 1 + 2 out: 3·6 = 18 weights)
    assert_eq!(chain.brain().parameters().len(), 18);
    // the robot file reads back through the kind's entry
    let again = (KIND.from_file)(&chain.to_json(None), "test").unwrap();
    assert_eq!(again, chain);
    assert!((KIND.from_short_forms)(&args("chain:1")).is_err_and(|e| e.part() == RobotPart::Body));

    let mut task = TaskSpec::parse("locomotion:flat").unwrap();
    if let TaskSpec::Locomotion(l) = &mut task {
        l.duration = 3.0;
    }
    let outcome = episode::run(chain.as_robot(), task.task(), 0, TraceLevel::Full).unwrap();
    assert!(outcome.fitness.iter().all(|f| f.is_finite()));
    assert_eq!(outcome.units, 8);
    let trace = outcome.trace.as_ref().unwrap();
    // its own channels and its brain's, though the chain's code never mentions the latter
    assert_eq!(trace.channel(channels::ACTUATION.name).unwrap().width, 8);
    assert!(trace.outlines.iter().all(|p| p.is_finite()));
    let actuations = trace.values(channels::ACTUATION.name);
    assert!(actuations.iter().any(|a| a.abs() > 1e-3), "the brain acts");
    // drawn: eight links, each an outline polygon
    let frame = render_frame(trace, trace.len() - 1, &RenderOptions::default());
    let blank = render_frame(
        &Trace {
            outlines: Vec::new(),
            ..trace.clone()
        },
        0,
        &RenderOptions::default(),
    );
    assert_ne!(frame.data(), blank.data());
    // replayed: its per-step channels, and units numbered for the viewer
    let replay = Replay::from_trace(trace, &ReplayOptions::default()).unwrap();
    assert_eq!(replay.body.cells.len(), 8);
    assert_eq!(replay.channels["actuation"].per_frame, 8);
    assert_eq!(replay.channels["touch"].per_frame, 8);
    // the same inputs give the same bits
    assert_eq!(
        episode::run(chain.as_robot(), task.task(), 0, TraceLevel::Full).unwrap(),
        outcome
    );
}

#[test]
fn a_third_kind_is_evolvable_through_its_body_form() {
    let body = (KIND.decode_body)(serde_json::json!({"kind": "chain", "links": 6})).unwrap();
    assert!((KIND.decode_body)(serde_json::json!({"kind": "chain", "links": 2})).is_err());
    let representation = Representation {
        body,
        sensors: None,
        brain: BrainSpec::parse("distributed-mlp").unwrap(),
        preset: Default::default(),
    };
    // no body genes; the brain's 18 weights are the genotype
    assert_eq!(representation.genotype_length(), Ok(18));
    let mut task = TaskSpec::parse("locomotion:flat").unwrap();
    if let TaskSpec::Locomotion(l) = &mut task {
        l.duration = 2.0;
    }
    let genotype: Vec<f64> = (0..18).map(|i| (i as f64 * 0.37).sin()).collect();
    let outcome = evaluate(&representation, &genotype, task.task(), 0).unwrap();
    assert!(outcome.fitness.iter().all(|f| f.is_finite()));
    assert_eq!(outcome.units, 6);
    // a genotype of the wrong length is named
    assert!(evaluate(&representation, &genotype[..17].to_vec(), task.task(), 0).is_err());
    // the resolved experiment file writes the form back
    let text = serde_json::to_string(&representation.body).unwrap();
    assert_eq!(text, r#"{"kind":"chain","links":6}"#);
}
