//! Determinism and checkpointing, for every optimizer:
//! - the same seed gives bit-identical runs; another seed gives a different run;
//! - results told in a permuted order, or collected from several threads in completion order,
//!   give bit-identical runs;
//! - serialising the optimizer to JSON mid-run (after a tell, and between ask and tell),
//!   deserialising it and continuing gives a run bit-identical to the uninterrupted one.
//!
//! "Bit-identical" is checked on the whole serialised state (population, archive, mean,
//! covariance, counters, best), written with `serde_json`'s `float_roundtrip`.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::sync::Mutex;
use vsrlab_evolution::rng::{SeededRng, Stream};
use vsrlab_evolution::test_functions::{rastrigin, zdt1};
use vsrlab_evolution::*;

const GENERATIONS: u64 = 12;

/// Rastrigin plus a small term from the candidate's evaluation seed, so that the seeds handed
/// out are checked too.
fn noisy_rastrigin(c: &Candidate<Vec<f64>>) -> Evaluation<[f64; 2]> {
    let noise = (c.seed >> 11) as f64 / (1u64 << 53) as f64;
    let x = &c.genotype;
    Evaluation::single(rastrigin(x) + 1e-3 * noise)
        .with_descriptor(vec![x[0].tanh(), x[1].tanh()])
        .with_outcome([x[0].sin(), x[1].cos()])
}

fn zdt_evaluation(c: &Candidate<Vec<f64>>) -> Evaluation<[f64; 2]> {
    Evaluation::multi(zdt1(&c.genotype).to_vec()).with_outcome([0.0, 0.0])
}

/// How results are handed back.
#[derive(Clone, Copy, PartialEq)]
enum Order {
    AsAsked,
    Permuted,
    Threads,
}

/// Where (if anywhere) the run is checkpointed and resumed.
#[derive(Clone, Copy, PartialEq)]
enum Checkpoint {
    None,
    AfterTell(u64),
    BetweenAskAndTell(u64),
}

fn evaluate_batch<F>(batch: &[Candidate<Vec<f64>>], f: F, order: Order, generation: u64) -> Vec<Told<[f64; 2]>>
where
    F: Fn(&Candidate<Vec<f64>>) -> Evaluation<[f64; 2]> + Sync,
{
    match order {
        Order::AsAsked => batch.iter().map(|c| c.told(f(c))).collect(),
        Order::Permuted => {
            let mut told: Vec<_> = batch.iter().map(|c| c.told(f(c))).collect();
            let mut rng = SeededRng::derive(99, generation, 0, Stream::Variation);
            for i in (1..told.len()).rev() {
                told.swap(i, rng.below(i + 1));
            }
            told
        }
        Order::Threads => {
            let out = Mutex::new(Vec::new());
            std::thread::scope(|scope| {
                for chunk in batch.chunks(batch.len().div_ceil(4)) {
                    let out = &out;
                    let f = &f;
                    scope.spawn(move || {
                        for c in chunk.iter().rev() {
                            let told = c.told(f(c));
                            out.lock().unwrap().push(told);
                        }
                    });
                }
            });
            out.into_inner().unwrap()
        }
    }
}

fn run<T, F>(mut opt: T, f: F, order: Order, checkpoint: Checkpoint) -> String
where
    T: Tell<[f64; 2], Genotype = Vec<f64>> + Serialize + DeserializeOwned,
    F: Fn(&Candidate<Vec<f64>>) -> Evaluation<[f64; 2]> + Sync,
{
    let round_trip = |o: &T| -> T {
        let text = serde_json::to_string(o).unwrap();
        serde_json::from_str(&text).unwrap()
    };
    for g in 0..GENERATIONS {
        if checkpoint == Checkpoint::AfterTell(g) {
            opt = round_trip(&opt);
        }
        let batch = opt.ask();
        if checkpoint == Checkpoint::BetweenAskAndTell(g) {
            opt = round_trip(&opt);
            assert_eq!(opt.ask(), batch, "ask() after resume must return the pending batch");
        }
        opt.tell(evaluate_batch(&batch, &f, order, g)).unwrap();
    }
    assert_eq!(opt.generation(), GENERATIONS);
    serde_json::to_string(&opt).unwrap()
}

