//! `[genotype] kind = "cppn"`: the indirect encoding of thesis ch. 5.2 (§5.2.4.3, after Cheney et
//! al. 2013 and EvoGym's CPPN-NEAT). The genotype is a CPPN (a NEAT network genome with inputs
//! row, column and distance from the centre, and five outputs, one per material) evolved by
//! `[optimizer] kind = "neat"`; the body is the grid it draws ([`cppn_body`]), and its fitness is
//! what PPO learns for that body on the experiment's EvoGym task ([`crate::codesign`]).
//!
//! - `width`, `height`: the grid (5 × 5);
//! - `[genotype.ppo]`, `learning_curve`: as `material-grid`.
//!
//! The first genomes connect the three inputs to the five outputs directly (weights and biases
//! from N(0, 1)); EvoGym's configuration instead starts from one hidden node and half of the
//! direct connections (docs/ch5.2.md).

use super::material_grid::LearnedBodies;
use super::{GenotypeConfig, GenotypeEntry, GenotypeKind, GenotypeSize};
use crate::codesign::{self, cppn_body, BodyOf, CodesignEvaluator, OUTPUT_MATERIALS};
use crate::config::{Experiment, TaskConfig};
use crate::genotype::{fnv1a, Genotype};
use crate::optimizers::{FieldError, NeatParams, OptimizerConfig, Searcher};
use crate::runner::{Observer, RunError, RunOptions, RunSummary};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::sync::Arc;
use vsrlab_evolution::neat::{Innovations, NetworkGenome};
use vsrlab_evolution::rng::{SeededRng, Stream};
use vsrlab_evolution::Sense;
use vsrlab_learning::PpoConfig;
use vsrlab_tasks::{Representation, StoredGenotypes};

/// The CPPN's inputs: row, column, distance from the centre.
pub const CPPN_INPUTS: usize = 3;

/// The `kind` tag of the table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CppnTag {
    /// A CPPN drawing a material grid.
    Cppn,
}

/// The `[genotype]` table of the CPPN encoding (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CppnGenotype {
    /// `cppn`.
    pub kind: CppnTag,
    /// Cells per row.
    #[serde(default = "five")]
    pub width: usize,
    /// Rows.
    #[serde(default = "five")]
    pub height: usize,
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

fn yes() -> bool {
    true
}

impl Genotype for NetworkGenome {
    /// FNV-1a over the JSON form.
    fn key(&self) -> u64 {
        fnv1a(serde_json::to_vec(self).expect("genomes serialise"))
    }
}

/// NEAT's table of the experiment, or the field and message.
fn neat(experiment: &Experiment) -> Result<&NeatParams, FieldError> {
    match &experiment.optimizer {
        OptimizerConfig::Neat(params) => Ok(params),
        other => Err(FieldError::new(
            "optimizer.kind",
            format!("a cppn genotype evolves with neat, not {}", other.kind().name()),
        )),
    }
}

impl CppnGenotype {
    fn body(&self) -> BodyOf<NetworkGenome> {
        let (width, height) = (self.width, self.height);
        Box::new(move |g: &NetworkGenome| cppn_body(g, width, height))
    }

    fn evaluator(
        &self,
        experiment: &Experiment,
        ppo: PpoConfig,
    ) -> Result<CodesignEvaluator<NetworkGenome>, FieldError> {
        codesign::codesign_evaluator(experiment, self.body(), ppo, self.learning_curve)
    }
}

impl GenotypeKind for CppnGenotype {
    fn name(&self) -> &'static str {
        "cppn"
    }

    /// As the direct encoding's (NEAT's population already is its whole generation).
    fn snapshots_whole_generation(&self) -> bool {
        true
    }

    fn implied_representation(&self, task: &TaskConfig) -> Option<Representation> {
        codesign::implied_representation(task, self.width, self.height)
    }

    fn validate(&self, experiment: &Experiment) -> Result<(), FieldError> {
        codesign::validate_codesign(experiment, self.width, self.height, &self.ppo)?;
        neat(experiment)?;
        Ok(())
    }

    fn size(&self, _experiment: &Experiment) -> Result<GenotypeSize, FieldError> {
        let outputs = OUTPUT_MATERIALS.len();
        Ok(GenotypeSize {
            genes: CPPN_INPUTS * outputs + outputs,
            text: format!(
                "CPPNs from {CPPN_INPUTS} inputs and {outputs} outputs drawing {}×{} material grids, each trained by {} PPO iterations",
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
        let params = neat(experiment)?.clone();
        let evaluator = self.evaluator(experiment, self.ppo.clone())?;
        let new_optimizer = |seed: u64| {
            let neat = params.build_networks(CPPN_INPUTS, OUTPUT_MATERIALS.len(), &[Sense::Maximize], seed)?;
            Ok(Searcher(neat))
        };
        codesign::run_codesign(experiment, &evaluator, &new_optimizer, out, options, observer)
    }

    fn time_evaluations(&self, experiment: &Experiment, count: usize) -> Result<(), FieldError> {
        let activation = neat(experiment)?.output_activation;
        let evaluator = self.evaluator(experiment, codesign::timed_ppo(&self.ppo).0)?;
        let outputs = OUTPUT_MATERIALS.len();
        let mut innovations = Innovations::new((CPPN_INPUTS + outputs) as u32);
        let genotypes: Vec<NetworkGenome> = (0..count)
            .map(|i| {
                let mut rng = SeededRng::derive(0, 0, i as u64, Stream::Initialisation);
                NetworkGenome::initial(CPPN_INPUTS, outputs, activation, &mut innovations, &mut rng)
            })
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

/// The registry entry of `kind = "cppn"`.
pub(crate) const ENTRY: GenotypeEntry = GenotypeEntry {
    name: "cppn",
    decode: |v| crate::optimizers::decode::<CppnGenotype>(v).map(GenotypeConfig::new),
};
