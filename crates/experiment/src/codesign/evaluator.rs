//! [`CodesignEvaluator`]: a genotype's body, trained by PPO on the experiment's EvoGym task, as
//! one evaluation for the runner.

use super::learn::{learn, learned_robot, Episode, LEARNING_CURVE, TRAINING_REWARD};
use crate::evaluator::{Evaluated, Evaluator, EvaluatorError, Record};
use std::collections::BTreeMap;
use std::path::Path;
use std::time::Instant;
use vsrlab_field::FieldError;
use vsrlab_learning::PpoConfig;
use vsrlab_tasks::kinds::evogym::{Material, MaterialGrid};
use vsrlab_tasks::kinds::RobotDescription;
use vsrlab_tasks::EvaluationError;

/// The morphology descriptors logged for the best body of every generation (`best_<name>` in
/// `generations.csv`), thesis §5.2.5.8: the share of the grid's cells present, and the shares of
/// the body's voxels that are rigid, soft, horizontal and vertical actuators.
pub const MATERIAL_COLUMNS: [&str; 5] = ["size", "rigid", "soft", "horizontal", "vertical"];

/// The descriptors of [`MATERIAL_COLUMNS`] for a body.
pub fn material_shares(body: &MaterialGrid) -> Vec<f64> {
    let present = body.cell_count().max(1) as f64;
    let share = |m: Material| body.present().filter(|c| c.2 == m).count() as f64 / present;
    vec![
        body.cell_count() as f64 / (body.width() * body.height()) as f64,
        share(Material::Rigid),
        share(Material::Soft),
        share(Material::HorizontalActuator),
        share(Material::VerticalActuator),
    ]
}

/// The body of a genotype, or why it has none (no actuator, nothing present).
pub type BodyOf<G> = Box<dyn Fn(&G) -> Result<MaterialGrid, FieldError> + Send + Sync>;

/// Evaluates genotypes by training PPO for their bodies (module docs of [`crate::codesign`]).
pub struct CodesignEvaluator<G> {
    body: BodyOf<G>,
    episode: Episode,
    ppo: PpoConfig,
    learning_curve: bool,
}

impl<G> CodesignEvaluator<G> {
    /// Bodies from `body`, trained with `ppo` on `episode`'s task; `learning_curve`: record the
    /// off-line reward after every iteration.
    pub fn new(body: BodyOf<G>, episode: Episode, ppo: PpoConfig, learning_curve: bool) -> Self {
        CodesignEvaluator {
            body,
            episode,
            ppo,
            learning_curve,
        }
    }
}

impl<G: Sync> Evaluator<G> for CodesignEvaluator<G> {
    fn evaluate(&self, genotype: &G, seed: u64) -> Evaluated {
        let start = Instant::now();
        let body = match (self.body)(genotype) {
            Ok(body) => body,
            Err(e) => return self.failure(seed, format!("genotype: {e}")),
        };
        let learned = learn(&body, self.episode, &self.ppo, self.learning_curve, seed);
        let mut series = BTreeMap::new();
        let (fitness, error) = match learned {
            Ok(learned) => {
                series.insert(TRAINING_REWARD.to_string(), learned.training);
                if self.learning_curve {
                    series.insert(LEARNING_CURVE.to_string(), learned.curve);
                }
                (learned.fitness, None)
            }
            Err(e) => (f64::NAN, Some(format!("learning: {e}"))),
        };
        Evaluated {
            objectives: vec![fitness],
            descriptor: Vec::new(),
            features: Vec::new(),
            record: Record {
                seed,
                fitness: error.is_none().then_some(fitness),
                distance: None,
                velocity: None,
                voxels: Some(body.cell_count()),
                body: Some(body.to_rows()),
                error,
                objectives: None,
                series,
            },
            seconds: start.elapsed().as_secs_f64(),
        }
    }

