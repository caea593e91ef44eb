//! The pressure-based soft agent as a [`Robot`] (thesis ch. 6): a [`PsaRobot`] assembles into a
//! [`Psa`] body, its [`PsaSensors`] and its brain; at every step its [`PsaAgent`] senses, controls
//! and actuates, in that order (the step order of every vsrlab robot).
//!
//! The brain sees the agent as units, one per controlled actuator: with spring control, unit i is
//! mass i (readings touch, x, y; actuator: spring i, joining mass i and i+1), and these units form
//! a ring (each one's neighbours are the masses beside it on the membrane); with pressure control,
//! one more unit is the gas (readings Δx, Δy, p/p_max; actuator: Δp), outside the ring. Without
//! pressure control the gas's three readings go to the last spring unit; without spring control
//! the gas unit has all 3n+3 readings. Any brain whose shape fits runs a PSA; the thesis's is
//! `heads` (tanh spring heads, a linear Δp head).

use crate::agent::{Agent, Robot};
use crate::channels::{ACTUATION, ANGLE, AREA_RATIO, TOUCH, UNIT_POLYGONS};
use crate::episode::EpisodeError;
use crate::kinds::voxel::short_forms::{RobotArgsError, RobotPart};
use crate::outcome::Trace;
use serde::{Deserialize, Serialize};
use vsrlab_body::psa::{Psa, PsaBody, PsaSensors};
use vsrlab_body::{Body, Channel, Probe};
use vsrlab_brain::{BrainShape, BrainSpec, Controller, HeadsSpec, RingLayout};
use vsrlab_field::FieldError;
use vsrlab_physics::{Vec2, World, WorldBuilder};

/// Collision group of the agent (touch sensing).
const PSA_GROUP: u32 = 1;

/// A PSA robot: its body and its brain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PsaRobot {
    /// Size and constants.
    pub body: PsaBody,
    /// The controller (default: the thesis's `heads`).
    #[serde(default = "default_brain")]
    pub brain: BrainSpec,
}

fn default_brain() -> BrainSpec {
    BrainSpec::Heads(HeadsSpec::default())
}

impl PsaRobot {
    /// The brain's view of the agent: the controlled units, the readings of each, and their ring
    /// layout (see the module documentation).
    pub fn brain_shape(&self) -> BrainShape {
        let p = &self.body.params;
        let n = p.masses;
        let mut readings = Vec::new();
        let layout = if p.spring_control {
            readings.extend(std::iter::repeat_n(3, n));
            if p.pressure_control {
                readings.push(3);
            } else {
                readings[n - 1] += 3;
            }
            RingLayout::new(n, usize::from(p.pressure_control))
        } else {
            readings.push(3 * n + 3);
            RingLayout::new(0, 1)
        };
        BrainShape::new(layout, readings)
    }

    /// Number of brain parameters for this body; an error names the brain's field (`brain.…`).
    pub fn brain_parameters(&self) -> Result<usize, FieldError> {
        Ok(self.brain.parameter_count(&self.brain_shape())?)
    }

