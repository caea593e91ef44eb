//! NEAT (Stanley & Miikkulainen 2002) as an ask/tell optimizer over [`NetworkGenome`]s: a
//! generational search whose population is divided into species by compatibility distance,
//! each species given offspring in proportion to its mean fitness (explicit fitness sharing),
//! children made within a species by crossover of two of its fittest or by mutation of one,
//! and species that stop improving removed. Settings follow the NEAT paper, with neat-python's
//! defaults (what EvoGym's CPPN-NEAT used) where the paper is silent.
//!
//! Decisions where the sources differ or are silent:
//! - Fitness sharing is applied as neat-python does: each species' mean fitness, shifted by the
//!   population's lowest fitness and divided by its range, sets its share of the offspring (at
//!   least 2 each); a failed evaluation (NaN) counts as the lowest fitness.
//! - A species' representative in the next generation is the member closest to its old one;
//!   species are tried in the order they were founded.
//! - Each species keeps its `elitism` fittest members unchanged; a species that has not improved
//!   its best fitness for `stagnation` generations is removed, unless it holds the best genome.

use crate::error::EvolutionError;
use crate::neat::genome::Mutation;
use crate::neat::{Activation, Innovations, NetworkGenome};
use crate::optimizer::{ensure, Candidate, Individual, Optimizer, Sense, Tell, Told};
use crate::rng::Stream;
use crate::search_state::SearchState;
use serde::{Deserialize, Serialize};

/// NEAT's settings as an experiment's `[optimizer]` table writes them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct NeatSettings {
    /// Genomes per generation (thesis ch. 5.2: 25; neat-python: 150).
    pub population_size: usize,
    /// Distance under which a genome joins a species (3.0, EvoGym's CPPN-NEAT).
    pub compatibility_threshold: f64,
    /// c1, weight of excess genes in the distance (1.0).
    pub excess_coefficient: f64,
    /// c2, weight of disjoint genes (1.0).
    pub disjoint_coefficient: f64,
    /// c3, weight of the mean weight difference of matching genes (0.4).
    pub weight_coefficient: f64,
    /// Share of a species' fittest members that may be parents (0.2).
    pub survival_threshold: f64,
    /// Members of each species copied unchanged into the next generation (1).
    pub elitism: usize,
    /// Probability that a child is a crossover of two parents rather than a copy of one (0.75).
    pub crossover_rate: f64,
    /// Generations without improvement after which a species is removed (15).
    pub stagnation: u64,
    /// Mutation rates and the activations nodes may have.
    pub mutation: Mutation,
}

impl Default for NeatSettings {
    fn default() -> Self {
        NeatSettings {
            population_size: 150,
            compatibility_threshold: 3.0,
            excess_coefficient: 1.0,
            disjoint_coefficient: 1.0,
            weight_coefficient: 0.4,
            survival_threshold: 0.2,
            elitism: 1,
            crossover_rate: 0.75,
            stagnation: 15,
            mutation: Mutation::default(),
        }
    }
}

/// NEAT's parameters: its settings, the shape of the networks and the sense of the fitness.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NeatConfig {
    /// The settings.
    #[serde(flatten)]
    pub settings: NeatSettings,
    /// Inputs of every network.
    pub inputs: usize,
    /// Outputs of every network.
    pub outputs: usize,
    /// The output nodes' activation at first (they mutate like the others).
    pub output_activation: Activation,
    /// Whether fitness is maximised or minimised.
    pub sense: Sense,
}

/// A species: its representative, its members in the current population, and how long it has
/// gone without improving.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Species {
    /// Founding order.
    pub id: u64,
    /// The genome new members are compared with.
    pub representative: NetworkGenome,
    /// Indices of its members in the population.
    pub members: Vec<usize>,
    /// Its best fitness so far (as utility: larger is better).
    pub best: f64,
    /// The generation in which `best` last rose.
    pub improved: u64,
}

/// The NEAT optimizer (see the module docs).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Neat {
    config: NeatConfig,
    #[serde(flatten)]
    state: SearchState<NetworkGenome>,
    innovations: Innovations,
    species: Vec<Species>,
    next_species: u64,
    /// The last evaluated generation.
    population: Vec<Individual<NetworkGenome>>,
    /// The genomes of the next batch, made when the last one was told.
    offspring: Vec<NetworkGenome>,
}

