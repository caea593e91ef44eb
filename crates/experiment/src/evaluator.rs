//! From a genotype to what the optimizer and the logs need: fitness values, descriptor,
//! speciation features and a small record for snapshots.
//!
//! [`Evaluator`] is the seam between the runner and the robots: [`RobotEvaluator`] maps genotypes
//! to robots through a [`Mapper`] and calls [`vsrlab_tasks::evaluate_traced`], the one
//! genotype → outcome path; tests plug in cheap functions. Evaluations are pure and thread-safe:
//! the same genotype and seed give the same result on any thread.

use crate::config::Experiment;
use crate::features;
use crate::optimizers::{Descriptor, Extract};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;
use vsrlab_tasks::BodySummary;
use vsrlab_tasks::{evaluate_traced, EvaluationError, Mapper, Representation, TaskSpec, TraceLevel};

/// The summary of one evaluation that population snapshots carry (the row type the analyses read
/// back, [`vsrlab_analysis::rows`]).
pub use vsrlab_analysis::rows::Record;

/// What one evaluation produced. Serialisable (non-finite values included), so that evaluations
/// run on other machines (Ray workers) come back whole.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluated {
    /// The fitness values; NaN (the optimizers' worst value) when the evaluation failed.
    #[serde(with = "vsrlab_evolution::serde_float::vec")]
    pub objectives: Vec<f64>,
    /// MAP-Elites descriptor (empty when unused).
    #[serde(with = "vsrlab_evolution::serde_float::vec")]
    pub descriptor: Vec<f64>,
    /// Speciation features (empty unless SE-s / SE-b).
    #[serde(with = "vsrlab_evolution::serde_float::vec")]
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

    /// The first fitness value (NaN when there is none).
    pub fn fitness(&self) -> f64 {
        self.objectives.first().copied().unwrap_or(f64::NAN)
    }
}

