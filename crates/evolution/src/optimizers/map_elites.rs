//! MAP-Elites (Mouret & Clune 2015; Cully et al. 2015), thesis §3.3.5.2 "ME": a grid archive
//! over a behaviour descriptor that keeps the best individual of every cell.
//!
//! The first generation evaluates `initial_population` random genotypes; every later
//! generation evaluates `batch_size` children (thesis n_parents = 20), each the mutation of an
//! elite drawn uniformly from the archive (no crossover). Each evaluated individual goes to the
//! cell of its descriptor and replaces the incumbent only if strictly better (thesis: "empty or
//! stores an individual of lower fitness"; the TELO copy replaced on ties). Results are inserted
//! in candidate-id order.
//!
//! Binning per descriptor dimension: `bin = ⌊(d − min)/(max − min) · bins⌋` clamped to
//! `[0, bins − 1]`; out-of-range values go to the border cells. jgea v2.0.2 omitted the `− min`
//! (thesis-code-facts §2.7, §8.8); here the minimum is subtracted. A NaN descriptor component
//! goes to bin 0.

use crate::error::EvolutionError;
use crate::operators::{random_genotypes, Representation};
use crate::optimizer::{ensure, Candidate, Individual, Optimizer, Sense, Tell, Told};
use crate::rng::Stream;
use crate::search_state::SearchState;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// One dimension of the descriptor grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridAxis {
    /// Lower bound of the descriptor.
    pub min: f64,
    /// Upper bound of the descriptor.
    pub max: f64,
    /// Number of bins.
    pub bins: usize,
}

impl GridAxis {
    /// The bin of descriptor value `value` (see the module docs).
    pub fn bin(&self, value: f64) -> usize {
        let x = ((value - self.min) / (self.max - self.min) * self.bins as f64).floor();
        if x.is_nan() || x < 0.0 {
            0
        } else {
            (x as usize).min(self.bins - 1)
        }
    }
}

/// MAP-Elites' batch sizes as a user writes them in an experiment's `[optimizer]` table (and as
/// checkpoints keep them). `Default` gives the thesis' n_parents = 20 for both.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MapElitesSettings {
    /// Random genotypes evaluated in the first generation (thesis: n_parents = 20).
    pub initial_population: usize,
    /// Children per later generation (thesis: n_parents = 20).
    pub batch_size: usize,
}

impl Default for MapElitesSettings {
    fn default() -> Self {
        Self {
            initial_population: 20,
            batch_size: 20,
        }
    }
}

/// Parameters of [`MapElites`]: the grid, the batch sizes and the sense of the objective.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapElitesConfig {
    /// The grid, one axis per descriptor dimension.
    pub axes: Vec<GridAxis>,
    /// The batch sizes, written flat beside `axes` and `sense`.
    #[serde(flatten)]
    pub settings: MapElitesSettings,
    /// Whether fitness is maximised or minimised.
    pub sense: Sense,
}

impl MapElitesConfig {
    /// A grid with the given axes and the thesis batch sizes (20), maximising.
    pub fn new(axes: Vec<GridAxis>) -> Self {
        Self {
            axes,
            settings: MapElitesSettings::default(),
            sense: Sense::Maximize,
        }
    }
}

/// MAP-Elites over any [`Representation`] (see the module docs).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(bound(
    serialize = "R: Serialize, R::Genotype: Serialize",
    deserialize = "R: Deserialize<'de>, R::Genotype: Deserialize<'de>"
))]
pub struct MapElites<R: Representation> {
    config: MapElitesConfig,
    representation: R,
    #[serde(flatten)]
    state: SearchState<R::Genotype>,
    /// Elites by flat (row-major) cell index.
    archive: BTreeMap<u64, Individual<R::Genotype>>,
}

