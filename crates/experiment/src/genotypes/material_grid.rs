//! `[genotype] kind = "material-grid"`: the direct encoding of thesis ch. 5.2 (§5.2.4.2). The
//! genotype is the material grid itself (`width × height` cells, each empty, rigid, soft, a
//! horizontal or a vertical actuator), the body is its largest connected piece, and its fitness
//! is what PPO learns for that body on the experiment's EvoGym task ([`crate::codesign`]).
//!
//! - `width`, `height`: the grid (5 × 5);
//! - `mutation_rate`: each cell changes to one of the other four materials with this
//!   probability (0.1); the first population draws each cell uniformly among the five;
//! - `[genotype.ppo]`: PPO's settings ([`PpoConfig`]: `iterations`, `environments`, …; the
//!   EvoGym examples' by default);
//! - `learning_curve`: run an off-line episode after every PPO iteration and record the curve
//!   (true; false runs only the last one, the fitness).
//!
//! Grids have no crossover: they evolve with the GA (`mutation_probability = 1.0`; the thesis's
//! GA keeps the best fifth and fills the rest with their mutants: `population_size = 5`,
//! `offspring_size = 20`, `tournament_size = 1`, `initial_population_size = 25`), NSGA-II or
//! MAP-Elites. Genotypes are stored as rows of material digits, top row first (`"33000/01100"`).

use super::{check_operators, GenotypeConfig, GenotypeEntry, GenotypeKind, GenotypeSize};
use crate::codesign::{self, kept_body, BodyOf, CodesignEvaluator};
use crate::config::{Experiment, TaskConfig};
use crate::genotype::{fnv1a, Genotype};
use crate::optimizers::FieldError;
use crate::runner::{Observer, RunError, RunOptions, RunSummary};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use vsrlab_evolution::rng::{SeededRng, Stream};
use vsrlab_evolution::Representation as Variation;
use vsrlab_learning::PpoConfig;
use vsrlab_tasks::kinds::evogym::{Material, MaterialGrid};
use vsrlab_tasks::{EvaluationError, Representation, Robot, StoredGenotypes};

/// The `kind` tag of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MaterialGridTag {
    /// A material grid, directly encoded.
    MaterialGrid,
}

/// The `[genotype]` table of the direct encoding (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialGridGenotype {
    /// `material-grid`.
    pub kind: MaterialGridTag,
    /// Cells per row.
    #[serde(default = "five")]
    pub width: usize,
    /// Rows.
    #[serde(default = "five")]
    pub height: usize,
    /// Probability that a cell changes material in a mutation.
    #[serde(default = "tenth")]
    pub mutation_rate: f64,
    /// PPO's settings.
    #[serde(default)]
    pub ppo: PpoConfig,
    /// Record the off-line reward after every PPO iteration.
    #[serde(default = "yes")]
    pub learning_curve: bool,
}

fn five() -> usize {
    5
}

fn tenth() -> f64 {
    0.1
}

fn yes() -> bool {
    true
}

/// The materials a cell may take, in code order.
const MATERIALS: [Material; 5] = codesign::OUTPUT_MATERIALS;

/// A directly encoded grid: its cells as rows of material digits joined by `/`, top row first
/// (before the largest piece is kept).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct MaterialCells(pub String);

impl MaterialCells {
    /// The cells row by row, top first; an error naming the genotype when a digit is not a
    /// material or the rows are not `width × height`.
    fn cells(&self, width: usize, height: usize) -> Result<Vec<Material>, FieldError> {
        let rows: Vec<&str> = self.0.split('/').collect();
        if rows.len() != height || rows.iter().any(|r| r.chars().count() != width) {
            return Err(FieldError::new(
                "genotype",
                format!("'{}' is not {height} rows of {width} cells", self.0),
            ));
        }
        rows.iter()
            .flat_map(|r| r.chars())
            .map(|c| match Material::from_char(c) {
                Some(m) if MATERIALS.contains(&m) => Ok(m),
                _ => Err(FieldError::new(
                    "genotype",
                    format!("'{c}' is not a material digit 0-4"),
                )),
            })
            .collect()
    }

    fn of(cells: &[Material], width: usize) -> MaterialCells {
        let rows: Vec<String> = cells
            .chunks(width)
            .map(|row| row.iter().map(|m| char::from(b'0' + m.code())).collect())
            .collect();
        MaterialCells(rows.join("/"))
    }
}

