//! Many genotypes of one experiment evaluated in one call: the entry point of optimisers that live
//! outside vsrlab (`vsrlab evaluate`, Python's `evaluate_batch`).
//!
//! A [`BatchEvaluator`] is built from an experiment file's text, so every process that reads the
//! same text (a worker on another machine included) evaluates the same way; each evaluation is
//! the runner's, [`RobotEvaluator::evaluate`] with the candidate seed given, so fitness values
//! are bit-identical to those of `vsrlab run` for the same genotype and seed, whatever the number
//! of threads or machines.

use crate::config::{self, Experiment};
use crate::evaluator::{Evaluated, Evaluator, RobotEvaluator};

/// Evaluates flat genotypes (the rows of a matrix) on an experiment's robot and task.
#[derive(Debug, Clone)]
pub struct BatchEvaluator {
    experiment: Experiment,
    evaluator: RobotEvaluator,
    genes: usize,
}

/// Why a batch could not be evaluated; the message names the argument or field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct BatchError(pub String);

impl BatchEvaluator {
    /// The evaluator of an experiment file's text (`origin` names it in error messages).
    pub fn from_text(text: &str, origin: &str) -> Result<BatchEvaluator, BatchError> {
        let experiment = config::parse(text, origin).map_err(|e| BatchError(e.to_string()))?;
        BatchEvaluator::new(experiment)
    }

    /// The evaluator of a parsed experiment; refuses graph genotypes, which are not rows of
    /// numbers.
    pub fn new(experiment: Experiment) -> Result<BatchEvaluator, BatchError> {
        let kind = experiment.genotype_kind();
        if !kind.rows() {
            return Err(BatchError(format!(
                "genotype: batch evaluation takes flat genotypes (rows of numbers); this experiment's \
                 genotypes are of kind {}",
                kind.name()
            )));
        }
        let evaluator = RobotEvaluator::new(&experiment).map_err(|e| BatchError(e.to_string()))?;
        let genes = evaluator.genotype_length();
        Ok(BatchEvaluator {
            experiment,
            evaluator,
            genes,
        })
    }

    /// Genes per genotype (the width of the matrix [`BatchEvaluator::fitness`] takes).
    pub fn genotype_length(&self) -> usize {
        self.genes
    }

    /// The experiment (its task, representation, optimizer).
    pub fn experiment(&self) -> &Experiment {
        &self.experiment
    }

    /// The runner's evaluator.
    pub fn evaluator(&self) -> &RobotEvaluator {
        &self.evaluator
    }

    /// Checks a row-major matrix of `genes` values per row against `seeds`, one per row.
    fn check(&self, genes: &[f64], seeds: &[u64]) -> Result<(), BatchError> {
        let width = self.genes;
        if width == 0 {
            return Err(BatchError("genotypes: this experiment has no genes".into()));
        }
        if !genes.len().is_multiple_of(width) {
            return Err(BatchError(format!(
                "genotypes: {} values are not rows of {width} genes",
                genes.len()
            )));
        }
        let rows = genes.len() / width;
        if seeds.len() != rows {
            return Err(BatchError(format!(
                "seeds: {} seeds for {rows} genotypes (one per genotype)",
                seeds.len()
            )));
        }
        if let Some(i) = genes.iter().position(|g| !g.is_finite()) {
            return Err(BatchError(format!(
                "genotypes: row {}, gene {} is {} (genes must be finite)",
                i / width,
                i % width,
                genes[i]
            )));
        }
        Ok(())
    }

    /// Every evaluation of a row-major matrix of genotypes (one seed per row), on the current
    /// rayon pool, in row order.
    pub fn evaluate(&self, genes: &[f64], seeds: &[u64]) -> Result<Vec<Evaluated>, BatchError> {
        self.check(genes, seeds)?;
        let rows: Vec<Vec<f64>> = genes.chunks(self.genes).map(<[f64]>::to_vec).collect();
        let refs: Vec<&Vec<f64>> = rows.iter().collect();
        self.evaluator
            .evaluate_batch(&refs, seeds)
            .map_err(|e| BatchError(e.to_string()))
    }