impl Neat {
    /// A new run with the given run seed.
    pub fn new(config: NeatConfig, seed: u64) -> Result<Self, EvolutionError> {
        let s = &config.settings;
        ensure(s.population_size >= 2, || {
            "NEAT: population_size must be at least 2".into()
        })?;
        ensure(config.inputs > 0 && config.outputs > 0, || {
            "NEAT: networks need inputs and outputs".into()
        })?;
        ensure(
            s.compatibility_threshold.is_finite() && s.compatibility_threshold > 0.0,
            || "NEAT: compatibility_threshold must be > 0".into(),
        )?;
        ensure(
            (0.0..=1.0).contains(&s.survival_threshold) && s.survival_threshold > 0.0,
            || "NEAT: survival_threshold must be in (0, 1]".into(),
        )?;
        ensure((0.0..=1.0).contains(&s.crossover_rate), || {
            "NEAT: crossover_rate must be in [0, 1]".into()
        })?;
        let m = &s.mutation;
        for (name, p) in [
            ("weight_rate", m.weight_rate),
            ("weight_replace_rate", m.weight_replace_rate),
            ("add_connection", m.add_connection),
            ("add_node", m.add_node),
            ("delete_connection", m.delete_connection),
            ("delete_node", m.delete_node),
            ("activation_rate", m.activation_rate),
        ] {
            ensure((0.0..=1.0).contains(&p), || {
                format!("NEAT: mutation.{name} must be in [0, 1]")
            })?;
        }
        ensure(m.weight_power.is_finite() && m.weight_power >= 0.0, || {
            "NEAT: mutation.weight_power must be ≥ 0".into()
        })?;
        let nodes = (config.inputs + config.outputs) as u32;
        Ok(Neat {
            config,
            state: SearchState::new(seed),
            innovations: Innovations::new(nodes),
            species: Vec::new(),
            next_species: 0,
            population: Vec::new(),
            offspring: Vec::new(),
        })
    }

    /// The species of the last evaluated generation.
    pub fn species(&self) -> &[Species] {
        &self.species
    }

    fn utility(&self, individual: &Individual<NetworkGenome>) -> f64 {
        self.config.sense.utility(individual.fitness())
    }

    /// Sorts the population into species: each genome joins the first species whose
    /// representative is nearer than the threshold, or founds one.
    fn speciate(&mut self) {
        let s = &self.config.settings;
        let distance = |a: &NetworkGenome, b: &NetworkGenome| {
            a.distance(b, s.excess_coefficient, s.disjoint_coefficient, s.weight_coefficient)
        };
        for species in &mut self.species {
            species.members.clear();
        }
        for (i, individual) in self.population.iter().enumerate() {
            let genome = &individual.genotype;
            match self
                .species
                .iter_mut()
                .find(|sp| distance(&sp.representative, genome) < s.compatibility_threshold)
            {
                Some(species) => species.members.push(i),
                None => {
                    self.species.push(Species {
                        id: self.next_species,
                        representative: genome.clone(),
                        members: vec![i],
                        best: f64::NEG_INFINITY,
                        improved: self.state.generation(),
                    });
                    self.next_species += 1;
                }
            }
        }
        self.species.retain(|sp| !sp.members.is_empty());
        let generation = self.state.generation();
        let utilities: Vec<f64> = self.population.iter().map(|i| self.utility(i)).collect();
        for species in &mut self.species {
            let best = species
                .members
                .iter()
                .map(|&m| utilities[m])
                .fold(f64::NEG_INFINITY, f64::max);
            if best > species.best {
                species.best = best;
                species.improved = generation;
            }
            let old = species.representative.clone();
            let nearest = species
                .members
                .iter()
                .copied()
                .min_by(|&a, &b| {
                    distance(&old, &self.population[a].genotype)
                        .total_cmp(&distance(&old, &self.population[b].genotype))
                })
                .expect("non-empty");
            species.representative = self.population[nearest].genotype.clone();
        }
        // stagnant species go, except the one that holds the best genome
        let overall = utilities.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let stagnation = self.config.settings.stagnation;
        self.species
            .retain(|sp| generation.saturating_sub(sp.improved) < stagnation || sp.best >= overall);
    }

