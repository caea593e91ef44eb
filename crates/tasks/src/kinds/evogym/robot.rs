//! [`EvoGymRobot`]: a material grid with a brain, as the robot kinds' registry sees it. Its brain
//! sees the whole observation of the EvoGym task it was built for (`env`: the observation's size
//! depends on the task) and gives one action per actuator voxel.

use super::grid::MaterialGrid;
use super::tasks::EvoGymTask;
use super::EvoGymEnv;
use crate::agent::{Agent, Robot};
use crate::body_summary::BodySummary;
use crate::episode::EpisodeError;
use crate::kinds::RobotDescription;
use serde::{Deserialize, Serialize};
use vsrlab_body::Morphology;
use vsrlab_brain::{BrainShape, BrainSpec, UnitSet};
use vsrlab_field::FieldError;
use vsrlab_physics::{Vec2, WorldBuilder};

/// An EvoGym robot: its material grid (text rows, top first, one digit per cell: 0 empty,
/// 1 rigid, 2 soft, 3 horizontal actuator, 4 vertical actuator), the task whose observation its
/// brain sees, and the brain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EvoGymRobot {
    /// The material grid as rows joined by `/` (`"33333/31113"`).
    pub body: String,
    /// The EvoGym task the brain is sized for (`Walker-v0`, `BridgeWalker-v0`, `BeamToppler-v0`,
    /// `CaveCrawler-v0`).
    #[serde(default = "walker")]
    pub env: String,
    /// The brain: all observations in, one value in [-1, 1] per actuator voxel out.
    pub brain: BrainSpec,
}

fn walker() -> String {
    EvoGymTask::Walker.name().to_string()
}

/// EvoGym's action space: target length ratios in [0.6, 1.6].
pub const TARGET_RANGE: (f64, f64) = (0.6, 1.6);
/// The target of brain output 0.
pub const TARGET_CENTRE: f64 = 1.1;
/// Target change per unit of brain output (a power of two: learned policies round-trip exactly).
pub const TARGET_HALF_RANGE: f64 = 0.5;

/// A brain output in [-1, 1] as EvoGym's action: a target length ratio in [0.6, 1.6] (its
/// action space), 1.1 at output 0. EvoGym's policies give raw actions that its engine clips to
/// this range; vsrlab's brains end in tanh, so the range is mapped linearly instead. The target
/// is clipped, not the output: output −1 gives 0.6000000000000001 (1.1 − 0.5), and a learned
/// policy that wants 0.6 exactly gives −1.0000000000000002 (vsrlab_brain::TargetAction).
pub fn action_of(output: f64) -> f64 {
    (TARGET_CENTRE + TARGET_HALF_RANGE * output).clamp(TARGET_RANGE.0, TARGET_RANGE.1)
}

impl EvoGymRobot {
    /// The grid, checked as an EvoGym robot (connected, with an actuator); the error's path is
    /// relative to the robot (`body…`).
    pub fn grid(&self) -> Result<MaterialGrid, FieldError> {
        let grid = MaterialGrid::from_rows(&self.body).map_err(|e| e.at("body"))?;
        grid.validate_robot().map_err(|e| e.at("body"))?;
        Ok(grid)
    }

    /// The task named by `env`; the error names the field.
    pub fn task(&self) -> Result<EvoGymTask, FieldError> {
        EvoGymTask::from_name(&self.env).ok_or_else(|| FieldError::new("env", EvoGymTask::unknown(&self.env)))
    }

    /// The brain's view: one unit per actuator voxel, the whole observation as the first unit's
    /// readings (a centralized brain reads them all).
    pub fn brain_shape(&self) -> Result<BrainShape, FieldError> {
        let env = EvoGymEnv::new(self.task()?, &self.grid()?).map_err(|e| FieldError::new("body", e.to_string()))?;
        Ok(shape(env.observation_size(), env.action_count()))
    }

    /// Checks the body, the task and that the brain fits them; paths are relative to the robot.
    pub fn validate(&self) -> Result<(), FieldError> {
        let shape = self.brain_shape()?;
        self.brain
            .parameter_count(&shape)
            .map_err(|e| FieldError::from(e).at("brain"))?;
        Ok(())
    }
}

/// The brain shape of an observation of `observations` values and `actions` actuators.
pub(crate) fn shape(observations: usize, actions: usize) -> BrainShape {
    let mut readings = vec![0; actions];
    if let Some(first) = readings.first_mut() {
        *first = observations;
    }
    BrainShape::new(UnitSet::new(actions), readings)
}

impl Robot for EvoGymRobot {
    fn footprint(&self) -> Vec<Vec2> {
        Vec::new()
    }

    /// EvoGym robots live on their own engine: only EvoGym tasks run them.
    fn assemble(&self, _builder: &mut WorldBuilder, _origin: Vec2, _seed: u64) -> Result<Box<dyn Agent>, EpisodeError> {
        Err(EpisodeError::Field(FieldError::new(
            "task.kind",
            "an EvoGym robot runs in an EvoGym task (evogym:Walker-v0, …), not on the rigid-body engine",
        )))
    }

    fn summary(&self) -> Option<BodySummary> {
        let grid = self.grid().ok()?;
        let rows: Vec<String> = (0..grid.height())
            .map(|y| {
                (0..grid.width())
                    .map(|x| if grid.at(x, y).is_present() { '#' } else { '.' })
                    .collect()
            })
            .collect();
        let occupancy = Morphology::parse(&rows.join("/")).ok()?;
        Some(BodySummary {
            text: self.body.clone(),
            ..BodySummary::of_grid(&occupancy)
        })
    }

    fn description(&self) -> Option<&dyn RobotDescription> {
        Some(self)
    }
}