impl Genotype for MaterialCells {
    /// FNV-1a over the rows.
    fn key(&self) -> u64 {
        fnv1a(self.0.bytes())
    }
}

/// The direct encoding's variation: uniform cells at first, per-cell mutation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridVariation {
    width: usize,
    height: usize,
    mutation_rate: f64,
}

impl Variation for GridVariation {
    type Genotype = MaterialCells;

    fn random(&self, rng: &mut SeededRng) -> MaterialCells {
        let cells: Vec<Material> = (0..self.width * self.height)
            .map(|_| MATERIALS[rng.below(MATERIALS.len())])
            .collect();
        MaterialCells::of(&cells, self.width)
    }

    /// Each cell, with probability `mutation_rate`, becomes one of the other four materials.
    fn mutate(&self, parent: &MaterialCells, rng: &mut SeededRng) -> MaterialCells {
        let Ok(mut cells) = parent.cells(self.width, self.height) else {
            return self.random(rng);
        };
        for cell in &mut cells {
            if rng.uniform() < self.mutation_rate {
                let others: Vec<Material> = MATERIALS.into_iter().filter(|m| m != cell).collect();
                *cell = others[rng.below(others.len())];
            }
        }
        MaterialCells::of(&cells, self.width)
    }

    /// Grids have no crossover: the first parent's mutation (unused: validation requires a
    /// mutation probability of 1).
    fn crossover(&self, first: &MaterialCells, _second: &MaterialCells, rng: &mut SeededRng) -> MaterialCells {
        self.mutate(first, rng)
    }
}

impl MaterialGridGenotype {
    fn variation(&self) -> GridVariation {
        GridVariation {
            width: self.width,
            height: self.height,
            mutation_rate: self.mutation_rate,
        }
    }

    fn body(&self) -> BodyOf<MaterialCells> {
        let (width, height) = (self.width, self.height);
        Box::new(move |g: &MaterialCells| kept_body(width, height, g.cells(width, height)?))
    }

    fn evaluator(
        &self,
        experiment: &Experiment,
        ppo: PpoConfig,
    ) -> Result<CodesignEvaluator<MaterialCells>, FieldError> {
        codesign::codesign_evaluator(experiment, self.body(), ppo, self.learning_curve)
    }
}

impl GenotypeKind for MaterialGridGenotype {
    fn name(&self) -> &'static str {
        "material-grid"
    }

    /// Learning curves and radius are medians over the population as EvoGym and the thesis count
    /// it: every body trained in a generation (for the GA, the parents and children before the
    /// best are kept).
    fn snapshots_whole_generation(&self) -> bool {
        true
    }

    fn implied_representation(&self, task: &TaskConfig) -> Option<Representation> {
        codesign::implied_representation(task, self.width, self.height)
    }

    fn validate(&self, experiment: &Experiment) -> Result<(), FieldError> {
        codesign::validate_codesign(experiment, self.width, self.height, &self.ppo)?;
        if !(0.0..=1.0).contains(&self.mutation_rate) {
            return Err(FieldError::new(
                "genotype.mutation_rate",
                format!("must be in [0, 1], got {}", self.mutation_rate),
            ));
        }
        check_operators(experiment, false)?;
        Ok(())
    }

    fn size(&self, _experiment: &Experiment) -> Result<GenotypeSize, FieldError> {
        let cells = self.width * self.height;
        Ok(GenotypeSize {
            genes: cells,
            text: format!(
                "{}×{} material grids ({cells} cells), each trained by {} PPO iterations",
                self.width, self.height, self.ppo.iterations
            ),
        })
    }

    fn run(
        &self,
        experiment: &Experiment,
        out: &Path,
        options: &RunOptions,
        observer: &mut dyn Observer,
    ) -> Result<Vec<RunSummary>, RunError> {
        let plan = check_operators(experiment, false)?;
        let evaluator = self.evaluator(experiment, self.ppo.clone())?;
        let variation = self.variation();
        let new_optimizer = |seed: u64| Ok(plan.build(variation.clone(), seed)?);
        codesign::run_codesign(experiment, &evaluator, &new_optimizer, out, options, observer)
    }

    fn time_evaluations(&self, experiment: &Experiment, count: usize) -> Result<(), FieldError> {
        let evaluator = self.evaluator(experiment, codesign::timed_ppo(&self.ppo).0)?;
        let variation = self.variation();
        let genotypes: Vec<MaterialCells> = (0..count)
            .map(|i| variation.initial(i, &mut SeededRng::derive(0, 0, i as u64, Stream::Initialisation)))
            .collect();
        codesign::time_codesign(&evaluator, &genotypes)
    }

    fn timing_scale(&self, _experiment: &Experiment) -> f64 {
        codesign::timed_ppo(&self.ppo).1
    }

    fn stored(&self, _experiment: &Experiment) -> Result<Arc<dyn StoredGenotypes>, FieldError> {
        Ok(Arc::new(LearnedBodies))
    }

    fn column_figures(&self) -> Vec<super::ColumnFigure> {
        codesign::column_figures()
    }

    fn fitness_name(&self) -> Option<&'static str> {
        Some(codesign::FITNESS_NAME)
    }
}