    /// Checks the body's constants and that a `heads` brain's linear outputs fit the treatment;
    /// the error's path is relative to the robot (`body.masses`, `brain.linear_outputs`).
    pub fn validate_body(&self) -> Result<(), FieldError> {
        let p = &self.body.params;
        p.validate().map_err(|e| e.at("body"))?;
        if let BrainSpec::Heads(h) = &self.brain {
            let expected = usize::from(p.pressure_control);
            if h.linear_outputs != expected {
                return Err(FieldError::new(
                    "brain.linear_outputs",
                    format!(
                        "{} with pressure control {}; the last output is {} here, so set {expected}",
                        h.linear_outputs,
                        if p.pressure_control { "on" } else { "off" },
                        if p.pressure_control {
                            "Δp (linear)"
                        } else {
                            "a spring (tanh)"
                        }
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Checks that body and brain fit together, parameters included; the error's path is
    /// relative to the robot, as for [`PsaRobot::validate_body`].
    pub fn validate(&self) -> Result<(), FieldError> {
        self.validate_body()?;
        self.brain.build(&self.brain_shape()).map(|_| ())?;
        Ok(())
    }
}

impl Robot for PsaRobot {
    /// The undersides of the masses, relative to the origin: the lower left corner of the
    /// circle's bounding box.
    fn footprint(&self) -> Vec<Vec2> {
        let p = &self.body.params;
        let n = p.masses;
        (0..n)
            .map(|i| {
                let a = 2.0 * std::f64::consts::PI * i as f64 / n as f64;
                Vec2::new(
                    p.radius * (1.0 + a.cos()),
                    p.radius * (1.0 + a.sin()) - 0.5 * p.mass_side,
                )
            })
            .collect()
    }

    fn assemble(&self, builder: &mut WorldBuilder, origin: Vec2, _seed: u64) -> Result<Box<dyn Agent>, EpisodeError> {
        // the brain is built once, below (validate() would build it a second time)
        self.validate_body().map_err(|e| e.at("robot"))?;
        let p = &self.body.params;
        let centre = origin + Vec2::new(p.radius, p.radius);
        let psa = Psa::assemble(builder, p, centre, PSA_GROUP);
        let shape = self.brain_shape();
        let mut brain = self.brain.build(&shape).map_err(|e| FieldError::from(e).at("robot"))?;
        brain.reset();
        let sensors = PsaSensors::new(&psa, builder.settings().dt).map_err(|e| e.at("robot.body"))?;
        Ok(Box::new(PsaAgent::new(psa, sensors, brain, shape.units())))
    }

    fn description(&self) -> Option<&dyn crate::kinds::RobotDescription> {
        Some(self)
    }
}

/// A PSA in a world: body, sensors, brain and the buffers they share each step.
pub struct PsaAgent {
    psa: Psa,
    sensors: PsaSensors,
    brain: Box<dyn Controller>,
    readings: Vec<f64>,
    /// The brain's outputs, one per controlled unit.
    outputs: Vec<f64>,
    /// The body's actuation: one per spring, then Δp.
    actuations: Vec<f64>,
    /// Pressure before the last actuation, φ and each mass's touch flag, for the trace.
    pressure: f64,
    phi: f64,
    touching: Vec<bool>,
}

impl PsaAgent {
    /// Wires a body, its sensors and a brain built for `units` outputs.
    pub fn new(psa: Psa, sensors: PsaSensors, brain: Box<dyn Controller>, units: usize) -> Self {
        let readings = vec![0.0; sensors.reading_count()];
        let actuations = vec![0.0; psa.actuator_count()];
        let touching = vec![false; psa.mass_count()];
        PsaAgent {
            psa,
            sensors,
            brain,
            readings,
            outputs: vec![0.0; units],
            touching,
            actuations,
            pressure: 0.0,
            phi: 1.0,
        }
    }

    /// The body.
    pub fn psa(&self) -> &Psa {
        &self.psa
    }
}

impl PsaAgent {
    /// Maps the outputs to the body's actuation, notes what the trace shows, and actuates.
    fn apply(&mut self, world: &mut World) {
        let p = self.psa.params();
        let n = p.masses;
        if p.spring_control {
            self.actuations[..n].copy_from_slice(&self.outputs[..n]);
        }
        if p.pressure_control {
            self.actuations[n] = self.outputs[self.outputs.len() - 1];
        }
        self.pressure = self.psa.pressure(world);
        self.phi = self.psa.area_ratio(world);
        for (flag, &m) in self.touching.iter_mut().zip(self.psa.masses()) {
            *flag = world.part_touching(m);
        }
        self.psa.actuate(world, &self.actuations);
    }
}

impl Agent for PsaAgent {
    fn body(&self) -> &dyn Body {
        &self.psa
    }

    fn act(&mut self, world: &mut World, t: f64) {
        self.sensors.sense(&self.psa, world, &mut self.readings);
        self.brain.control(t, &self.readings, &mut self.outputs);
        self.apply(world);
    }

    fn sense(&mut self, world: &World, _t: f64) {
        self.sensors.sense(&self.psa, world, &mut self.readings);
    }

    fn readings(&self) -> &[f64] {
        &self.readings
    }

    fn action_count(&self) -> usize {
        self.outputs.len()
    }

    fn actuate(&mut self, world: &mut World, actions: &[f64]) {
        self.outputs.copy_from_slice(actions);
        self.apply(world);
    }

    fn brain(&self) -> Option<&dyn Controller> {
        Some(self.brain.as_ref())
    }

    fn describe(&mut self, trace: &mut Trace) {
        let p = self.psa.params();
        trace.side_length = p.mass_side;
        // brain units: the masses (polygons 1…n) when springs are controlled, then the gas unit
        // (the membrane, polygon 0)
        let masses = if p.spring_control { p.masses } else { 0 };
        let gas = usize::from(p.pressure_control || !p.spring_control);
        let polygons: Vec<f64> = (1..=masses)
            .chain(std::iter::repeat_n(0, gas))
            .map(|i| i as f64)
            .collect();
        trace.fixed(&UNIT_POLYGONS, 1, &polygons);
    }

    fn record(&self, trace: &mut Trace) {
        // the trace's units are the outline's polygons: the membrane (φ as its area ratio, no
        // touch, the Δp actuation), then each mass
        let masses = self.psa.mass_count();
        trace.step_from(
            &AREA_RATIO,
            &mut std::iter::once(self.phi).chain((0..masses).map(|_| 1.0)),
        );
        trace.step_from(&ANGLE, &mut (0..=masses).map(|_| 0.0));
        let touch = self.touching.iter().map(|&t| f64::from(u8::from(t)));
        trace.step_from(&TOUCH, &mut std::iter::once(0.0).chain(touch));
        let actuations = self.actuations[..masses].iter().copied();
        trace.step_from(
            &ACTUATION,
            &mut std::iter::once(self.actuations[masses]).chain(actuations),
        );
        trace.step(&PRESSURE, &[self.pressure / self.psa.max_pressure()]);
    }
}

/// The pressure of a pressurised body over its largest pressure, per step.
pub const PRESSURE: Channel = Channel::replayed("pressure", 1e-3).single();

/// Seed of the random brain parameters of a PSA built from short forms (as for voxel robots).
const RANDOM_BRAIN_SEED: u64 = 0;

impl PsaRobot {
    /// A PSA from command-line short forms: `psa[:small|medium|large]` and a brain short form
    /// (`heads` for the thesis's controller); a brain with parameters gets seeded random ones in
    /// [−1, 1]. Errors name the part at fault (body or brain).
    pub fn from_short_forms(body: &str, brain: &str) -> Result<PsaRobot, RobotArgsError> {
        let size = match body.strip_prefix("psa:") {
            None if body == "psa" => Default::default(),
            Some(size) => serde_json::from_value(serde_json::Value::String(size.to_string())).map_err(|_| {
                kind_error(
                    RobotPart::Body,
                    format!("unknown PSA size '{size}': expected small, medium or large"),
                )
            })?,
            None => {
                return Err(kind_error(
                    RobotPart::Body,
                    format!("'{body}' is not a PSA (psa[:small|medium|large])"),
                ))
            }
        };
        let brain_text = brain;
        let brain = BrainSpec::parse(brain).map_err(RobotArgsError::Brain)?;
        let mut robot = PsaRobot {
            body: PsaBody::of_size(size),
            brain,
        };
        let shape = robot.brain_shape();
        let count = robot.brain.parameter_count(&shape).map_err(RobotArgsError::Brain)?;
        if count > 0 && robot.brain.parameters().is_empty() {
            robot.brain = robot
                .brain
                .with_random_parameters(RANDOM_BRAIN_SEED, &shape)
                .map_err(RobotArgsError::Brain)?;
        }
        robot.validate().map_err(|e| match e.path.strip_prefix("brain") {
            // the command line gave the brain as a short form: name it, not a file's field
            Some(inner) => {
                let field = inner.trim_start_matches('.');
                let field = if field.is_empty() {
                    String::new()
                } else {
                    format!(" ({field})")
                };
                kind_error(RobotPart::Brain, format!("'{brain_text}'{field}: {}", e.message))
            }
            None => kind_error(RobotPart::Body, e.at("robot").to_string()),
        })?;
        Ok(robot)
    }
}

fn kind_error(part: RobotPart, message: String) -> RobotArgsError {
    RobotArgsError::Kind { part, message }
}
