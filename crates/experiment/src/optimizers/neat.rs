//! `[optimizer] kind = "neat"`: NEAT (Stanley & Miikkulainen 2002, [`vsrlab_evolution::Neat`])
//! over network genomes. It evolves networks, not flat vectors or other kinds' operators, so only
//! genotype kinds whose genotypes are networks run it (`[genotype] kind = "cppn"`); the kind gives
//! the networks' inputs and outputs.

use super::check::{positive, probability};
use super::{decode_flat, AnyOptimizer, FieldError, OptimizerConfig, OptimizerEntry, OptimizerKind};
use serde::{Deserialize, Serialize};
use vsrlab_evolution::neat::Activation;
use vsrlab_evolution::{EvolutionError, Neat, NeatConfig, NeatSettings, Sense};

/// The `[optimizer]` table of NEAT: its settings (neat-python's defaults where the paper is
/// silent) and the output nodes' first activation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NeatParams {
    /// Population, speciation, reproduction and mutation settings, written flat.
    #[serde(flatten)]
    pub neat: NeatSettings,
    /// The output nodes' activation at first (sigmoid, EvoGym's CPPN-NEAT).
    #[serde(default = "sigmoid")]
    pub output_activation: Activation,
}

fn sigmoid() -> Activation {
    Activation::Sigmoid
}

impl NeatParams {
    /// The optimizer of a run over networks of `inputs` inputs and `outputs` outputs.
    pub fn build_networks(
        &self,
        inputs: usize,
        outputs: usize,
        senses: &[Sense],
        seed: u64,
    ) -> Result<Neat, EvolutionError> {
        let config = NeatConfig {
            settings: self.neat.clone(),
            inputs,
            outputs,
            output_activation: self.output_activation,
            sense: super::single(senses),
        };
        Neat::new(config, seed)
    }
}

impl OptimizerKind for NeatParams {
    fn name(&self) -> &'static str {
        "neat"
    }

    fn validate(&self) -> Result<(), FieldError> {
        let s = &self.neat;
        positive("population_size", s.population_size)?;
        if s.population_size < 2 {
            return Err(FieldError::new("population_size", "NEAT needs at least 2"));
        }
        let positive_number = |field: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(FieldError::new(field, format!("must be a finite number > 0, got {v}")))
            }
        };
        positive_number("compatibility_threshold", s.compatibility_threshold)?;
        for (field, v) in [
            ("excess_coefficient", s.excess_coefficient),
            ("disjoint_coefficient", s.disjoint_coefficient),
            ("weight_coefficient", s.weight_coefficient),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(FieldError::new(field, format!("must be a finite number ≥ 0, got {v}")));
            }
        }
        positive_number("survival_threshold", s.survival_threshold)?;
        probability("survival_threshold", s.survival_threshold)?;
        probability("crossover_rate", s.crossover_rate)?;
        let m = &s.mutation;
        for (field, p) in [
            ("mutation.weight_rate", m.weight_rate),
            ("mutation.weight_replace_rate", m.weight_replace_rate),
            ("mutation.add_connection", m.add_connection),
            ("mutation.add_node", m.add_node),
            ("mutation.delete_connection", m.delete_connection),
            ("mutation.delete_node", m.delete_node),
            ("mutation.activation_rate", m.activation_rate),
        ] {
            probability(field, p)?;
        }
        if !(m.weight_power.is_finite() && m.weight_power >= 0.0) {
            return Err(FieldError::new(
                "mutation.weight_power",
                format!("must be a finite number ≥ 0, got {}", m.weight_power),
            ));
        }
        if m.activations.is_empty() {
            return Err(FieldError::new("mutation.activations", "give at least one activation"));
        }
        Ok(())
    }

    fn flat_vectors(&self) -> bool {
        false
    }

    /// NEAT evolves networks: a flat-vector experiment cannot run it (validation says so first).
    fn build(&self, _dimension: usize, _senses: &[Sense], _seed: u64) -> Result<AnyOptimizer, EvolutionError> {
        Err(EvolutionError::InvalidConfig(
            "NEAT evolves network genomes: use it with [genotype] kind = \"cppn\"".into(),
        ))
    }

    fn held_genotypes(&self, _dimension: usize, _budget: Option<u64>) -> u128 {
        2 * self.neat.population_size as u128
    }

    fn batch_size(&self, _dimension: usize) -> usize {
        self.neat.population_size
    }
}

/// The registry entry of `kind = "neat"`.
pub(crate) const ENTRY: OptimizerEntry = OptimizerEntry {
    name: "neat",
    decode: |v| decode_flat::<NeatParams>(v).map(OptimizerConfig::Neat),
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optimizers::decode_table;

    fn table(text: &str) -> toml::Table {
        text.parse().unwrap()
    }

    #[test]
    fn the_table_reads_neat_settings_and_names_bad_fields() {
        let config = decode_table(table(
            "kind = \"neat\"\npopulation_size = 25\nweight_coefficient = 0.6\nmutation = { add_node = 0.2, activations = [\"sigmoid\"] }",
        ))
        .unwrap();
        let OptimizerConfig::Neat(p) = &config else {
            panic!("{config:?}")
        };
        assert_eq!(
            (
                p.neat.population_size,
                p.neat.weight_coefficient,
                p.neat.mutation.add_node
            ),
            (25, 0.6, 0.2)
        );
        assert_eq!(p.neat.mutation.activations, [Activation::Sigmoid]);
        assert!(config.kind().validate().is_ok() && !config.kind().flat_vectors());
        let e = decode_table(table("kind = \"neat\"\npopulaton_size = 25")).unwrap_err();
        assert_eq!(e.path, "populaton_size", "{e}");
        let bad = decode_table(table("kind = \"neat\"\nmutation = { add_node = 2.0 }")).unwrap();
        assert_eq!(bad.kind().validate().unwrap_err().path, "mutation.add_node");
        let none = decode_table(table("kind = \"neat\"\nmutation = { activations = [] }")).unwrap();
        assert_eq!(none.kind().validate().unwrap_err().path, "mutation.activations");
        assert!(config.kind().build(3, &[Sense::Maximize], 0).is_err());
    }
}
