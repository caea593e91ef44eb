//! The optimizers of an experiment behind one serialisable value ([`AnyOptimizer`]), built from
//! the `[optimizer]` table of an experiment file.
//!
//! All search flat real vectors (body genes then brain genes). Evaluations carry the
//! speciation features as their outcome (`Vec<f64>`, empty unless SE-s / SE-b) and the
//! MAP-Elites descriptor in their descriptor.

use crate::config::{OptimizerConfig, SeFeatures};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{
    Candidate, CanonicalEs, CanonicalEsConfig, CmaEs, CmaEsConfig, EvolutionError, FeatureProvider, GaConfig,
    GeneticAlgorithm, GridAxis, Individual, MapElites, MapElitesConfig, RealVector, SeConfig, Sense, SpeciatedEvolver,
    Tell, Told,
};

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

/// One of the optimizers, as a single serialisable value (checkpoints hold it).
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
}

fn real_vector(dimension: usize, init: [f64; 2], sigma: f64, crossover: [f64; 2], crossover_sigma: f64) -> RealVector {
    RealVector {
        dimension,
        init_min: init[0],
        init_max: init[1],
        mutation_sigma: sigma,
        crossover_min: crossover[0],
        crossover_max: crossover[1],
        crossover_sigma,
    }
}

impl AnyOptimizer {
    /// Builds the optimizer of `config` for genotypes of `dimension` genes and a run seed.
    pub fn new(config: &OptimizerConfig, dimension: usize, seed: u64) -> Result<Self, EvolutionError> {
        Ok(match config {
            OptimizerConfig::Ga(p) => AnyOptimizer::Ga(GeneticAlgorithm::new(
                GaConfig {
                    population_size: p.population_size,
                    offspring_size: p.offspring_size,
                    tournament_size: p.tournament_size,
                    mutation_probability: p.mutation_probability,
                    reevaluate_survivors: p.reevaluate_survivors,
                    sense: Sense::Maximize,
                },
                real_vector(
                    dimension,
                    p.init_range,
                    p.mutation_sigma,
                    p.crossover_range,
                    p.crossover_sigma,
                ),
                seed,
            )?),
            OptimizerConfig::Es(p) => AnyOptimizer::Es(CanonicalEs::new(
                CanonicalEsConfig {
                    population_size: p.population_size,
                    parents: p.parents.unwrap_or((p.population_size / 4).max(1)),
                    sigma: p.sigma,
                    init_min: p.init_range[0],
                    init_max: p.init_range[1],
                    sense: Sense::Maximize,
                },
                dimension,
                seed,
            )?),
            OptimizerConfig::CmaEs(p) => AnyOptimizer::CmaEs(CmaEs::new(
                CmaEsConfig {
                    population_size: p.population_size,
                    sigma0: p.sigma0,
                    init_min: p.init_range[0],
                    init_max: p.init_range[1],
                    active: p.active,
                    sense: Sense::Maximize,
                },
                dimension,
                seed,
            )?),
            OptimizerConfig::Se(p) => AnyOptimizer::Se(SpeciatedEvolver::new(
                SeConfig {
                    population_size: p.population_size,
                    species: p.species,
                    rank_base: p.alpha,
                    min_species_size_for_elitism: p.elite_min_species_size,
                    mutation_probability: p.mutation_probability,
                    kmeans_iterations: p.kmeans_iterations,
                    sense: Sense::Maximize,
                },
                real_vector(
                    dimension,
                    p.init_range,
                    p.mutation_sigma,
                    p.crossover_range,
                    p.crossover_sigma,
                ),
                match p.features {
                    SeFeatures::Genotype => SpeciationFeatures::Genotype,
                    SeFeatures::Shape | SeFeatures::Behaviour => SpeciationFeatures::Outcome,
                },
                seed,
            )?),
            OptimizerConfig::MapElites(p) => AnyOptimizer::MapElites(MapElites::new(
                MapElitesConfig {
                    axes: p
                        .axes
                        .iter()
                        .map(|a| GridAxis {
                            min: a.min,
                            max: a.max,
                            bins: a.bins,
                        })
                        .collect(),
                    initial_population: p.initial_population,
                    batch_size: p.batch_size,
                    sense: Sense::Maximize,
                },
                real_vector(dimension, p.init_range, p.mutation_sigma, [0.0, 1.0], 0.0),
                seed,
            )?),
        })
    }

    /// The optimizer inside, behind the common ask/tell interface.
    fn inner(&self) -> &dyn Tell<Vec<f64>, Genotype = Vec<f64>> {
        match self {
            AnyOptimizer::Ga(o) => o,
            AnyOptimizer::Es(o) => o,
            AnyOptimizer::CmaEs(o) => o,
            AnyOptimizer::Se(o) => o,
            AnyOptimizer::MapElites(o) => o,
        }
    }

    /// The optimizer inside, mutably.
    fn inner_mut(&mut self) -> &mut dyn Tell<Vec<f64>, Genotype = Vec<f64>> {
        match self {
            AnyOptimizer::Ga(o) => o,
            AnyOptimizer::Es(o) => o,
            AnyOptimizer::CmaEs(o) => o,
            AnyOptimizer::Se(o) => o,
            AnyOptimizer::MapElites(o) => o,
        }
    }

    /// The batch to evaluate now (the same batch again until [`tell`](Self::tell)).
    pub fn ask(&mut self) -> Vec<Candidate<Vec<f64>>> {
        self.inner_mut().ask()
    }

    /// Hands back the results of the pending batch.
    pub fn tell(&mut self, results: Vec<Told<Vec<f64>>>) -> Result<(), EvolutionError> {
        self.inner_mut().tell(results)
    }

    /// Completed generations.
    pub fn generation(&self) -> u64 {
        self.inner().generation()
    }

    /// Evaluations told.
    pub fn evaluations(&self) -> u64 {
        self.inner().evaluations()
    }

    /// New genotypes evaluated.
    pub fn births(&self) -> u64 {
        self.inner().births()
    }

    /// The best individual so far.
    pub fn best(&self) -> Option<&Individual<Vec<f64>>> {
        self.inner().best()
    }

    /// The current population (survivors, last batch, or archive).
    pub fn population(&self) -> Vec<&Individual<Vec<f64>>> {
        self.inner().population()
    }

    /// Number of species (speciated evolver only).
    pub fn species(&self) -> Option<usize> {
        match self {
            AnyOptimizer::Se(se) => Some(se.species().len()),
            _ => None,
        }
    }

    /// Number of filled cells (MAP-Elites only).
    pub fn archive_cells(&self) -> Option<usize> {
        match self {
            AnyOptimizer::MapElites(me) => Some(me.archive().count()),
            _ => None,
        }
    }
}