/// Why an evaluator could not evaluate a batch, check a genotype or save a robot.
#[derive(Debug, thiserror::Error)]
pub enum EvaluatorError {
    /// The genotype does not make a robot, or its episode failed.
    #[error(transparent)]
    Robot(#[from] EvaluationError),
    /// This kind of robot has no robot file.
    #[error("this kind of robot has no robot file")]
    NoRobotFile,
    /// A file could not be written.
    #[error("{}: {source}", path.display())]
    File {
        /// The file.
        path: std::path::PathBuf,
        /// The OS error.
        source: std::io::Error,
    },
    /// The replay could not be written.
    #[error(transparent)]
    Replay(#[from] vsrlab_render::replay::SaveReplayError),
    /// The episode recorded no trace.
    #[error("the episode recorded no trace")]
    NoTrace,
    /// Evaluations sent elsewhere (Ray workers, a Python callable) came back with an error: what
    /// that side reported.
    #[error("{0}")]
    Remote(String),
}

/// Evaluates genotypes of type `G`. Implementations must be deterministic in (genotype, seed).
pub trait Evaluator<G>: Sync {
    /// Evaluates a genotype; `candidate_seed` is the optimizer's per-candidate seed.
    fn evaluate(&self, genotype: &G, candidate_seed: u64) -> Evaluated;
    /// Number of fitness values of every evaluation (1 unless multi-objective).
    fn objectives(&self) -> usize {
        1
    }
    /// The result of an evaluation that failed with `error` before producing anything (used
    /// when an evaluation panics): NaN fitness values and empty descriptor and features.
    fn failure(&self, seed: u64, error: String) -> Evaluated {
        Evaluated {
            objectives: vec![f64::NAN; self.objectives()],
            descriptor: Vec::new(),
            features: Vec::new(),
            record: Record {
                error: Some(error),
                ..Record::new(seed)
            },
            seconds: 0.0,
        }
    }
    /// Evaluates a batch, one candidate seed per genotype, in the batch's order (through
    /// [`Evaluator::evaluate_batch_reporting`], without reports).
    fn evaluate_batch(&self, genotypes: &[&G], seeds: &[u64]) -> Result<Vec<Evaluated>, EvaluatorError>
    where
        G: Sync,
    {
        self.evaluate_batch_reporting(genotypes, seeds, &|_, _| {})
    }
    /// Evaluates a batch, one candidate seed per genotype, in the batch's order, and calls
    /// `done(index, evaluation)` as each evaluation ends (from worker threads, in any order): the
    /// runner saves a long generation's finished evaluations while the others run. Default:
    /// every genotype on the current rayon pool, each guarded against panics
    /// ([`evaluate_guarded`]). Evaluators that send the work elsewhere (Ray workers) override
    /// this method; an error (the workers are gone) stops the run at its last checkpoint.
    fn evaluate_batch_reporting(
        &self,
        genotypes: &[&G],
        seeds: &[u64],
        done: &(dyn Fn(usize, &Evaluated) + Sync),
    ) -> Result<Vec<Evaluated>, EvaluatorError>
    where
        G: Sync,
    {
        Ok(evaluate_each(self, genotypes, seeds, done))
    }
    /// Saves the robot of a genotype to a file (the best of a run); `record`: its evaluation's
    /// record when the run kept it (evaluators whose robots depend on the evaluation's seed, as a
    /// brain learned during it, read the seed there). A no-op by default.
    fn save_robot(
        &self,
        _genotype: &G,
        _record: Option<&Record>,
        _path: &Path,
        _note: &str,
    ) -> Result<(), EvaluatorError> {
        Ok(())
    }
    /// Saves the episode of a genotype's robot as a replay file for the browser viewer (the best
    /// of a run); a no-op by default.
    fn save_replay(&self, _genotype: &G, _path: &Path, _title: &str) -> Result<(), EvaluatorError> {
        Ok(())
    }
    /// Names of the per-genotype statistics logged for the best genotype of every generation
    /// (`best_<name>` columns of `generations.csv`); none by default.
    fn genotype_columns(&self) -> &'static [&'static str] {
        &[]
    }
    /// The statistics named by [`Evaluator::genotype_columns`], for one genotype.
    fn genotype_stats(&self, _genotype: &G) -> Vec<f64> {
        Vec::new()
    }
    /// Checks that a genotype read from a file (a checkpoint) fits the representation, without
    /// evaluating it; accepts everything by default.
    fn check(&self, _genotype: &G) -> Result<(), EvaluatorError> {
        Ok(())
    }
}

/// Every genotype on the current rayon pool, one at a time, each guarded against panics
/// ([`evaluate_guarded`]): [`Evaluator::evaluate_batch_reporting`]'s default.
pub fn evaluate_each<G: Sync, E: Evaluator<G> + ?Sized>(
    evaluator: &E,
    genotypes: &[&G],
    seeds: &[u64],
    done: &(dyn Fn(usize, &Evaluated) + Sync),
) -> Vec<Evaluated> {
    genotypes
        .par_iter()
        .zip(seeds.par_iter())
        .enumerate()
        .map(|(index, (g, &seed))| {
            let evaluated = evaluate_guarded(evaluator, g, seed);
            done(index, &evaluated);
            evaluated
        })
        .collect()
}

/// Evaluates a genotype, turning a panic inside the evaluation into a failed evaluation so that
/// one bad genotype never ends a run.
pub fn evaluate_guarded<G, E: Evaluator<G> + ?Sized>(evaluator: &E, genotype: &G, seed: u64) -> Evaluated {
    let start = Instant::now();
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| evaluator.evaluate(genotype, seed))).unwrap_or_else(
        |panic| {
            let message = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".to_string());
            let mut failed = evaluator.failure(seed, format!("the evaluation panicked: {message}"));
            failed.seconds = start.elapsed().as_secs_f64();
            failed
        },
    )
}

/// Evaluates genotypes as robots on the experiment's task.
#[derive(Debug, Clone)]
pub struct RobotEvaluator<M = Representation> {
    mapper: M,
    task: TaskSpec,
    random_terrain: bool,
    episode_seed: u64,
    extract: Extract,
    descriptors: Vec<Descriptor>,
}