    /// Offspring per species, in proportion to their shifted mean fitness, at least 2 each,
    /// adding up to the population size (largest remainders).
    fn shares(&self) -> Vec<usize> {
        let utilities: Vec<f64> = self.population.iter().map(|i| self.utility(i)).collect();
        let finite: Vec<f64> = utilities.iter().copied().filter(|u| u.is_finite()).collect();
        let low = finite.iter().copied().fold(f64::INFINITY, f64::min);
        let high = finite.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let range = (high - low).max(1.0);
        let adjusted: Vec<f64> = self
            .species
            .iter()
            .map(|sp| {
                let sum: f64 = sp
                    .members
                    .iter()
                    .map(|&m| {
                        if utilities[m].is_finite() {
                            (utilities[m] - low) / range
                        } else {
                            0.0
                        }
                    })
                    .sum();
                sum / sp.members.len() as f64
            })
            .collect();
        let total: f64 = adjusted.iter().sum();
        let n = self.config.settings.population_size;
        let min = 2.min(n / self.species.len().max(1)).max(1);
        let free = n.saturating_sub(min * self.species.len());
        let exact: Vec<f64> = adjusted
            .iter()
            .map(|a| {
                if total > 0.0 {
                    free as f64 * a / total
                } else {
                    free as f64 / adjusted.len() as f64
                }
            })
            .collect();
        let mut shares: Vec<usize> = exact.iter().map(|e| min + e.floor() as usize).collect();
        let mut order: Vec<usize> = (0..shares.len()).collect();
        order.sort_by(|&a, &b| {
            (exact[b] - exact[b].floor())
                .total_cmp(&(exact[a] - exact[a].floor()))
                .then(a.cmp(&b))
        });
        let mut k = 0;
        while shares.iter().sum::<usize>() < n {
            shares[order[k % order.len()]] += 1;
            k += 1;
        }
        while shares.iter().sum::<usize>() > n {
            let biggest = (0..shares.len())
                .max_by_key(|&i| (shares[i], std::cmp::Reverse(i)))
                .expect("species");
            shares[biggest] -= 1;
        }
        shares
    }

    /// The next generation's genomes: each species' elites, then children of its fittest.
    fn reproduce(&mut self) -> Vec<NetworkGenome> {
        let shares = self.shares();
        let settings = self.config.settings.clone();
        let mut next = Vec::with_capacity(settings.population_size);
        for (species, &share) in self.species.clone().iter().zip(&shares) {
            let mut ranked = species.members.clone();
            ranked.sort_by(|&a, &b| {
                self.utility(&self.population[b])
                    .total_cmp(&self.utility(&self.population[a]))
                    .then(a.cmp(&b))
            });
            let elites = settings.elitism.min(share).min(ranked.len());
            next.extend(ranked[..elites].iter().map(|&m| self.population[m].genotype.clone()));
            let parents = ((settings.survival_threshold * ranked.len() as f64).ceil() as usize).clamp(1, ranked.len());
            for _ in elites..share {
                let mut rng = self.state.rng(next.len(), Stream::Variation);
                let first = ranked[rng.below(parents)];
                let mut child = if parents > 1 && rng.uniform() < settings.crossover_rate {
                    let second = ranked[rng.below(parents)];
                    // the fitter parent gives the structure (ranked is best first)
                    let (fitter, other) =
                        if ranked.iter().position(|&m| m == first) <= ranked.iter().position(|&m| m == second) {
                            (first, second)
                        } else {
                            (second, first)
                        };
                    self.population[fitter]
                        .genotype
                        .crossover(&self.population[other].genotype, &mut rng)
                } else {
                    self.population[first].genotype.clone()
                };
                child.mutate(&settings.mutation, &mut self.innovations, &mut rng);
                next.push(child);
            }
        }
        next
    }
}

impl Optimizer for Neat {
    type Genotype = NetworkGenome;