    fn genotype_columns(&self) -> &'static [&'static str] {
        &MATERIAL_COLUMNS
    }

    /// Trains the body again with its evaluation's seed (training is deterministic, so this is
    /// the policy its fitness came from) and writes the body with that policy as an EvoGym
    /// robot file.
    fn save_robot(&self, genotype: &G, record: Option<&Record>, path: &Path, note: &str) -> Result<(), EvaluatorError> {
        let genotype_error = |m: String| EvaluatorError::Robot(EvaluationError::Genotype(FieldError::message(m)));
        let seed = record.map(|r| r.seed).ok_or_else(|| {
            genotype_error("its evaluation record (the seed its brain was learned with) was not kept".into())
        })?;
        let body = (self.body)(genotype).map_err(|e| genotype_error(e.to_string()))?;
        let learned = learn(&body, self.episode, &self.ppo, false, seed).map_err(|e| genotype_error(e.to_string()))?;
        let robot = learned_robot(&body, self.episode, &learned.ppo);
        vsrlab_tasks::files::write_atomic(path, robot.to_json(Some(note)).as_bytes()).map_err(|source| {
            EvaluatorError::File {
                path: path.to_path_buf(),
                source,
            }
        })
    }

    fn genotype_stats(&self, genotype: &G) -> Vec<f64> {
        match (self.body)(genotype) {
            Ok(body) => material_shares(&body),
            Err(_) => vec![f64::NAN; MATERIAL_COLUMNS.len()],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use vsrlab_tasks::kinds::evogym::EvoGymTask;

    fn tiny() -> PpoConfig {
        PpoConfig {
            iterations: 2,
            steps_per_environment: 16,
            environments: 2,
            hidden: vec![8],
            ..PpoConfig::default()
        }
    }

    fn rows_evaluator(curve: bool) -> CodesignEvaluator<String> {
        let body: BodyOf<String> = Box::new(|rows: &String| {
            let grid = MaterialGrid::from_rows(rows)?;
            let cells: Vec<Material> = (0..grid.height())
                .flat_map(|y| (0..grid.width()).map(move |x| (x, y)))
                .map(|(x, y)| grid.at(x, y))
                .collect();
            super::super::kept_body(grid.width(), grid.height(), cells)
        });
        let episode = Episode {
            task: EvoGymTask::Walker,
            steps: 60,
        };
        CodesignEvaluator::new(body, episode, tiny(), curve)
    }

    #[test]
    fn an_evaluation_trains_records_its_curve_and_is_deterministic() {
        let evaluator = rows_evaluator(true);
        let body = "33333/30003/30003".to_string();
        let a = evaluator.evaluate(&body, 5);
        assert!(!a.failed(), "{:?}", a.record.error);
        let curve = a.record.series[LEARNING_CURVE].clone();
        assert_eq!(curve.len(), 3, "before training and after each of 2 iterations");
        assert_eq!(a.fitness(), curve[2]);
        assert_eq!(a.record.series[TRAINING_REWARD].len(), 2);
        assert!(curve.iter().all(|r| r.is_finite()));
        assert_eq!(a.record.body.as_deref(), Some("33333/30003/30003"));
        let b = evaluator.evaluate(&body, 5);
        assert_eq!((a.objectives, a.record), (b.objectives, b.record));
        // without the curve: the same fitness, one off-line episode
        let lean = rows_evaluator(false).evaluate(&body, 5);
        assert_eq!(lean.fitness(), curve[2]);
        assert!(!lean.record.series.contains_key(LEARNING_CURVE));
        // the descriptors: 9 of 15 cells present, all horizontal actuators
        assert_eq!(evaluator.genotype_stats(&body), vec![0.6, 0.0, 0.0, 1.0, 0.0]);
    }

    #[test]
    fn a_body_without_an_actuator_fails_with_the_reason() {
        let failed = rows_evaluator(true).evaluate(&"222/222".to_string(), 1);
        assert!(failed.failed() && failed.fitness().is_nan());
        assert!(
            failed.record.error.as_deref().unwrap().contains("no actuator"),
            "{:?}",
            failed.record.error
        );
    }
}