impl RobotEvaluator<Representation> {
    /// The evaluator of an experiment (already validated by [`crate::config::parse`]).
    pub fn new(experiment: &Experiment) -> Result<Self, EvaluationError> {
        experiment.representation.genotype_length()?;
        Ok(Self::with_mapper(experiment.representation.clone(), experiment))
    }

    /// Genes per genotype.
    pub fn genotype_length(&self) -> usize {
        self.mapper.genotype_length().unwrap_or(0)
    }
}

impl<M> RobotEvaluator<M> {
    /// An evaluator of an experiment's task and optimizer needs, with another genotype mapper.
    pub fn with_mapper(mapper: M, experiment: &Experiment) -> Self {
        let kind = experiment.optimizer.kind();
        Self {
            mapper,
            task: experiment.task.spec.clone(),
            random_terrain: experiment.task.random_terrain_per_evaluation,
            episode_seed: experiment.task.episode_seed,
            extract: kind.extract(),
            descriptors: kind.descriptors(),
        }
    }

    fn objective_count(&self) -> usize {
        self.task.task().objectives().len()
    }

    fn failed_with(&self, seed: u64, body: Option<&BodySummary>, error: String, start: Instant) -> Evaluated {
        let features_len = match self.extract {
            Extract::Nothing => 0,
            Extract::Pose => features::POSE_LEN,
            Extract::Spectrum => features::spectrum_len(),
        };
        Evaluated {
            objectives: vec![f64::NAN; self.objective_count()],
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
                voxels: body.map(|b| b.units),
                body: body.map(|b| b.text.clone()),
                error: Some(error),
                objectives: None,
                series: Default::default(),
            },
            seconds: start.elapsed().as_secs_f64(),
        }
    }

    /// The MAP-Elites descriptor of a body, from its kind's named descriptors (0 for one the
    /// kind does not give).
    fn descriptor(&self, body: &BodySummary) -> Vec<f64> {
        self.descriptors
            .iter()
            .map(|d| body.descriptor(d.name()).unwrap_or(0.0))
            .collect()
    }
}

impl<G, M: Mapper<G>> Evaluator<G> for RobotEvaluator<M> {
    fn objectives(&self) -> usize {
        self.objective_count()
    }

    fn evaluate(&self, genotype: &G, candidate_seed: u64) -> Evaluated {
        let start = Instant::now();
        let seed = self.seed(candidate_seed);
        let result = evaluate_traced(&self.mapper, genotype, self.task.task(), seed, self.level());
        self.evaluated(genotype, seed, result, start)
    }

    /// Same-shape robots of a batch step together when the task can (population lanes,
    /// [`vsrlab_tasks::Task::run_episodes`]); every evaluation has the bits of
    /// [`Evaluator::evaluate`] on its own.
    fn evaluate_batch_reporting(
        &self,
        genotypes: &[&G],
        seeds: &[u64],
        done: &(dyn Fn(usize, &Evaluated) + Sync),
    ) -> Result<Vec<Evaluated>, EvaluatorError>
    where
        G: Sync,
    {
        let task = self.task.task();
        if task.episode_batch() < 2 || self.level() != TraceLevel::None {
            return Ok(evaluate_each(self, genotypes, seeds, done));
        }
        let threads = rayon::current_num_threads();
        let groups = crate::batches::group(genotypes.len(), task.episode_batch(), threads, |i| {
            self.mapper
                .robot(genotypes[i])
                .ok()
                .and_then(|r| task.episode_group(r.as_ref()))
        });
        let finished: Vec<Vec<(usize, Evaluated)>> = groups
            .par_iter()
            .map(|batch| {
                let evaluations = self.evaluate_together(genotypes, seeds, batch);
                for (index, evaluated) in &evaluations {
                    done(*index, evaluated);
                }
                evaluations
            })
            .collect();
        Ok(crate::batches::in_order(genotypes.len(), finished))
    }

    fn failure(&self, seed: u64, error: String) -> Evaluated {
        self.failed_with(seed, None, error, Instant::now())
    }

