//! From a genotype to what the optimizer and the logs need: fitness, descriptor, speciation
//! features and a small record for snapshots.
//!
//! [`Evaluator`] is the seam between the runner and the robots: [`RobotEvaluator`] runs
//! locomotion episodes; tests plug in cheap functions. Evaluations are pure and thread-safe: the
//! same genotype and seed give the same result on any thread.

use crate::config::{Descriptor, Experiment, Fitness, OptimizerConfig, SeFeatures};
use crate::features;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;
use vsrlab_tasks::{locomotion, Locomotion, Representation, TraceLevel};

/// The summary of one evaluation that population snapshots carry (serialisable: checkpoints
/// hold the records of the current population).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The episode seed used.
    pub seed: u64,
    /// The fitness (`None` when the evaluation failed).
    pub fitness: Option<f64>,
    /// Distance travelled.
    pub distance: Option<f64>,
    /// Average velocity.
    pub velocity: Option<f64>,
    /// Number of voxels.
    pub voxels: Option<usize>,
    /// The body as rows of `#` and `.`, top row first, joined by `/`.
    pub body: Option<String>,
    /// Why the evaluation failed.
    pub error: Option<String>,
}

/// What one evaluation produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluated {
    /// The fitness; NaN (the optimizers' worst value) when the evaluation failed.
    pub fitness: f64,
    /// MAP-Elites descriptor (empty when unused).
    pub descriptor: Vec<f64>,
    /// Speciation features (empty unless SE-s / SE-b).
    pub features: Vec<f64>,
    /// The record for snapshots.
    pub record: Record,
    /// Seconds spent in this evaluation (building the robot, the episode, the features).
    pub seconds: f64,
}

impl Evaluated {
    /// Whether the evaluation failed.
    pub fn failed(&self) -> bool {
        self.record.error.is_some()
    }
}

/// Evaluates genotypes. Implementations must be deterministic in (genotype, seed).
pub trait Evaluator: Sync {
    /// Genes per genotype.
    fn genotype_length(&self) -> usize;
    /// Evaluates a genotype; `candidate_seed` is the optimizer's per-candidate seed.
    fn evaluate(&self, genotype: &[f64], candidate_seed: u64) -> Evaluated;
    /// The result of an evaluation that failed with `error` before producing anything (used
    /// when an evaluation panics): NaN fitness and zero descriptor and features of the right
    /// lengths. The default has empty descriptor and features.
    fn failure(&self, seed: u64, error: String) -> Evaluated {
        Evaluated {
            fitness: f64::NAN,
            descriptor: Vec::new(),
            features: Vec::new(),
            record: Record {
                seed,
                fitness: None,
                distance: None,
                velocity: None,
                voxels: None,
                body: None,
                error: Some(error),
            },
            seconds: 0.0,
        }
    }
    /// Saves the robot of a genotype to a file (the best of a run); a no-op by default.
    fn save_robot(&self, _genotype: &[f64], _path: &Path, _note: &str) -> Result<(), String> {
        Ok(())
    }
}

/// Which extra data an evaluation must extract from its episode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Extract {
    Nothing,
    Pose,
    Spectrum,
}

/// Evaluates genotypes as robots on the experiment's locomotion task.
#[derive(Debug, Clone)]
pub struct RobotEvaluator {
    representation: Representation,
    task: Locomotion,
    fitness: Fitness,
    random_terrain: bool,
    episode_seed: u64,
    extract: Extract,
    descriptors: Vec<Descriptor>,
    genes: usize,
}

impl RobotEvaluator {
    /// The evaluator of an experiment (already validated by [`crate::config::parse`]).
    pub fn new(experiment: &Experiment) -> Result<Self, String> {
        let genes = experiment.representation.genotype_length().map_err(|e| e.to_string())?;
        let (extract, descriptors) = match &experiment.optimizer {
            OptimizerConfig::Se(p) => match p.features {
                SeFeatures::Shape => (Extract::Pose, vec![]),
                SeFeatures::Behaviour => (Extract::Spectrum, vec![]),
                SeFeatures::Genotype => (Extract::Nothing, vec![]),
            },
            OptimizerConfig::MapElites(p) => (Extract::Nothing, p.axes.iter().map(|a| a.descriptor).collect()),
            _ => (Extract::Nothing, vec![]),
        };
        Ok(Self {
            representation: experiment.representation.clone(),
            task: experiment.task.locomotion(),
            fitness: experiment.task.fitness,
            random_terrain: experiment.task.random_terrain_per_evaluation,
            episode_seed: experiment.task.episode_seed,
            extract,
            descriptors,
            genes,
        })
    }

