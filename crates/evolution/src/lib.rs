//! # vsrlab-evolution
//!
//! Evolutionary optimizers driven by ask/tell, knowing nothing of robots: any genotype, any
//! fitness. They are the solvers of the thesis (Pigozzi 2023) and of its jgea code:
//!
//! | optimizer | file | thesis use |
//! | --- | --- | --- |
//! | [`GeneticAlgorithm`] (μ + λ) | `optimizers/ga.rs` | GA, §3.3.5.2; ch. 4 |
//! | [`CanonicalEs`] | `optimizers/canonical_es.rs` | ES, §3.3.5.2; ch. 5.3 |
//! | [`CmaEs`] | `optimizers/cma_es.rs` | ch. 6 |
//! | [`SpeciatedEvolver`] (k-means species) | `optimizers/speciated.rs` | SE-g/s/b, §3.3.5.2 |
//! | [`MapElites`] | `optimizers/map_elites.rs` | ME, §3.3.5.2 |
//! | [`Nsga2`] | `optimizers/nsga2.rs` | ch. 5.1 |
//!
//! ## Protocol
//! [`Optimizer::ask`] returns a batch of [`Candidate`]s; the caller evaluates them in any order,
//! on any number of threads or machines, and returns [`Told`] results (tagged with the candidate
//! id) through [`Tell::tell`]. Fitness is a vector of objectives ([`Evaluation`]); each
//! optimizer has a [`Sense`] per objective, [`Sense::Maximize`] by default (robots maximise
//! velocity). NaN fitness is the worst. Evaluations may carry a descriptor (MAP-Elites) and an
//! arbitrary outcome (the speciated evolver's [`FeatureProvider`]).
//!
//! ## Guarantees
//! - **Determinism**: every random draw comes from a generator derived from
//!   (run seed, generation, index, purpose) ([`rng`]); results are a pure function of the seed
//!   and the fitness values, independent of evaluation order and thread count.
//! - **Checkpoints**: optimizer state is serde-serialisable (including a pending batch);
//!   deserialising and continuing gives bit-identical results to an uninterrupted run. Non-finite
//!   fitness values survive JSON (written as `"NaN"`, `"inf"`, `"-inf"`).
//! - Numbers do not depend on `rand`/`rand_distr` versions: uniform, integer and Gaussian
//!   variates are computed in [`rng`] from ChaCha8 words.
//!
//! ## Example
//! ```
//! use vsrlab_evolution::{run_to_budget, CmaEs, CmaEsConfig, Evaluation, Optimizer, Sense, Stop};
//! use vsrlab_evolution::test_functions::sphere;
//!
//! let config = CmaEsConfig { sense: Sense::Minimize, ..CmaEsConfig::default() };
//! let mut cma = CmaEs::new(config, 10, 42).unwrap();
//! let stop = Stop::evaluations(10_000).or_target(1e-8);
//! run_to_budget(&mut cma, |c| Evaluation::single(sphere(&c.genotype)), &stop).unwrap();
//! assert!(cma.best().unwrap().fitness() <= 1e-8);
//! ```
#![warn(missing_docs)]

mod dense;
pub mod error;
mod kmeans;
pub mod linalg;
pub mod neat;
pub mod operators;
pub mod optimizer;
pub mod optimizers;
pub mod pareto;
pub mod rng;
pub mod run;
pub mod search_state;
mod selection;
pub mod serde_float;
mod simd;
pub mod test_functions;

pub use error::EvolutionError;
pub use operators::{RealVector, Representation, SbxPolynomial};
pub use optimizer::{Candidate, Counters, Evaluation, Individual, Optimizer, Sense, Tell, Told};
pub use optimizers::canonical_es::{CanonicalEs, CanonicalEsConfig, EsSettings};
pub use optimizers::cma_es::{CmaEs, CmaEsConfig, CmaParameters, CmaSettings, RestartStrategy};
pub use optimizers::cma_termination::{CmaTermination, Criterion};
pub use optimizers::ga::{GaConfig, GaSettings, GeneticAlgorithm};
pub use optimizers::map_elites::{GridAxis, MapElites, MapElitesConfig, MapElitesSettings};
pub use optimizers::neat::{Neat, NeatConfig, NeatSettings};
pub use optimizers::nsga2::{Nsga2, Nsga2Config, Nsga2Settings};
pub use optimizers::speciated::{FeatureProvider, GenotypeFeatures, SeConfig, SeSettings, SpeciatedEvolver, Species};
pub use run::{run_to_budget, RunSummary, Stop, StopReason};
pub use search_state::SearchState;