    fn genotype_columns(&self) -> &'static [&'static str] {
        self.mapper.stats_columns()
    }

    fn genotype_stats(&self, genotype: &G) -> Vec<f64> {
        self.mapper.stats(genotype)
    }

    /// The genotype must become a robot (right length, finite genes, a body).
    fn check(&self, genotype: &G) -> Result<(), EvaluatorError> {
        Ok(self.mapper.robot(genotype).map(drop)?)
    }

    fn save_robot(
        &self,
        genotype: &G,
        _record: Option<&Record>,
        path: &Path,
        note: &str,
    ) -> Result<(), EvaluatorError> {
        let robot = self.mapper.robot(genotype)?;
        let text = robot
            .description()
            .map(|d| d.to_json(Some(note)))
            .ok_or(EvaluatorError::NoRobotFile)?;
        vsrlab_tasks::files::write_atomic(path, text.as_bytes()).map_err(|source| EvaluatorError::File {
            path: path.to_path_buf(),
            source,
        })
    }

    /// The episode with the experiment's episode seed (what `vsrlab simulate --robot
    /// best.robot.json --task-of OUT --seed <episode seed>` shows).
    fn save_replay(&self, genotype: &G, path: &Path, title: &str) -> Result<(), EvaluatorError> {
        let (outcome, _) = evaluate_traced(
            &self.mapper,
            genotype,
            self.task.task(),
            self.episode_seed,
            TraceLevel::Full,
        )?;
        let trace = outcome.trace.ok_or(EvaluatorError::NoTrace)?;
        let options = vsrlab_render::replay::ReplayOptions {
            title: title.to_string(),
            ..Default::default()
        };
        Ok(vsrlab_render::replay::save_replay(&trace, &options, path).map(drop)?)
    }
}

impl<M> RobotEvaluator<M> {
    /// The episode seed of a candidate: its own when the terrain is redrawn per evaluation.
    fn seed(&self, candidate_seed: u64) -> u64 {
        if self.random_terrain {
            candidate_seed
        } else {
            self.episode_seed
        }
    }

    /// The trace an evaluation needs for its features.
    fn level(&self) -> TraceLevel {
        match self.extract {
            Extract::Nothing => TraceLevel::None,
            Extract::Pose => TraceLevel::Full,
            Extract::Spectrum => TraceLevel::Center,
        }
    }