/// Stored co-design genotypes: their robots' brains are learned during the evaluation, so an
/// analysis cannot replay them from the genotype alone.
pub struct LearnedBodies;

impl StoredGenotypes for LearnedBodies {
    fn robot(&self, _genotype: &serde_json::Value) -> Result<Box<dyn Robot>, EvaluationError> {
        Err(EvaluationError::Genotype(FieldError::message(
            "a co-designed body's brain is learned by PPO during its evaluation: replay a run's best.robot.json instead",
        )))
    }
}

/// The body a stored genotype of this kind stands for (analyses of material shares).
pub fn stored_body(genotype: &serde_json::Value, width: usize, height: usize) -> Result<MaterialGrid, FieldError> {
    let cells: MaterialCells =
        serde_json::from_value(genotype.clone()).map_err(|e| FieldError::new("genotype", e.to_string()))?;
    kept_body(width, height, cells.cells(width, height)?)
}

/// The registry entry of `kind = "material-grid"`.
pub(crate) const ENTRY: GenotypeEntry = GenotypeEntry {
    name: "material-grid",
    decode: |v| crate::optimizers::decode::<MaterialGridGenotype>(v).map(GenotypeConfig::new),
};

#[cfg(test)]
mod tests {
    use super::*;

    fn variation() -> GridVariation {
        GridVariation {
            width: 5,
            height: 4,
            mutation_rate: 0.1,
        }
    }

    #[test]
    fn random_grids_use_every_material_and_mutants_change_about_a_tenth_of_the_cells() {
        let v = variation();
        let mut rng = SeededRng::derive(3, 0, 0, Stream::Initialisation);
        let grids: Vec<MaterialCells> = (0..200).map(|_| v.random(&mut rng)).collect();
        let all: String = grids.iter().map(|g| g.0.replace('/', "")).collect();
        for digit in ['0', '1', '2', '3', '4'] {
            let share = all.chars().filter(|&c| c == digit).count() as f64 / all.len() as f64;
            assert!((share - 0.2).abs() < 0.02, "{digit}: {share}");
        }
        let (mut changed, mut cells) = (0, 0);
        for g in &grids {
            let child = v.mutate(g, &mut rng);
            assert_eq!(child.0.len(), g.0.len());
            changed += child.0.chars().zip(g.0.chars()).filter(|(a, b)| a != b).count();
            cells += 20;
        }
        let rate = changed as f64 / cells as f64;
        assert!((rate - 0.1).abs() < 0.02, "{rate}");
    }

    #[test]
    fn stored_rows_become_their_largest_piece_and_bad_rows_name_the_genotype() {
        let rows = serde_json::json!("33000/01100/00000/04400");
        assert_eq!(stored_body(&rows, 5, 4).unwrap().to_rows(), "33000/01100/00000/00000");
        let e = stored_body(&serde_json::json!("3300/0110"), 5, 4).unwrap_err();
        assert_eq!(e.path, "genotype");
        let e = stored_body(&serde_json::json!("33000/01100/00000/04409"), 5, 4).unwrap_err();
        assert!(e.message.contains("'9'"), "{e}");
        assert_eq!(MaterialCells("33/00".into()).key(), MaterialCells("33/00".into()).key());
        assert_ne!(MaterialCells("33/00".into()).key(), MaterialCells("33/01".into()).key());
    }
}
