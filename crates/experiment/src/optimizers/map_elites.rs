//! MAP-Elites over the thesis' morphology descriptors (ME, §3.3.5.2).

use super::check::{positive, range, sigma};
use super::{
    decode_flat, real_vector, single, AnyOptimizer, OperatorPlan, OptimizerConfig, OptimizerEntry, OptimizerKind,
};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::{EvolutionError, GridAxis, MapElites, MapElitesConfig, MapElitesSettings, Sense};
use vsrlab_field::FieldError;

/// A morphology descriptor usable as a MAP-Elites axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Descriptor {
    /// d_num: number of voxels.
    Voxels,
    /// d_elong: eccentricity of the moment-equivalent ellipse.
    Elongation,
    /// d_compact: voxels ÷ cells in the convex hull.
    Compactness,
}

impl Descriptor {
    /// Its name among a robot kind's descriptors ([`vsrlab_tasks::BodySummary`]).
    pub fn name(self) -> &'static str {
        match self {
            Descriptor::Voxels => "voxels",
            Descriptor::Elongation => "elongation",
            Descriptor::Compactness => "compactness",
        }
    }
}

/// One MAP-Elites axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// The descriptor.
    pub descriptor: Descriptor,
    /// Lower bound.
    pub min: f64,
    /// Upper bound.
    pub max: f64,
    /// Bins (thesis 10).
    #[serde(default = "ten")]
    pub bins: usize,
}

fn ten() -> usize {
    10
}

/// Parameters of MAP-Elites: the descriptor axes, its batch sizes ([`MapElitesSettings`],
/// declared once, in the optimizer's crate) and the mutation's parameters, written flat in the
/// table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct MapElitesParams {
    /// The grid (default: the thesis' d_num over [0, W·H], d_elong and d_compact over [0, 1],
    /// 10 bins each).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub axes: Vec<Axis>,
    /// Random genotypes of the first generation and children per generation (thesis
    /// n_parents = 20 each).
    #[serde(flatten)]
    pub map_elites: MapElitesSettings,
    /// Initial genes uniform in [min, max).
    pub init_range: [f64; 2],
    /// σ of the Gaussian mutation (thesis 0.35).
    pub mutation_sigma: f64,
}

impl Default for MapElitesParams {
    fn default() -> Self {
        Self {
            axes: Vec::new(),
            map_elites: MapElitesSettings::default(),
            init_range: [-1.0, 1.0],
            mutation_sigma: 0.35,
        }
    }
}

impl MapElitesParams {
    /// MAP-Elites' settings for an objective of this sense.
    fn config(&self, senses: &[Sense]) -> MapElitesConfig {
        MapElitesConfig {
            axes: self
                .axes
                .iter()
                .map(|a| GridAxis {
                    min: a.min,
                    max: a.max,
                    bins: a.bins,
                })
                .collect(),
            settings: self.map_elites.clone(),
            sense: single(senses),
        }
    }
}

impl OptimizerKind for MapElitesParams {
    fn name(&self) -> &'static str {
        "map-elites"
    }

    fn validate(&self) -> Result<(), FieldError> {
        positive("initial_population", self.map_elites.initial_population)?;
        positive("batch_size", self.map_elites.batch_size)?;
        range("init_range", self.init_range)?;
        sigma("mutation_sigma", self.mutation_sigma)?;
        for (i, axis) in self.axes.iter().enumerate() {
            if !(axis.min.is_finite() && axis.max.is_finite() && axis.min < axis.max) {
                return Err(FieldError::new(format!("axes[{i}]"), "needs finite min < max"));
            }
            positive(&format!("axes[{i}].bins"), axis.bins)?;
        }
        let cells = self.axes.iter().try_fold(1u64, |acc, a| acc.checked_mul(a.bins as u64));
        if cells.is_none() {
            return Err(FieldError::new(
                "axes",
                "the product of the bins is too large to index the archive",
            ));
        }
        Ok(())
    }

    /// The thesis' grid: d_num over [0, W·H], d_elong and d_compact over [0, 1], 10 bins each.
    fn resolved(&self, cells: usize, _genes: Option<usize>) -> Option<OptimizerConfig> {
        if !self.axes.is_empty() {
            return None;
        }
        let axis = |descriptor, max| Axis {
            descriptor,
            min: 0.0,
            max,
            bins: 10,
        };
        let axes = vec![
            axis(Descriptor::Voxels, cells as f64),
            axis(Descriptor::Elongation, 1.0),
            axis(Descriptor::Compactness, 1.0),
        ];
        Some(OptimizerConfig::MapElites(MapElitesParams { axes, ..self.clone() }))
    }

    fn descriptors(&self) -> Vec<Descriptor> {
        self.axes.iter().map(|a| a.descriptor).collect()
    }

    fn build(&self, dimension: usize, senses: &[Sense], seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Ok(AnyOptimizer::MapElites(MapElites::new(
            self.config(senses),
            real_vector(dimension, self.init_range, self.mutation_sigma, [0.0, 1.0], 0.0),
            seed,
        )?))
    }

    fn over_operators(&self, senses: &[Sense]) -> Option<OperatorPlan> {
        Some(OperatorPlan::MapElites(self.config(senses)))
    }

    /// The archive (at most one elite per cell, and never more than the evaluation budget) plus
    /// two batches.
    fn held_genotypes(&self, _dimension: usize, budget: Option<u64>) -> u128 {
        let cells = self
            .axes
            .iter()
            .fold(1u128, |acc, a| acc.saturating_mul(a.bins as u128));
        let archive = budget.map_or(cells, |b| cells.min(b as u128));
        archive + 2 * self.map_elites.initial_population.max(self.map_elites.batch_size) as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.map_elites.batch_size
    }
}

/// The registry entry of `kind = "map-elites"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "map-elites",
    decode: |v| decode_flat::<MapElitesParams>(v).map(OptimizerConfig::MapElites),
};