impl<R: Representation> MapElites<R> {
    /// A new run with the given run seed.
    pub fn new(config: MapElitesConfig, representation: R, seed: u64) -> Result<Self, EvolutionError> {
        ensure(!config.axes.is_empty(), || "MAP-Elites: at least one grid axis".into())?;
        for (i, axis) in config.axes.iter().enumerate() {
            ensure(axis.bins > 0 && axis.min < axis.max, || {
                format!("MAP-Elites: axis {i} needs bins > 0 and min < max")
            })?;
        }
        let cells = config
            .axes
            .iter()
            .try_fold(1u64, |acc, a| acc.checked_mul(a.bins as u64));
        ensure(cells.is_some(), || "MAP-Elites: too many cells".into())?;
        ensure(
            config.settings.initial_population > 0 && config.settings.batch_size > 0,
            || "MAP-Elites: initial_population and batch_size must be > 0".into(),
        )?;
        representation.validate()?;
        Ok(Self {
            config,
            representation,
            state: SearchState::new(seed),
            archive: BTreeMap::new(),
        })
    }

    /// The cell (one bin per axis) of a descriptor.
    pub fn cell_of(&self, descriptor: &[f64]) -> Vec<usize> {
        self.config
            .axes
            .iter()
            .zip(descriptor)
            .map(|(axis, &d)| axis.bin(d))
            .collect()
    }

    fn flat_index(&self, cell: &[usize]) -> u64 {
        cell.iter()
            .zip(&self.config.axes)
            .fold(0u64, |acc, (&b, axis)| acc * axis.bins as u64 + b as u64)
    }

    fn unflatten(&self, mut index: u64) -> Vec<usize> {
        let mut cell = vec![0; self.config.axes.len()];
        for (c, axis) in cell.iter_mut().zip(&self.config.axes).rev() {
            *c = (index % axis.bins as u64) as usize;
            index /= axis.bins as u64;
        }
        cell
    }

    /// The elites with their cells, in cell order.
    pub fn archive(&self) -> impl Iterator<Item = (Vec<usize>, &Individual<R::Genotype>)> {
        self.archive.iter().map(|(&k, v)| (self.unflatten(k), v))
    }

    /// The elite of a cell, if any.
    pub fn elite(&self, cell: &[usize]) -> Option<&Individual<R::Genotype>> {
        self.archive.get(&self.flat_index(cell))
    }

    /// Fraction of cells holding an elite.
    pub fn coverage(&self) -> f64 {
        let cells: u64 = self.config.axes.iter().map(|a| a.bins as u64).product();
        self.archive.len() as f64 / cells as f64
    }
}

impl<R: Representation> Optimizer for MapElites<R> {
    type Genotype = R::Genotype;

    fn ask(&mut self) -> Vec<Candidate<R::Genotype>> {
        if let Some(pending) = self.state.pending_batch() {
            return pending;
        }
        let genotypes: Vec<R::Genotype> = if self.archive.is_empty() {
            random_genotypes(
                &self.representation,
                &self.state,
                self.config.settings.initial_population,
            )
        } else {
            let elites: Vec<&Individual<R::Genotype>> = self.archive.values().collect();
            (0..self.config.settings.batch_size)
                .map(|i| {
                    let mut rng = self.state.rng(i, Stream::Variation);
                    let parent = elites[rng.below(elites.len())];
                    self.representation.mutate(&parent.genotype, &mut rng)
                })
                .collect()
        };
        let n = genotypes.len();
        self.state.hand_out(genotypes, n)
    }

    fn search_state(&self) -> &SearchState<R::Genotype> {
        &self.state
    }

    fn senses(&self) -> &[Sense] {
        std::slice::from_ref(&self.config.sense)
    }

    fn population(&self) -> Vec<&Individual<R::Genotype>> {
        self.archive.values().collect()
    }
}