fn check_all<T, F>(make: impl Fn(u64) -> T, f: F)
where
    T: Tell<[f64; 2], Genotype = Vec<f64>> + Serialize + DeserializeOwned,
    F: Fn(&Candidate<Vec<f64>>) -> Evaluation<[f64; 2]> + Sync + Copy,
{
    let reference = run(make(5), f, Order::AsAsked, Checkpoint::None);
    assert_eq!(
        reference,
        run(make(5), f, Order::AsAsked, Checkpoint::None),
        "same seed"
    );
    assert_ne!(
        reference,
        run(make(6), f, Order::AsAsked, Checkpoint::None),
        "other seed"
    );
    assert_eq!(
        reference,
        run(make(5), f, Order::Permuted, Checkpoint::None),
        "permuted"
    );
    assert_eq!(reference, run(make(5), f, Order::Threads, Checkpoint::None), "threads");
    for g in [0, 1, GENERATIONS / 2] {
        assert_eq!(
            reference,
            run(make(5), f, Order::AsAsked, Checkpoint::AfterTell(g)),
            "resume after tell at generation {g}"
        );
        assert_eq!(
            reference,
            run(make(5), f, Order::Permuted, Checkpoint::BetweenAskAndTell(g)),
            "resume between ask and tell at generation {g}"
        );
    }
}

#[test]
fn genetic_algorithm() {
    for reevaluate_survivors in [false, true] {
        check_all(
            |seed| {
                let config = GaConfig {
                    settings: GaSettings {
                        population_size: 20,
                        offspring_size: 15,
                        reevaluate_survivors,
                        ..GaSettings::default()
                    },
                    sense: Sense::Minimize,
                    ties: Vec::new(),
                };
                GeneticAlgorithm::new(config, RealVector::thesis(6), seed).unwrap()
            },
            noisy_rastrigin,
        );
    }
}

#[test]
fn canonical_es() {
    check_all(
        |seed| {
            let config = CanonicalEsConfig {
                sense: Sense::Minimize,
                ..CanonicalEsConfig::default()
            };
            CanonicalEs::new(config, 6, seed).unwrap()
        },
        noisy_rastrigin,
    );
}

#[test]
fn cma_es() {
    for active in [true, false] {
        check_all(
            |seed| {
                let config = CmaEsConfig {
                    settings: CmaSettings {
                        active,
                        ..CmaSettings::default()
                    },
                    sense: Sense::Minimize,
                    ..CmaEsConfig::default()
                };
                CmaEs::new(config, 6, seed).unwrap()
            },
            noisy_rastrigin,
        );
    }
}

/// An SE-b-like provider: features from the outcome, serialisable so the run can checkpoint.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
struct OutcomeFeatures;

impl FeatureProvider<Vec<f64>, [f64; 2]> for OutcomeFeatures {
    fn features(&self, _genotype: &Vec<f64>, outcome: &[f64; 2]) -> Vec<f64> {
        outcome.to_vec()
    }
}

#[test]
fn speciated_evolver() {
    let config = || SeConfig {
        settings: SeSettings {
            population_size: 30,
            species: 4,
            ..SeSettings::default()
        },
        sense: Sense::Minimize,
    };
    check_all(
        |seed| SpeciatedEvolver::new(config(), RealVector::thesis(6), GenotypeFeatures, seed).unwrap(),
        noisy_rastrigin,
    );
    check_all(
        |seed| SpeciatedEvolver::new(config(), RealVector::thesis(6), OutcomeFeatures, seed).unwrap(),
        noisy_rastrigin,
    );
}

