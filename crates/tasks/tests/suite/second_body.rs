//! A body that is not a voxel grid, written in this one file: a "hopper" of a triangle and a
//! square joined by one actuated spring. It proves that a new body kind needs only a type
//! implementing `Body`, `Robot` and `Agent`, and then runs on every task through the one episode
//! loop, with traces of polygons of any corner count.

use vsrlab_body::{Body, Probe, VoxelState};
use vsrlab_physics::{
    PartDesc, PartHandle, Polygon, SpringDesc, SpringHandle, SpringMassModel, Vec2, World, WorldBuilder,
};
use vsrlab_tasks::{episode, Agent, EpisodeError, Robot, TaskSpec, Trace, TraceLevel};

/// The hopper as described before it is put in a world.
struct HopperSpec {
    /// Actuation frequency (Hz).
    frequency: f64,
}

/// The hopper in a world.
struct Hopper {
    head: PartHandle,
    foot: PartHandle,
    spring: SpringHandle,
    rest: f64,
    frequency: f64,
    actuation: f64,
}

const HEAD: [Vec2; 3] = [Vec2::new(-1.0, -0.5), Vec2::new(1.0, -0.5), Vec2::new(0.0, 1.0)];

impl Body for Hopper {
    fn actuator_count(&self) -> usize {
        1
    }
    fn actuate(&self, world: &mut World, values: &[f64]) {
        let a = values[0].clamp(-1.0, 1.0);
        world.set_spring_rest_length(self.spring, self.rest * (1.0 - 0.4 * a));
    }
    fn center(&self, world: &World) -> Vec2 {
        (world.part_position(self.head) + world.part_position(self.foot)) * 0.5
    }
    fn sensing_units(&self) -> usize {
        0
    }
    fn unit_state(&self, _world: &World, i: usize) -> VoxelState {
        unreachable!("the hopper has no sensing unit {i}")
    }
    fn outline_corners(&self) -> Vec<usize> {
        vec![3, 4]
    }
    fn outline(&self, world: &World, out: &mut Vec<Vec2>) {
        out.extend(HEAD.iter().map(|&p| world.part_point(self.head, p)));
        for p in [(-1.0, 1.0), (1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            out.push(world.part_point(self.foot, Vec2::new(p.0, p.1)));
        }
    }
}

impl Agent for Hopper {
    fn body(&self) -> &dyn Body {
        self
    }
    fn act(&mut self, world: &mut World, t: f64) {
        self.actuation = (2.0 * std::f64::consts::PI * self.frequency * t).sin();
        self.actuate(world, &[self.actuation]);
    }
    fn describe(&mut self, trace: &mut Trace) {
        trace.side_length = 2.0;
    }
    fn record(&self, trace: &mut Trace) {
        trace.step(&vsrlab_tasks::channels::ACTUATION, &[self.actuation]);
    }
}

impl Robot for HopperSpec {
    fn footprint(&self) -> Vec<Vec2> {
        vec![Vec2::new(-1.0, 0.0), Vec2::new(1.0, 0.0)]
    }
    fn assemble(&self, builder: &mut WorldBuilder, origin: Vec2, _seed: u64) -> Result<Box<dyn Agent>, EpisodeError> {
        if !(self.frequency.is_finite() && self.frequency > 0.0) {
            return Err(EpisodeError::Invalid(format!(
                "robot.frequency must be > 0, got {}",
                self.frequency
            )));
        }
        let foot = builder
            .add_part(PartDesc::new(origin + Vec2::new(0.0, 1.0), Polygon::square(Vec2::ZERO, 2.0)).friction(1.0));
        let triangle = Polygon::convex(&HEAD).expect("a convex triangle");
        let head = builder.add_part(PartDesc::new(origin + Vec2::new(0.0, 3.5), triangle).friction(1.0));
        let rest = 2.5;
        let spring = builder.add_spring(SpringDesc {
            part_a: foot,
            anchor_a: Vec2::ZERO,
            part_b: head,
            anchor_b: Vec2::ZERO,
            rest_length: rest,
            frequency: 8.0,
            damping_ratio: 0.3,
            mass_model: SpringMassModel::default(),
            collide_connected: false,
        });
        Ok(Box::new(Hopper {
            head,
            foot,
            spring,
            rest,
            frequency: self.frequency,
            actuation: 0.0,
        }))
    }
}

#[test]
fn a_second_body_kind_runs_on_every_task_with_general_outlines() {
    let hopper = HopperSpec { frequency: 2.0 };
    for task in ["locomotion:flat", "locomotion:hilly-1-10", "jump"] {
        let spec = TaskSpec::parse(task)
            .unwrap()
            .with_settings(&[("duration", serde_json::json!(5.0))])
            .unwrap();
        let outcome = episode::run(&hopper, spec.task(), 1, TraceLevel::Full).unwrap();
        assert_eq!(outcome.units, 1, "{task}");
        // 5 s of 1/60 s steps counted as the original does (task::original_episode_steps)
        let steps = outcome.steps as usize;
        assert_eq!(steps, 301, "{task}");
        assert!(outcome.fitness.iter().all(|f| f.is_finite()), "{task}: {outcome:?}");
        let trace = outcome.trace.as_ref().unwrap();
        assert_eq!(trace.outline_corners, [3, 4]);
        assert_eq!(trace.outlines.len(), steps * 7, "{task}");
        let last = trace.polygons_at(steps - 1);
        assert_eq!(last.first().unwrap().len(), 3);
        assert_eq!(last.get(1).unwrap().len(), 4);
        assert!(trace.outlines.iter().all(|p| p.is_finite()), "{task}");
        assert_eq!(trace.values("actuation").len(), steps);
        // the same inputs give the same bits
        let again = episode::run(&hopper, spec.task(), 1, TraceLevel::Full).unwrap();
        assert_eq!(again, outcome);
    }
    let jump = TaskSpec::parse("jump").unwrap();
    let outcome = episode::run(&hopper, jump.task(), 0, TraceLevel::None).unwrap();
    assert!(
        outcome.metric("height") > 0.0,
        "the hopper rises: {:?}",
        outcome.metrics
    );
}

#[test]
fn a_bad_second_body_is_reported_not_run() {
    let err = episode::run(
        &HopperSpec { frequency: -1.0 },
        TaskSpec::default().task(),
        0,
        TraceLevel::None,
    )
    .unwrap_err();
    assert!(err.to_string().contains("robot.frequency"), "{err}");
}
