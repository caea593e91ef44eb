//! [`SearchOptimizer`]: what the runner needs of an optimizer over any genotype, and
//! [`AnyOptimizer`], the optimizers of flat-vector experiments behind one serialisable value
//! (checkpoints hold it).

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{
    Candidate, CanonicalEs, CmaEs, EvolutionError, FeatureProvider, GeneticAlgorithm, Individual, MapElites, Nsga2,
    RealVector, Sense, SpeciatedEvolver, Tell, Told,
};

/// An optimizer as the runner drives it: ask, tell, counters, best and population, and serde
/// for checkpoints. Evaluations carry the speciation features as their outcome.
pub trait SearchOptimizer<G>: Serialize + DeserializeOwned + Send {
    /// The batch to evaluate now (the same batch again until [`SearchOptimizer::tell`]).
    fn ask(&mut self) -> Vec<Candidate<G>>;
    /// Hands back the results of the pending batch.
    fn tell(&mut self, results: Vec<Told<Vec<f64>>>) -> Result<(), EvolutionError>;
    /// Completed generations.
    fn generation(&self) -> u64;
    /// Evaluations told.
    fn evaluations(&self) -> u64;
    /// New genotypes evaluated.
    fn births(&self) -> u64;
    /// Whether each objective is maximised or minimised.
    fn senses(&self) -> Vec<Sense>;
    /// The best individual so far.
    fn best(&self) -> Option<&Individual<G>>;
    /// The current population (survivors, last batch, or archive).
    fn population(&self) -> Vec<&Individual<G>>;
    /// The last generation whole (the μ + λ GA's pool before truncation; otherwise the
    /// population): see `vsrlab_evolution::Optimizer::generation_pool`.
    fn generation_pool(&self) -> Vec<&Individual<G>>;
    /// Number of species (speciated evolvers only).
    fn species(&self) -> Option<usize> {
        None
    }
    /// Number of filled cells (archive-based optimizers only).
    fn archive_cells(&self) -> Option<usize> {
        None
    }
    /// Why the optimizer stopped by itself (e.g. `"cma-es:tolfun"`), if it did; the runner
    /// then ends the run with this as its stop reason.
    fn stop_reason(&self) -> Option<&'static str> {
        None
    }
}

/// Any ask/tell optimizer of `vsrlab-evolution` as a [`SearchOptimizer`]: how a genotype that is
/// not a flat vector (a graph, a material grid) goes through the runner.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(transparent)]
pub struct Searcher<T>(pub T);

/// An optimizer the runner drives through the `vsrlab-evolution` optimizer inside it: every
/// such wrapper is a [`SearchOptimizer`] by delegation, written once.
pub trait WrapsOptimizer<G: Clone> {
    /// The optimizer inside.
    fn optimizer(&self) -> &dyn Tell<Vec<f64>, Genotype = G>;
    /// The optimizer inside, mutably.
    fn optimizer_mut(&mut self) -> &mut dyn Tell<Vec<f64>, Genotype = G>;
    /// Number of species (speciated evolvers only).
    fn species(&self) -> Option<usize> {
        None
    }
    /// Number of filled cells (archive-based optimizers only).
    fn archive_cells(&self) -> Option<usize> {
        None
    }
}

impl<G, T> SearchOptimizer<G> for T
where
    G: Clone,
    T: WrapsOptimizer<G> + Serialize + DeserializeOwned + Send,
{
    fn ask(&mut self) -> Vec<Candidate<G>> {
        self.optimizer_mut().ask()
    }
    fn tell(&mut self, results: Vec<Told<Vec<f64>>>) -> Result<(), EvolutionError> {
        self.optimizer_mut().tell(results)
    }
    fn generation(&self) -> u64 {
        self.optimizer().generation()
    }
    fn evaluations(&self) -> u64 {
        self.optimizer().evaluations()
    }
    fn births(&self) -> u64 {
        self.optimizer().births()
    }
    fn senses(&self) -> Vec<Sense> {
        self.optimizer().senses().to_vec()
    }
    fn best(&self) -> Option<&Individual<G>> {
        self.optimizer().best()
    }
    fn population(&self) -> Vec<&Individual<G>> {
        self.optimizer().population()
    }
    fn generation_pool(&self) -> Vec<&Individual<G>> {
        self.optimizer().generation_pool()
    }
    fn stop_reason(&self) -> Option<&'static str> {
        self.optimizer().stop_reason()
    }
    fn species(&self) -> Option<usize> {
        WrapsOptimizer::species(self)
    }
    fn archive_cells(&self) -> Option<usize> {
        WrapsOptimizer::archive_cells(self)
    }
}

impl<G: Clone, T: Tell<Vec<f64>, Genotype = G>> WrapsOptimizer<G> for Searcher<T> {
    fn optimizer(&self) -> &dyn Tell<Vec<f64>, Genotype = G> {
        &self.0
    }
    fn optimizer_mut(&mut self) -> &mut dyn Tell<Vec<f64>, Genotype = G> {
        &mut self.0
    }
}

/// Where the speciated evolver takes its features from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum SpeciationFeatures {
    /// The genotype itself (SE-g).
    Genotype,
    /// The feature vector the evaluator computed (SE-s: pose, SE-b: spectrum).
    Outcome,
}

impl FeatureProvider<Vec<f64>, Vec<f64>> for SpeciationFeatures {
    fn features(&self, genotype: &Vec<f64>, outcome: &Vec<f64>) -> Vec<f64> {
        match self {
            SpeciationFeatures::Genotype => genotype.clone(),
            SpeciationFeatures::Outcome => outcome.clone(),
        }
    }
}

/// One of the flat-vector optimizers, as a single serialisable value.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[allow(clippy::large_enum_variant)]
pub enum AnyOptimizer {
    /// μ + λ GA.
    Ga(GeneticAlgorithm<RealVector>),
    /// Canonical ES.
    Es(CanonicalEs),
    /// CMA-ES.
    CmaEs(CmaEs),
    /// Speciated evolver.
    Se(SpeciatedEvolver<RealVector, SpeciationFeatures>),
    /// MAP-Elites.
    MapElites(MapElites<RealVector>),
    /// NSGA-II.
    Nsga2(Nsga2<RealVector>),
}

impl WrapsOptimizer<Vec<f64>> for AnyOptimizer {
    fn optimizer(&self) -> &dyn Tell<Vec<f64>, Genotype = Vec<f64>> {
        match self {
            AnyOptimizer::Ga(o) => o,
            AnyOptimizer::Es(o) => o,
            AnyOptimizer::CmaEs(o) => o,
            AnyOptimizer::Se(o) => o,
            AnyOptimizer::MapElites(o) => o,
            AnyOptimizer::Nsga2(o) => o,
        }
    }

    fn optimizer_mut(&mut self) -> &mut dyn Tell<Vec<f64>, Genotype = Vec<f64>> {
        match self {
            AnyOptimizer::Ga(o) => o,
            AnyOptimizer::Es(o) => o,
            AnyOptimizer::CmaEs(o) => o,
            AnyOptimizer::Se(o) => o,
            AnyOptimizer::MapElites(o) => o,
            AnyOptimizer::Nsga2(o) => o,
        }
    }

    fn species(&self) -> Option<usize> {
        match self {
            AnyOptimizer::Se(se) => Some(se.species().len()),
            _ => None,
        }
    }

    fn archive_cells(&self) -> Option<usize> {
        match self {
            AnyOptimizer::MapElites(me) => Some(me.archive().count()),
            _ => None,
        }
    }
}