    fn ask(&mut self) -> Vec<Candidate<NetworkGenome>> {
        if let Some(pending) = self.state.pending_batch() {
            return pending;
        }
        let genotypes = if self.population.is_empty() {
            (0..self.config.settings.population_size)
                .map(|i| {
                    let mut rng = self.state.rng(i, Stream::Initialisation);
                    NetworkGenome::initial(
                        self.config.inputs,
                        self.config.outputs,
                        self.config.output_activation,
                        &mut self.innovations,
                        &mut rng,
                    )
                })
                .collect()
        } else {
            self.offspring.clone()
        };
        let n = genotypes.len();
        self.state.hand_out(genotypes, n)
    }

    fn search_state(&self) -> &SearchState<NetworkGenome> {
        &self.state
    }

    fn senses(&self) -> &[Sense] {
        std::slice::from_ref(&self.config.sense)
    }

    fn population(&self) -> Vec<&Individual<NetworkGenome>> {
        self.population.iter().collect()
    }
}

impl<O> Tell<O> for Neat {
    fn tell(&mut self, results: Vec<Told<O>>) -> Result<(), EvolutionError> {
        let (batch, evaluations) = self.state.take_told(results, 1)?;
        let senses = [self.config.sense];
        self.population = self.state.born_all(&batch, evaluations, &senses);
        self.speciate();
        self.offspring = self.reproduce();
        self.state.advance(&batch);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimizer::Evaluation;

    /// 4 − Σ (output − XOR)² over the four cases.
    fn xor_fitness(genome: &NetworkGenome) -> f64 {
        let cases = [
            ([0.0, 0.0], 0.0),
            ([0.0, 1.0], 1.0),
            ([1.0, 0.0], 1.0),
            ([1.0, 1.0], 0.0),
        ];
        4.0 - cases
            .iter()
            .map(|(x, y)| (genome.evaluate(x)[0] - y).powi(2))
            .sum::<f64>()
    }

    fn xor_config() -> NeatConfig {
        NeatConfig {
            settings: NeatSettings {
                mutation: Mutation {
                    activations: vec![Activation::Sigmoid],
                    ..Mutation::default()
                },
                ..NeatSettings::default()
            },
            inputs: 2,
            outputs: 1,
            output_activation: Activation::Sigmoid,
            sense: Sense::Maximize,
        }
    }

    /// Generations NEAT needs to reach XOR fitness 3.9 (at most `limit`), and the best.
    fn solve_xor(seed: u64, limit: u64) -> (u64, f64, Neat) {
        let mut neat = Neat::new(xor_config(), seed).unwrap();
        while neat.generation() < limit {
            let batch = neat.ask();
            let told = batch
                .iter()
                .map(|c| c.told(Evaluation::single(xor_fitness(&c.genotype))))
                .collect();
            neat.tell(told).unwrap();
            if neat.best().unwrap().fitness() > 3.9 {
                break;
            }
        }
        let best = neat.best().unwrap().fitness();
        (neat.generation(), best, neat)
    }

    /// Whether a genome classifies the four XOR cases (output on the right side of 0.5), the
    /// NEAT paper's "solved".
    fn classifies_xor(genome: &NetworkGenome) -> bool {
        [
            ([0.0, 0.0], false),
            ([0.0, 1.0], true),
            ([1.0, 0.0], true),
            ([1.0, 1.0], false),
        ]
        .iter()
        .all(|(x, y)| (genome.evaluate(x)[0] > 0.5) == *y)
    }

    /// Evaluations until a genome of a told batch classifies XOR (None within `limit`
    /// generations).
    fn evaluations_to_classify(seed: u64, limit: u64) -> Option<u64> {
        let mut neat = Neat::new(xor_config(), seed).unwrap();
        while neat.generation() < limit {
            let batch = neat.ask();
            let mut told = Vec::with_capacity(batch.len());
            for (k, c) in batch.iter().enumerate() {
                if classifies_xor(&c.genotype) {
                    return Some(neat.evaluations() + k as u64 + 1);
                }
                told.push(c.told(Evaluation::single(xor_fitness(&c.genotype))));
            }
            neat.tell(told).unwrap();
        }
        None
    }

    /// Median evaluations to classify XOR over `seeds` runs of at most 100 generations (unsolved
    /// runs count as never: the median is then over the solved ones only if more than half
    /// solved), and the runs solved.
    fn xor_median(seeds: std::ops::Range<u64>) -> (f64, usize) {
        let n = seeds.end - seeds.start;
        let mut counts: Vec<f64> = seeds
            .map(|s| evaluations_to_classify(s, 100).map_or(f64::INFINITY, |e| e as f64))
            .collect();
        counts.sort_by(f64::total_cmp);
        let solved = counts.iter().filter(|c| c.is_finite()).count();
        (counts[n as usize / 2], solved)
    }

    /// The NEAT paper (Stanley & Miikkulainen 2002, §4.1): XOR solved in 4,755 evaluations on
    /// average over 100 runs (150 genomes, never failing); ours, with neat-python's defaults, on
    /// 20 seeds here and 100 in the ignored test below (docs/ch5.2.md has the figures).
    #[test]
    fn xor_is_classified_in_evaluations_comparable_to_the_paper() {
        let (median, solved) = xor_median(0..20);
        eprintln!("XOR: median {median} evaluations, {solved} of 20 runs solved within 100 generations");
        assert!(solved >= 18, "{solved} of 20 solved");
        assert!(median < 2.0 * 4755.0, "median {median} evaluations");
    }

    /// `cargo test -p vsrlab-evolution --release xor_over_100 -- --ignored --nocapture`
    #[test]
    #[ignore = "100 runs: a measurement for docs/ch5.2.md"]
    fn xor_over_100_runs() {
        let (median, solved) = xor_median(0..100);
        let mut counts: Vec<u64> = (0..100).filter_map(|s| evaluations_to_classify(s, 100)).collect();
        counts.sort_unstable();
        let mean = counts.iter().sum::<u64>() as f64 / counts.len() as f64;
        eprintln!(
            "XOR over 100 runs: {solved} solved within 100 generations; median {median}, mean {mean:.0}, min {}, max {} evaluations",
            counts[0],
            counts[counts.len() - 1]
        );
    }

    #[test]
    fn it_evolves_xor_with_hidden_nodes() {
        let mut solved = 0;
        for seed in 0..5 {
            let (generations, best, neat) = solve_xor(seed, 150);
            eprintln!(
                "seed {seed}: fitness {best:.4} after {generations} generations, {} species",
                neat.species().len()
            );
            if best > 3.9 {
                solved += 1;
                let hidden = neat
                    .best()
                    .unwrap()
                    .genotype
                    .nodes
                    .iter()
                    .filter(|n| n.kind == crate::neat::NodeKind::Hidden)
                    .count();
                assert!(hidden > 0, "XOR needs a hidden node");
            }
            assert_eq!(neat.population().len(), 150);
        }
        assert!(solved >= 4, "{solved} of 5 seeds solved XOR within 150 generations");
    }

    #[test]
    fn a_run_resumes_from_its_serialised_state_bit_identically() {
        let (_, _, mut neat) = solve_xor(9, 3);
        let text = serde_json::to_string(&neat).unwrap();
        let mut copy: Neat = serde_json::from_str(&text).unwrap();
        for _ in 0..3 {
            for n in [&mut neat, &mut copy] {
                let batch = n.ask();
                let told = batch
                    .iter()
                    .map(|c| c.told(Evaluation::single(xor_fitness(&c.genotype))))
                    .collect();
                n.tell(told).unwrap();
            }
        }
        assert_eq!(
            serde_json::to_string(&neat).unwrap(),
            serde_json::to_string(&copy).unwrap()
        );
    }

    #[test]
    fn bad_settings_are_refused() {
        let mut config = xor_config();
        config.settings.compatibility_threshold = f64::NAN;
        assert!(Neat::new(config, 0).is_err());
        let mut config = xor_config();
        config.settings.mutation.add_node = 2.0;
        let e = Neat::new(config, 0).unwrap_err().to_string();
        assert!(e.contains("mutation.add_node"), "{e}");
    }
}