impl<R: Representation, O> Tell<O> for MapElites<R> {
    fn tell(&mut self, results: Vec<Told<O>>) -> Result<(), EvolutionError> {
        let dims = self.config.axes.len();
        let (batch, evaluations) = self.state.take_told_checked(results, 1, |evaluations| {
            match evaluations.iter().enumerate().find(|(_, e)| e.descriptor.len() != dims) {
                Some((id, e)) => Err(EvolutionError::DescriptorLength {
                    id,
                    expected: dims,
                    got: e.descriptor.len(),
                }),
                None => Ok(()),
            }
        })?;
        let sense = self.config.sense;
        for individual in self.state.born_all(&batch, evaluations, std::slice::from_ref(&sense)) {
            let key = self.flat_index(&self.cell_of(&individual.descriptor));
            let replace = match self.archive.get(&key) {
                None => true,
                Some(incumbent) => {
                    sense.compare(individual.fitness(), incumbent.fitness()) == std::cmp::Ordering::Greater
                }
            };
            if replace {
                self.archive.insert(key, individual);
            }
        }
        self.state.advance(&batch);
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operators::RealVector;
    use crate::test_functions::sphere;
    use crate::Evaluation;
    use std::collections::HashMap;

    #[test]
    fn binning_subtracts_the_minimum_and_clamps() {
        let axis = GridAxis {
            min: 2.0,
            max: 4.0,
            bins: 4,
        };
        assert_eq!(axis.bin(2.0), 0);
        assert_eq!(axis.bin(2.49), 0);
        assert_eq!(axis.bin(2.5), 1);
        assert_eq!(axis.bin(3.99), 3);
        assert_eq!(axis.bin(4.0), 3);
        assert_eq!(axis.bin(-10.0), 0);
        assert_eq!(axis.bin(10.0), 3);
        assert_eq!(axis.bin(f64::NAN), 0);
    }

    /// A 5-D genotype whose first two genes, squashed by tanh, are the descriptor on a
    /// 10 × 10 grid over [−1, 1]²; fitness −‖x‖² (maximised). Starting from [−0.1, 0.1]^5
    /// (a single central cell region), the σ = 0.35 mutations must spread the archive over
    /// at least 95 % of the grid in 5 000 evaluations, and every cell must hold exactly the
    /// best individual ever evaluated in it.
    #[test]
    fn fills_a_2d_descriptor_space_and_keeps_the_best_per_cell() {
        let axes = vec![
            GridAxis {
                min: -1.0,
                max: 1.0,
                bins: 10,
            };
            2
        ];
        let rep = RealVector::thesis(5).with_init_range(-0.1, 0.1);
        let mut me = MapElites::new(MapElitesConfig::new(axes), rep, 3).unwrap();
        let mut best_seen: HashMap<Vec<usize>, f64> = HashMap::new();
        while me.evaluations() < 5_000 {
            let batch = me.ask();
            let mut told = Vec::new();
            for c in &batch {
                let d = vec![c.genotype[0].tanh(), c.genotype[1].tanh()];
                let f = -sphere(&c.genotype);
                let cell = me.cell_of(&d);
                let entry = best_seen.entry(cell).or_insert(f64::NEG_INFINITY);
                *entry = entry.max(f);
                told.push(c.told(Evaluation::single(f).with_descriptor(d)));
            }
            me.tell(told).unwrap();
        }
        assert!(me.coverage() >= 0.95, "coverage {}", me.coverage());
        assert_eq!(me.archive().count(), best_seen.len());
        for (cell, elite) in me.archive() {
            assert_eq!(elite.fitness(), best_seen[&cell], "cell {cell:?}");
            assert_eq!(me.cell_of(&elite.descriptor), cell);
        }
        assert_eq!(me.evaluations(), 5_000);
    }

    #[test]
    fn replacement_is_strict_and_descriptors_are_checked() {
        let axes = vec![GridAxis {
            min: 0.0,
            max: 1.0,
            bins: 2,
        }];
        let mut config = MapElitesConfig::new(axes);
        config.settings.initial_population = 3;
        let mut me = MapElites::new(config, RealVector::thesis(1), 0).unwrap();
        let batch = me.ask();
        let told: Vec<_> = batch
            .iter()
            .map(|c| c.told(Evaluation::single(1.0).with_descriptor(vec![0.1])))
            .collect();
        me.tell(told).unwrap();
        // All three tie: the first one stays.
        assert_eq!(me.archive().count(), 1);
        assert_eq!(me.elite(&[0]).unwrap().genotype, batch[0].genotype);
        let batch = me.ask();
        let bad: Vec<_> = batch.iter().map(|c| c.told(Evaluation::single(1.0))).collect();
        assert!(matches!(me.tell(bad), Err(EvolutionError::DescriptorLength { .. })));
    }
}