    fn failed_with(
        &self,
        seed: u64,
        body: Option<&vsrlab_body::Morphology>,
        error: String,
        start: Instant,
    ) -> Evaluated {
        let features_len = match self.extract {
            Extract::Nothing => 0,
            Extract::Pose => features::POSE_LEN,
            Extract::Spectrum => features::spectrum_len(),
        };
        Evaluated {
            fitness: f64::NAN,
            descriptor: match body {
                Some(b) => self.descriptor(b),
                None => vec![0.0; self.descriptors.len()],
            },
            features: vec![0.0; features_len],
            record: Record {
                seed,
                fitness: None,
                distance: None,
                velocity: None,
                voxels: body.map(|b| b.voxel_count()),
                body: body.map(|b| b.to_rows().join("/")),
                error: Some(error),
            },
            seconds: start.elapsed().as_secs_f64(),
        }
    }

    fn descriptor(&self, body: &vsrlab_body::Morphology) -> Vec<f64> {
        let [voxels, elongation, compactness] = features::morphology_descriptors(body);
        self.descriptors
            .iter()
            .map(|d| match d {
                Descriptor::Voxels => voxels,
                Descriptor::Elongation => elongation,
                Descriptor::Compactness => compactness,
            })
            .collect()
    }
}

impl Evaluator for RobotEvaluator {
    fn genotype_length(&self) -> usize {
        self.genes
    }

    fn evaluate(&self, genotype: &[f64], candidate_seed: u64) -> Evaluated {
        let start = Instant::now();
        let seed = if self.random_terrain {
            candidate_seed
        } else {
            self.episode_seed
        };
        let robot = match self.representation.robot(genotype) {
            Ok(robot) => robot,
            Err(e) => return self.failed_with(seed, None, e.to_string(), start),
        };
        let level = match self.extract {
            Extract::Nothing => TraceLevel::None,
            Extract::Pose => TraceLevel::Full,
            Extract::Spectrum => TraceLevel::Center,
        };
        let outcome = match locomotion::run(&robot, &self.task, seed, level) {
            Ok(outcome) => outcome,
            Err(e) => return self.failed_with(seed, Some(&robot.body), e.to_string(), start),
        };
        let fitness = match self.fitness {
            Fitness::Velocity => outcome.velocity,
            Fitness::Distance => outcome.distance,
        };
        if !fitness.is_finite() {
            return self.failed_with(seed, Some(&robot.body), format!("non-finite fitness {fitness}"), start);
        }
        let features = match (&self.extract, &outcome.trace) {
            (Extract::Pose, Some(trace)) => features::dynamic_pose(trace),
            (Extract::Spectrum, Some(trace)) => features::center_spectrum(trace),
            _ => Vec::new(),
        };
        Evaluated {
            fitness,
            descriptor: self.descriptor(&robot.body),
            features,
            record: Record {
                seed,
                fitness: Some(fitness),
                distance: Some(outcome.distance),
                velocity: Some(outcome.velocity),
                voxels: Some(outcome.voxels),
                body: Some(robot.body.to_rows().join("/")),
                error: None,
            },
            seconds: start.elapsed().as_secs_f64(),
        }
    }

    fn failure(&self, seed: u64, error: String) -> Evaluated {
        self.failed_with(seed, None, error, Instant::now())
    }

    fn save_robot(&self, genotype: &[f64], path: &Path, note: &str) -> Result<(), String> {
        let robot = self.representation.robot(genotype).map_err(|e| e.to_string())?;
        vsrlab_tasks::files::save_robot(path, &robot, Some(note)).map_err(|e| e.to_string())
    }
}