    /// Genotypes `batch` (indices into `genotypes`) of one episode group, their episodes run
    /// together; alone, or after a panic, each on its own ([`evaluate_guarded`]).
    fn evaluate_together<G>(&self, genotypes: &[&G], seeds: &[u64], batch: &[usize]) -> Vec<(usize, Evaluated)>
    where
        M: Mapper<G>,
    {
        let one_by_one = || {
            batch
                .iter()
                .map(|&i| (i, evaluate_guarded(self, genotypes[i], seeds[i])))
                .collect()
        };
        if batch.len() < 2 {
            return one_by_one();
        }
        let start = Instant::now();
        let together = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            let robots: Vec<Box<dyn vsrlab_tasks::Robot>> = batch
                .iter()
                .map(|&i| self.mapper.robot(genotypes[i]))
                .collect::<Result<_, _>>()
                .ok()?;
            let refs: Vec<&dyn vsrlab_tasks::Robot> = robots.iter().map(|r| r.as_ref()).collect();
            let episode_seeds: Vec<u64> = batch.iter().map(|&i| self.seed(seeds[i])).collect();
            let outcomes = self.task.task().run_episodes(&refs, &episode_seeds);
            (outcomes.len() == batch.len()).then_some((robots, episode_seeds, outcomes))
        }));
        let Ok(Some((robots, episode_seeds, outcomes))) = together else {
            return one_by_one();
        };
        let mut evaluations: Vec<(usize, Evaluated)> = batch
            .iter()
            .zip(robots.into_iter().zip(episode_seeds).zip(outcomes))
            .map(|(&i, ((robot, seed), outcome))| {
                let result = outcome.map(|o| (o, robot)).map_err(EvaluationError::from);
                (i, self.evaluated(genotypes[i], seed, result, start))
            })
            .collect();
        let seconds = start.elapsed().as_secs_f64() / batch.len() as f64;
        evaluations.iter_mut().for_each(|(_, e)| e.seconds = seconds);
        evaluations
    }

    /// What the optimizer and the logs get of an episode's result.
    fn evaluated<G>(
        &self,
        genotype: &G,
        seed: u64,
        result: Result<(vsrlab_tasks::Outcome, Box<dyn vsrlab_tasks::Robot>), EvaluationError>,
        start: Instant,
    ) -> Evaluated
    where
        M: Mapper<G>,
    {
        let (outcome, robot) = match result {
            Ok(done) => done,
            Err(e) => {
                // the body of a robot whose episode failed still goes into the record
                let body = self.mapper.robot(genotype).ok().and_then(|r| r.summary());
                return self.failed_with(seed, body.as_ref(), e.to_string(), start);
            }
        };
        let body = robot.summary();
        if let Some(bad) = outcome.fitness.iter().find(|f| !f.is_finite()) {
            return self.failed_with(seed, body.as_ref(), format!("non-finite fitness {bad}"), start);
        }
        let features = match (&self.extract, &outcome.trace) {
            (Extract::Pose, Some(trace)) => features::dynamic_pose(trace),
            (Extract::Spectrum, Some(trace)) => features::center_spectrum(trace),
            _ => Vec::new(),
        };
        let metric = |name: &str| outcome.metrics.get(name).copied();
        Evaluated {
            descriptor: body
                .as_ref()
                .map_or_else(|| vec![0.0; self.descriptors.len()], |b| self.descriptor(b)),
            features,
            record: Record {
                seed,
                fitness: outcome.fitness.first().copied(),
                distance: metric("distance"),
                velocity: metric("velocity"),
                voxels: Some(outcome.units),
                body: body.map(|b| b.text),
                error: None,
                objectives: (outcome.fitness.len() > 1).then(|| outcome.fitness.clone()),
                series: Default::default(),
            },
            objectives: outcome.fitness,
            seconds: start.elapsed().as_secs_f64(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// experiments/voxels3d/quadruped-distributed.toml, 0.05 s episodes.
    fn quadruped_experiment() -> Experiment {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../experiments/voxels3d/quadruped-distributed.toml"
        ))
        .unwrap()
        .replace("duration = 2.0", "duration = 0.05");
        crate::config::parse(&text, "quadruped-distributed.toml").unwrap()
    }

    #[test]
    fn a_batch_of_same_shape_robots_in_lanes_gives_every_genotype_its_own_evaluation() {
        let evaluator = RobotEvaluator::new(&quadruped_experiment()).unwrap();
        // 3D lanes: 8 episodes on a CPU with AVX-512, else 4; a full chunk and one with idle lanes
        let lanes = evaluator.task.task().episode_batch();
        assert!(lanes == 4 || lanes == 8, "{lanes}");
        let count = lanes + 3;
        let n = evaluator.genotype_length();
        let genotypes: Vec<Vec<f64>> = (0..count)
            .map(|g| (0..n).map(|i| ((g * 31 + i * 7) as f64 * 0.37).sin()).collect())
            .collect();
        let refs: Vec<&Vec<f64>> = genotypes.iter().collect();
        let seeds: Vec<u64> = (0..count as u64).map(|i| 100 + i).collect();
        let reported = std::sync::Mutex::new(Vec::new());
        let batch = evaluator
            .evaluate_batch_reporting(&refs, &seeds, &|i, _| reported.lock().unwrap().push(i))
            .unwrap();
        let mut reported = reported.into_inner().unwrap();
        reported.sort_unstable();
        assert_eq!(reported, (0..count).collect::<Vec<_>>());
        let mut distances = Vec::new();
        for ((g, &seed), together) in refs.iter().zip(&seeds).zip(&batch) {
            let alone = Evaluator::evaluate(&evaluator, *g, seed);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&together.objectives), bits(&alone.objectives));
            assert_eq!(together.record, alone.record);
            distances.push(alone.record.distance.unwrap());
        }
        distances.sort_by(f64::total_cmp);
        distances.dedup();
        assert_eq!(distances.len(), count, "each genotype its own gait: {distances:?}");
    }
}