#[test]
fn map_elites() {
    check_all(
        |seed| {
            let axis = GridAxis {
                min: -1.0,
                max: 1.0,
                bins: 5,
            };
            let config = MapElitesConfig {
                sense: Sense::Minimize,
                ..MapElitesConfig::new(vec![axis; 2])
            };
            MapElites::new(config, RealVector::thesis(6), seed).unwrap()
        },
        noisy_rastrigin,
    );
}

#[test]
fn nsga2() {
    check_all(
        |seed| {
            let config = Nsga2Config {
                settings: Nsga2Settings {
                    population_size: 20,
                    offspring_size: 20,
                    ..Nsga2Config::new(vec![Sense::Minimize; 2]).settings
                },
                ..Nsga2Config::new(vec![Sense::Minimize; 2])
            };
            Nsga2::new(config, SbxPolynomial::new(8, 0.0, 1.0), seed).unwrap()
        },
        zdt_evaluation,
    );
    check_all(
        |seed| {
            let config = Nsga2Config {
                settings: Nsga2Settings {
                    population_size: 20,
                    offspring_size: 10,
                    mutation_probability: 1.0,
                },
                ..Nsga2Config::new(vec![Sense::Minimize; 2])
            };
            let rep = RealVector::thesis(8)
                .with_init_range(0.0, 1.0)
                .with_mutation_sigma(0.05);
            Nsga2::new(config, rep, seed).unwrap()
        },
        |c| {
            let x: Vec<f64> = c.genotype.iter().map(|v| v.clamp(0.0, 1.0)).collect();
            Evaluation::multi(zdt1(&x).to_vec()).with_outcome([0.0, 0.0])
        },
    );
}

/// A run interrupted by a checkpoint reaches the same budget through `run_to_budget`.
#[test]
fn run_to_budget_resumes_towards_the_same_budget() {
    let make = || {
        let config = CmaEsConfig {
            sense: Sense::Minimize,
            ..CmaEsConfig::default()
        };
        CmaEs::new(config, 5, 1).unwrap()
    };
    let f = |c: &Candidate<Vec<f64>>| Evaluation::single(rastrigin(&c.genotype));
    let stop = Stop::evaluations(500);
    let mut whole = make();
    let summary = run_to_budget(&mut whole, f, &stop).unwrap();
    let mut part = make();
    run_to_budget(&mut part, f, &Stop::evaluations(200)).unwrap();
    let text = serde_json::to_string(&part).unwrap();
    let mut resumed: CmaEs = serde_json::from_str(&text).unwrap();
    let resumed_summary = run_to_budget(&mut resumed, f, &stop).unwrap();
    assert_eq!(summary, resumed_summary);
    assert_eq!(
        serde_json::to_string(&whole).unwrap(),
        serde_json::to_string(&resumed).unwrap()
    );
    assert_eq!(
        run_to_budget(&mut make(), f, &Stop::default()),
        Err(EvolutionError::Unbounded)
    );
}

/// Non-finite fitness values (e.g. an exploding simulation) do not break checkpoints.
#[test]
fn checkpoints_survive_non_finite_fitness() {
    let config = GaConfig {
        settings: GaSettings {
            population_size: 6,
            offspring_size: 6,
            ..GaSettings::default()
        },
        ..GaConfig::default()
    };
    let mut ga = GeneticAlgorithm::new(config, RealVector::thesis(2), 3).unwrap();
    for _ in 0..3 {
        let batch = ga.ask();
        let told = batch
            .iter()
            .map(|c| {
                let f = match c.id % 3 {
                    0 => f64::NAN,
                    1 => f64::INFINITY,
                    _ => c.genotype[0],
                };
                c.told(Evaluation::single(f))
            })
            .collect();
        ga.tell(told).unwrap();
    }
    let text = serde_json::to_string(&ga).unwrap();
    let back: GeneticAlgorithm<RealVector> = serde_json::from_str(&text).unwrap();
    assert_eq!(text, serde_json::to_string(&back).unwrap());
    assert_eq!(back.best().unwrap().fitness(), f64::INFINITY);
}