    /// The first fitness value of every row (NaN for an evaluation that failed), on the current
    /// rayon pool: [`BatchEvaluator::evaluate`]'s, without the rest.
    pub fn fitness(&self, genes: &[f64], seeds: &[u64]) -> Result<Vec<f64>, BatchError> {
        Ok(self.evaluate(genes, seeds)?.iter().map(Evaluated::fitness).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CONFIG: &str = r#"
name = "batch"
[representation]
body = "biped-4x3"
sensors = "uniform-vxy+a+t-0"
brain = { kind = "distributed-mlp", layout = "homogeneous", signals = 1, hidden = [] }
[task]
terrain = "flat"
duration = 2.0
fitness = "velocity"
[optimizer]
kind = "ga"
[stop]
evaluations = 100
"#;

    #[test]
    fn rows_of_the_wrong_width_nan_genes_and_missing_seeds_are_refused_by_name() {
        let b = BatchEvaluator::from_text(CONFIG, "test.toml").unwrap();
        let n = b.genotype_length();
        assert!(n > 0);
        let err = b.fitness(&vec![0.0; n + 1], &[0]).unwrap_err().0;
        assert!(
            err.starts_with("genotypes:") && err.contains(&format!("rows of {n} genes")),
            "{err}"
        );
        let err = b.fitness(&vec![0.0; 2 * n], &[0]).unwrap_err().0;
        assert!(err.starts_with("seeds: 1 seeds for 2 genotypes"), "{err}");
        let mut genes = vec![0.0; 2 * n];
        genes[n + 1] = f64::NAN;
        let err = b.fitness(&genes, &[0, 1]).unwrap_err().0;
        assert!(err.contains("row 1, gene 1 is NaN"), "{err}");
    }

    #[test]
    fn fitness_is_the_runners_evaluation_in_row_order_whatever_the_threads() {
        let b = BatchEvaluator::from_text(CONFIG, "test.toml").unwrap();
        let n = b.genotype_length();
        let genes: Vec<f64> = (0..5 * n).map(|i| ((i * 7919) % 200) as f64 / 100.0 - 1.0).collect();
        let seeds = [3, 1, 4, 1, 5];
        let one = rayon::ThreadPoolBuilder::new().num_threads(1).build().unwrap();
        let serial = one.install(|| b.fitness(&genes, &seeds)).unwrap();
        let parallel = b.fitness(&genes, &seeds).unwrap();
        assert_eq!(serial, parallel);
        for (row, &f) in serial.iter().enumerate() {
            let direct = b
                .evaluator()
                .evaluate(&genes[row * n..(row + 1) * n].to_vec(), seeds[row]);
            assert_eq!(direct.fitness(), f);
        }
        let full = b.evaluate(&genes, &seeds).unwrap();
        assert_eq!(full.iter().map(Evaluated::fitness).collect::<Vec<_>>(), serial);
        assert!(
            serial.iter().any(|&f| f != serial[0]),
            "different genotypes, different fitness"
        );
    }

    #[test]
    fn evaluations_survive_a_json_round_trip_non_finite_values_included() {
        let b = BatchEvaluator::from_text(CONFIG, "test.toml").unwrap();
        let n = b.genotype_length();
        let mut e = b.evaluate(&vec![0.5; n], &[0]).unwrap();
        e[0].objectives.push(f64::NAN);
        e[0].descriptor.push(f64::NEG_INFINITY);
        let text = serde_json::to_string(&e).unwrap();
        let back: Vec<Evaluated> = serde_json::from_str(&text).unwrap();
        assert_eq!(back[0].objectives[0], e[0].objectives[0]);
        assert!(back[0].objectives[1].is_nan());
        assert_eq!(back[0].descriptor, vec![f64::NEG_INFINITY]);
        assert_eq!(back[0].record, e[0].record);
    }

    #[test]
    fn graph_genotypes_are_not_batched() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../experiments/ch4.1/reduced.toml");
        let experiment = config::load_all(path.as_ref()).unwrap().remove(0);
        assert!(experiment.genotype.is_some());
        let err = BatchEvaluator::new(experiment).unwrap_err().0;
        assert!(err.starts_with("genotype:") && err.contains("of kind graph"), "{err}");
    }
}
