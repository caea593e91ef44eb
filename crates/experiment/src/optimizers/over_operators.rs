//! The optimizers whose algorithm asks nothing of a genotype but its variation operators (GA,
//! NSGA-II, MAP-Elites), over any genotype kind: an [`OperatorPlan`] is what an `[optimizer]`
//! table says, [`OperatorOptimizer`] the running optimizer over one kind's operators.

use super::any::WrapsOptimizer;
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{
    EvolutionError, GaConfig, GeneticAlgorithm, MapElites, MapElitesConfig, Nsga2, Nsga2Config, Representation, Tell,
};

/// An optimizer's algorithm and settings, ready to run over any [`Representation`].
#[derive(Debug, Clone, PartialEq)]
pub enum OperatorPlan {
    /// μ + λ GA.
    Ga(GaConfig),
    /// NSGA-II, with or without duplicate elimination.
    Nsga2(Nsga2Config, bool),
    /// MAP-Elites (mutation only).
    MapElites(MapElitesConfig),
}

impl OperatorPlan {
    /// The share of children made by mutation alone (1 for MAP-Elites, which never crosses
    /// over): a genotype kind without crossover needs 1.
    pub fn mutation_probability(&self) -> f64 {
        match self {
            OperatorPlan::Ga(c) => c.settings.mutation_probability,
            OperatorPlan::Nsga2(c, _) => c.settings.mutation_probability,
            OperatorPlan::MapElites(_) => 1.0,
        }
    }

    /// The optimizer of a run with this seed, varying genotypes with `representation`.
    pub fn build<R: Representation>(
        &self,
        representation: R,
        seed: u64,
    ) -> Result<OperatorOptimizer<R>, EvolutionError> {
        Ok(match self {
            OperatorPlan::Ga(c) => OperatorOptimizer::Ga(GeneticAlgorithm::new(c.clone(), representation, seed)?),
            OperatorPlan::Nsga2(c, duplicates) => OperatorOptimizer::Nsga2(
                Nsga2::new(c.clone(), representation, seed)?.with_duplicate_elimination(*duplicates),
            ),
            OperatorPlan::MapElites(c) => {
                OperatorOptimizer::MapElites(MapElites::new(c.clone(), representation, seed)?)
            }
        })
    }
}

/// One of the optimizers over variation operators, as a single serialisable value (checkpoints
/// hold it).
#[derive(Serialize, Deserialize)]
#[serde(bound(
    serialize = "R: Serialize, R::Genotype: Serialize",
    deserialize = "R: Deserialize<'de>, R::Genotype: Deserialize<'de>"
))]
pub enum OperatorOptimizer<R: Representation> {
    /// μ + λ GA.
    Ga(GeneticAlgorithm<R>),
    /// NSGA-II.
    Nsga2(Nsga2<R>),
    /// MAP-Elites.
    MapElites(MapElites<R>),
}

impl<R: Representation> WrapsOptimizer<R::Genotype> for OperatorOptimizer<R> {
    fn optimizer(&self) -> &dyn Tell<Vec<f64>, Genotype = R::Genotype> {
        match self {
            OperatorOptimizer::Ga(o) => o,
            OperatorOptimizer::Nsga2(o) => o,
            OperatorOptimizer::MapElites(o) => o,
        }
    }

    fn optimizer_mut(&mut self) -> &mut dyn Tell<Vec<f64>, Genotype = R::Genotype> {
        match self {
            OperatorOptimizer::Ga(o) => o,
            OperatorOptimizer::Nsga2(o) => o,
            OperatorOptimizer::MapElites(o) => o,
        }
    }

    fn archive_cells(&self) -> Option<usize> {
        match self {
            OperatorOptimizer::MapElites(me) => Some(me.archive().count()),
            _ => None,
        }
    }
}
